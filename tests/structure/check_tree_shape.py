#!/usr/bin/env python3
"""The shape of the tree, read from its includes and folders: the core reads no files (sans-I/O:
callers hand it text and bytes); the analyzer's and the plugin's folders are floors, each
including only the floors below it (ANALYZER_FLOORS, PLUGIN_FLOORS); and the tests mirror the products: tests/<product>/ for
protocols, pcap, analyzer, dissector and packaging (tests/package), the core's in
tests/protocols/<family>/ for the families of protocols/src, beside only the shared
tests/support, tests/corpus and tests/structure. How many files a folder holds is no rule.

    check_tree_shape.py REPOSITORY_ROOT

Prints one line per breach and exits 1 when there is one.
"""
import os
import re
import sys

# Headers that open files, streams or descriptors. The core parses what it is handed.
FILE_IO = {"fstream", "filesystem", "cstdio", "stdio.h", "iostream", "fcntl.h", "unistd.h",
           "sys/stat.h", "sys/types.h"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')


def sources(folder):
    return [n for n in os.listdir(folder) if n.endswith((".cpp", ".h"))]


# The analyzer's folders from the ground up: text helpers, the report, the event port and its
# writers, the terminal line, the HTML page, the comparison of two audits (pvtap diff), the
# broker client and what pvtap publishes on it, serial devices, the carriers (a gateway's TCP
# flows: bare RTU, Modbus/TCP, logger sticks), the buses, the run's assembly of outputs, the
# sources that feed a run, the commands, Wireshark's extcap calls. A folder may include only
# those before it, so that nothing reaches up and no two folders need each other.
ANALYZER_FLOORS = ("formatting", "report", "events", "writers", "console", "html", "diff", "broker",
                   "mqtt", "serial", "carriers", "pipeline", "run", "sources", "logic", "cli", "extcap")


# The plugin's folders from the ground up: the Wireshark API shims, the per-frame plan (plain
# C++), the protocol handle every part fills or reads (field ids, subtrees, experts,
# preferences), the preferences and maps, the fields and expert infos, the tree, the columns and
# statistics, the streams of a bus, the carriers (Modbus/TCP, Solarman V5), and registration
# with the plugin's entry point on top.
PLUGIN_FLOORS = ("wireshark_api", "plan", "protocol", "settings", "fields", "tree", "columns",
                 "statistics", "stream", "carriers", "registration")


def floor_breaches(repo, product, floors):
    """Includes that reach a floor above their own, and folders missing from the floors."""
    src = os.path.join(repo, product, "src")
    breaches = []
    for folder in sorted(os.listdir(src)):
        if not os.path.isdir(os.path.join(src, folder)):
            continue
        if folder not in floors:
            breaches.append("%s/src/%s: a folder without a floor (add it to the floors of "
                            "check_tree_shape.py)" % (product, folder))
            continue
        floor = floors.index(folder)
        for name in sorted(sources(os.path.join(src, folder))):
            path = os.path.join(src, folder, name)
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    match = INCLUDE.match(line)
                    target = match.group(1).split("/")[0] if match else ""
                    if target in floors and floors.index(target) > floor:
                        breaches.append("%s:%d: %s/ includes %s, a floor above it"
                                        % (os.path.relpath(path, repo), number, folder,
                                           match.group(1)))
    return breaches


# Folders of tests/: one per product (package: packaging/), and what they all share.
TEST_FOLDERS = {"protocols", "pcap", "analyzer", "dissector", "package",
                "support", "corpus", "structure"}


def unmirrored_tests(repo):
    """Test folders that mirror no product, and core test folders that mirror no family."""
    breaches = []
    tests = os.path.join(repo, "tests")
    for name in sorted(os.listdir(tests)):
        if os.path.isdir(os.path.join(tests, name)) and name not in TEST_FOLDERS:
            breaches.append("tests/%s: mirrors no product (tests/<product>/: %s)"
                            % (name, ", ".join(sorted(TEST_FOLDERS))))
    families = set(os.listdir(os.path.join(repo, "protocols", "src")))
    core_tests = os.path.join(tests, "protocols")
    for name in sorted(os.listdir(core_tests)):
        if os.path.isdir(os.path.join(core_tests, name)) and name not in families:
            breaches.append("tests/protocols/%s: no such family in protocols/src" % name)
    return breaches


def main():
    core = os.path.join(sys.argv[1], "protocols")
    breaches = (floor_breaches(sys.argv[1], "analyzer", ANALYZER_FLOORS) +
                floor_breaches(sys.argv[1], "dissector", PLUGIN_FLOORS) +
                unmirrored_tests(sys.argv[1]))
    for root, _, _ in os.walk(core):
        names = sources(root)
        for name in names:
            path = os.path.join(root, name)
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    match = INCLUDE.match(line)
                    if match and match.group(1) in FILE_IO:
                        breaches.append("%s:%d: includes <%s>, file I/O in the core"
                                        % (os.path.relpath(path, sys.argv[1]), number,
                                           match.group(1)))
    for breach in breaches:
        print(breach)
    print("tree shape: %d breach(es)" % len(breaches))
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
