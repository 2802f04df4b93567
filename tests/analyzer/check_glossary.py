#!/usr/bin/env python3
"""One vocabulary (issue 38, item 2): `pvtap glossary` is the one list of pvtap's terms; the
README's glossary section is its markdown output, every jsonl key it names is in a real
summary, and the HTML page and the text report use its words (the page's headings and tiles
carry its meanings as tooltips; both station tables give latency p50 / p95 / max).

Usage: check_glossary.py PVTAP README CAPTURE
"""
import html
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 120


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=RUN_GUARD_S)


def has_key(summary, path):
    """Whether the dotted key (with [] for 'each element') is in the summary."""
    nodes = [summary]
    for part in path.split("."):
        name, each = (part[:-2], True) if part.endswith("[]") else (part, False)
        found = []
        for node in nodes:
            if isinstance(node, dict) and name in node:
                value = node[name]
                found.extend(value if each and isinstance(value, list) else [value])
        nodes = found
    return bool(nodes)


def readme_section(readme):
    text = open(readme, encoding="utf-8").read()
    match = re.search(r"^## Glossary\n(.*?)(?=^## )", text, re.MULTILINE | re.DOTALL)
    if match is None:
        return None
    return "\n".join(line for line in match.group(1).splitlines() if line.startswith("|")) + "\n"


def check_html(checks, pvtap, capture, terms):
    with tempfile.TemporaryDirectory(prefix="pvtap-glossary-") as work:
        page = os.path.join(work, "report.html")
        result = run(pvtap, "audit", "--summary-only", "--html", page, capture)
        checks.equal("exit status of the audit with --html", result.returncode, 0)
        text = open(page, encoding="utf-8").read()
    meanings = {t["meaning"] for t in terms}
    titled = [html.unescape(m) for m in re.findall(r'<th title="([^"]*)"', text)]
    checks.true(f"the page's table headings carry glossary meanings ({len(titled)})",
                len(titled) >= 9 and all(m in meanings for m in titled))
    tiles = re.findall(r'<a class="tile[^"]*" title="([^"]*)"[^>]*data-key="([^"]*)"', text)
    by_key = {t["key"]: t["meaning"] for t in terms if t["key"]}
    checks.true(f"every health tile's tooltip is its key's meaning ({len(tiles)} tiles)",
                len(tiles) >= 5 and all(by_key.get(k) == html.unescape(m) for m, k in tiles))
    headings = re.search(r'<table class="stations"><tr>(.*?)</tr>', text)
    words = re.findall(r">([^<]+)</th>", headings.group(1)) if headings else []
    checks.true(f"the page's station table: {words}",
                words[:8] == ["station", "requests", "responses", "bad checks", "timeouts",
                              "exceptions", "latency p50 ms", "p95"])


def main():
    pvtap, readme, capture = sys.argv[1:4]
    checks = Checks()
    listed = run(pvtap, "glossary", "--format", "jsonl")
    checks.equal("exit status of pvtap glossary", listed.returncode, 0)
    terms = [json.loads(line) for line in listed.stdout.splitlines()]
    names = [t["term"] for t in terms]
    checks.true(f"terms are many and unique ({len(names)})",
                len(names) >= 20 and len(set(names)) == len(names))
    checks.true("every meaning is one line", all(t["meaning"] and "\n" not in t["meaning"]
                                                  for t in terms))
    markdown = run(pvtap, "glossary", "--format", "markdown").stdout
    section = readme_section(readme)
    checks.true("README.md has a Glossary section, the output of pvtap glossary --format "
                "markdown (paste it there when the glossary changes)", section == markdown)
    summary = json.loads(run(pvtap, "audit", "--summary-only", "--format", "jsonl",
                             capture).stdout.splitlines()[-1])
    for t in terms:
        if t["key"]:
            checks.true(f"{t['term']}: key {t['key']} is in the jsonl summary",
                        has_key(summary, t["key"]))
    text = run(pvtap, "audit", "--summary-only", capture).stdout
    checks.true("the text report's station table gives latency p50 / p95 / max, as the page",
                "latency ms p50 / p95 / max" in text)
    check_html(checks, pvtap, capture, terms)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
