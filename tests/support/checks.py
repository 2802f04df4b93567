"""Checks: collects failed checks instead of stopping at the first, for the check_* scripts."""


class Checks:
    def __init__(self):
        self.failures = []

    def equal(self, what, actual, expected):
        if actual != expected:
            self.failures.append(f"{what}: got {actual!r}, expected {expected!r}")

    def true(self, what, condition):
        if not condition:
            self.failures.append(what)

    def finish(self):
        """Prints the failures (or that all held); the exit status for them."""
        for failure in self.failures:
            print("FAIL:", failure)
        print("all checks hold" if not self.failures else f"{len(self.failures)} failed")
        return 1 if self.failures else 0
