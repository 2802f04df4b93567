"""The man pages built by help2man (packaging/CMakeLists.txt), rendered by man: each names its
command and version, and every option of the command's --help is in its OPTIONS section.

Usage: check_man_pages.py PVTAP MAN_DIR
"""
import os
import re
import subprocess
import sys

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

PAGES = {"pvtap": [], "pvtap-audit": ["audit"], "pvtap-sniff": ["sniff"]}


def help_options(pvtap, subcommand):
    """The long options of `pvtap [SUBCOMMAND] --help`, from its option lines."""
    text = subprocess.run([pvtap, *subcommand, "--help"], capture_output=True, text=True,
                          check=True, timeout=RUN_GUARD_S).stdout
    return sorted(set(re.findall(r"^ {2,12}(?:-[a-z], *)?(--[a-z][a-z-]*)", text, re.MULTILINE)))


def rendered(path):
    """The page as man shows it, wide enough that no option is broken across lines."""
    env = dict(os.environ, MANWIDTH="1000", LC_ALL="C.UTF-8", MAN_KEEP_FORMATTING="")
    result = subprocess.run(["man", "-l", path], capture_output=True, text=True, env=env,
                            check=True, timeout=RUN_GUARD_S)
    # Drop overstrike formatting in case the pager kept it, and Unicode hyphens.
    return re.sub(r".\x08", "", result.stdout).replace("\u2010", "-").replace("\u2212", "-")


def section(text, name):
    match = re.search(r"^%s\n(.*?)(?=^[A-Z][A-Z ]+\n|\Z)" % re.escape(name), text,
                      re.MULTILINE | re.DOTALL)
    return match.group(1) if match else ""


def main():
    pvtap, man_dir = sys.argv[1], sys.argv[2]
    version = subprocess.run([pvtap, "--version"], capture_output=True, text=True,
                             check=True, timeout=RUN_GUARD_S).stdout.split()[1]
    failures = []
    for page, subcommand in PAGES.items():
        text = rendered(os.path.join(man_dir, page + ".1.gz"))
        options = section(text, "OPTIONS")
        if not text.startswith(page.upper() + "(1)"):
            failures.append("%s: no %s(1) header" % (page, page.upper()))
        if not re.search(r"^NAME\n\s+%s - \S" % re.escape(page), text, re.MULTILINE):
            failures.append("%s: NAME does not name %s" % (page, page))
        if "%s %s" % (page, version) not in text:
            failures.append("%s: no version %s in the footer" % (page, version))
        wanted = help_options(pvtap, subcommand)
        if len(wanted) < 2:
            failures.append("%s: too few options found in --help: %s" % (page, wanted))
        for option in wanted:
            if not re.search(r"^\s+(-[a-z],\s*)?%s\b" % re.escape(option), options, re.MULTILINE):
                failures.append("%s: %s of --help is not an entry of OPTIONS" % (page, option))
        print("%s(1): %d options checked" % (page, len(wanted)))
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
