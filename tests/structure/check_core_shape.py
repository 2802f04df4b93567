#!/usr/bin/env python3
"""The shape of the core, read from its includes and folders: it reads no files (sans-I/O:
callers hand it text and bytes) and no folder of it holds more than 20 source files.

    check_core_shape.py REPOSITORY_ROOT

Prints one line per breach and exits 1 when there is one.
"""
import os
import re
import sys

# Headers that open files, streams or descriptors. The core parses what it is handed.
FILE_IO = {"fstream", "filesystem", "cstdio", "stdio.h", "iostream", "fcntl.h", "unistd.h",
           "sys/stat.h", "sys/types.h"}
MAX_SOURCES = 20
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')


def sources(folder):
    return [n for n in os.listdir(folder) if n.endswith((".cpp", ".h"))]


def main():
    core = os.path.join(sys.argv[1], "protocols")
    breaches = []
    for root, _, _ in os.walk(core):
        names = sources(root)
        if len(names) > MAX_SOURCES:
            breaches.append("%s: %d source files (at most %d)"
                            % (os.path.relpath(root, sys.argv[1]), len(names), MAX_SOURCES))
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
    print("core shape: %d breach(es)" % len(breaches))
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
