"""The man pages built by help2man (packaging/CMakeLists.txt), rendered by man: each names its
command and version, every option of the command's --help is in its OPTIONS section, every
example of --help is in EXAMPLES whole (a command continued on a second line included), and
every kind of input the code tells apart (capture's FileFormat) is named in audit's --help and
its page.

Usage: check_man_pages.py PVTAP MAN_DIR FILE_FORMAT_HEADER
"""
import os
import re
import subprocess
import sys

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

PAGES = {"pvtap": [], "pvtap-audit": ["audit"], "pvtap-sniff": ["sniff"],
         "pvtap-diff": ["diff"]}


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


# How help and man page name each FileFormat the code reads (Text: a logic CSV is text; Zip: a
# sigrok session is a zip). A format without an entry fails the test until it is described.
INPUT_WORDS = {"Pcap": "pcap", "Pcapng": "pcapng", "Zip": "sigrok session", "Vcd": "VCD",
               "Text": "logic CSV"}
# Not inputs: what a file is called when it is none of them.
NOT_INPUTS = {"Unknown", "Unreadable"}


def help_text(pvtap, subcommand):
    return subprocess.run([pvtap, *subcommand, "--help"], capture_output=True, text=True,
                          check=True, timeout=RUN_GUARD_S).stdout


def help_examples(text):
    """The example commands of --help, a continuation line joined to its command."""
    block = re.search(r"^Examples:\n(.*?)(?:\n\n|\Z)", text, re.MULTILINE | re.DOTALL)
    examples = []
    for line in (block.group(1).splitlines() if block else []):
        if line.startswith("      ") and examples:
            examples[-1] += " " + line.strip()
        elif line.strip():
            examples.append(line.strip())
    return examples


def squeezed(text):
    return re.sub(r"\s+", " ", text)


def check_examples(page, text, help, failures):
    """Each example of --help is in EXAMPLES, whole and in one paragraph."""
    examples = help_examples(help)
    paragraphs = [squeezed(p) for p in re.split(r"\n\s*\n", section(text, "EXAMPLES"))]
    for example in examples:
        if not any(squeezed(example) in paragraph for paragraph in paragraphs):
            failures.append("%s: example not whole in EXAMPLES: %s" % (page, example))
    return len(examples)


def check_inputs(header, audit_help, audit_page, failures):
    formats = re.search(r"enum class FileFormat \{([^}]*)\}", open(header).read()).group(1)
    for name in (f.strip() for f in formats.split(",") if f.strip()):
        if name in NOT_INPUTS:
            continue
        word = INPUT_WORDS.get(name)
        if word is None:
            failures.append("FileFormat::%s has no words in this test: describe it in --help"
                            % name)
            continue
        for where, text in (("audit --help", audit_help), ("pvtap-audit(1)", audit_page)):
            if word.lower() not in squeezed(text).lower():
                failures.append("%s does not name the input %s (%s)" % (where, word, name))
    for where, text in (("audit --help", audit_help), ("pvtap-audit(1)", audit_page)):
        if "--raw" not in text or "plain dump" not in squeezed(text):
            failures.append("%s does not name the plain dump (--raw)" % where)


def main():
    pvtap, man_dir, header = sys.argv[1], sys.argv[2], sys.argv[3]
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
        help = help_text(pvtap, subcommand)
        examples = check_examples(page, text, help, failures)
        if page == "pvtap-audit":
            check_inputs(header, help, text, failures)
        print("%s(1): %d options and %d examples checked" % (page, len(wanted), examples))
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
