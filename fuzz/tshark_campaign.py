#!/usr/bin/env python3
"""The plugin and pvtap audit under sanitizers on mutated captures (issue 12, point 2).

For each variant (editcap -E with an error rate from 0.01 to 0.1, sometimes a random snap
length, sometimes pcapng) of the captures given, runs

  tshark -nVxr VARIANT     with the ASan+UBSan pvtap.so loaded (LD_PRELOAD of the ASan
                           runtime, WIRESHARK_ABORT_ON_DISSECTOR_BUG=1), as user 65534 when
                           run as root (tshark as root ignores personal plugin folders);
  pvtap audit VARIANT      the ASan+UBSan pvtap;

and counts crashes, sanitizer reports and dissector bugs: ours (pvtap.so, invascii, invrtu)
apart from Wireshark's own. Variants with a finding are kept in OUT/findings/. Exit status 1
when there is a finding of ours, else 0.

tshark spends most of a small variant starting up (1.7 s of 2 s with the ASan runtime), so
`--batch N` appends N variants of one capture into one file (mergecap -a) and runs tshark
once over it: each variant is dissected whole, after the ones before it, whose conversations
and reassembly state it meets (a harder input than the variant alone, not the same one). A
batch with any finding is run again one variant at a time, so that every finding names its
variant and no variant goes undissected behind an abort; a capture whose batches keep finding
something (Wireshark's own exported-PDU assertion aborts one variant in three of a `.pdu`
capture) gets batches half as large, down to one, and twice as large again after a clean one.
"""

import argparse
import glob
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tests", "dissector"))
from tshark_runner import plugin_subdir  # noqa: E402  (the personal folder of tshark's series)
NOBODY = 65534
OUR_PROTOCOLS = ("invascii", "invrtu", "pvtap")
OUR_FRAMES = ("pvtap.so", "/dissector/src/", "/protocols/src/", "pvtap::")
SANITIZER = re.compile(r"ERROR: AddressSanitizer|runtime error:|ERROR: LeakSanitizer")
DISSECTOR_BUG = re.compile(r"[Dd]issector bug, protocol ([A-Za-z0-9_.-]+)")


def asan_runtime():
    """The ASan runtime of the compiler that built the plugin (gcc's libasan)."""
    path = subprocess.run(["gcc", "-print-file-name=libasan.so"], capture_output=True,
                          text=True).stdout.strip()
    return os.path.realpath(path) if os.path.isfile(path) else None


class Home:
    """A temporary HOME with a fresh copy of the plugin, readable by the tshark user."""

    def __init__(self, plugin):
        self.dir = tempfile.mkdtemp(prefix="pvtap-campaign-")
        os.chmod(self.dir, 0o755)
        plugins = os.path.join(self.dir, plugin_subdir())
        os.makedirs(plugins)
        shutil.copy(plugin, os.path.join(plugins, "pvtap.so"))
        self.variants = os.path.join(self.dir, "variants")
        os.makedirs(self.variants)
        self.hand_over()

    def hand_over(self):
        if os.geteuid() != 0:
            return
        for root, dirs, files in os.walk(self.dir):
            for name in [root] + [os.path.join(root, n) for n in dirs + files]:
                os.chown(name, NOBODY, NOBODY)

    def tshark(self, args, runtime):
        env = ["HOME=" + self.dir, "PATH=/usr/sbin:/usr/bin:/sbin:/bin", "LC_ALL=C.UTF-8",
               "WIRESHARK_ABORT_ON_DISSECTOR_BUG=1",
               "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:symbolize=1",
               "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1"]
        if runtime:
            env.append("LD_PRELOAD=" + runtime)
        command = ["env", "-i"] + env + ["tshark"] + args
        if os.geteuid() == 0:
            command = ["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY,
                       "--clear-groups"] + command
        return command

    def close(self):
        shutil.rmtree(self.dir, ignore_errors=True)


def plugin_loaded(home, runtime):
    """Whether tshark decodes a sample with the plugin. (`tshark -G plugins` hangs with the
    ASan runtime preloaded, so the check reads a capture instead.)"""
    sample = os.path.join(REPO, "captures", "samples", "gsl-clean.pdu.pcap")
    copy = os.path.join(home.variants, "check.pcap")
    shutil.copy(sample, copy)
    home.hand_over()
    done = subprocess.run(home.tshark(["-nVr", copy, "-c", "5"], runtime), capture_output=True,
                          text=True, errors="replace", timeout=120)
    os.remove(copy)
    if "invrtu" not in done.stdout:
        print("campaign: tshark did not load the plugin:\n" + done.stderr[-4000:],
              file=sys.stderr)
        return False
    return True


def make_variant(rng, source, out, index):
    """An editcap -E variant of `source`; returns its path and how it was made."""
    rate = round(rng.uniform(0.01, 0.1), 3)
    args = ["editcap", "--seed", str(rng.randrange(1 << 31)), "-E", str(rate)]
    if rng.random() < 0.3:
        args += ["-s", str(rng.randrange(16, 200))]
    pcapng = rng.random() < 0.3
    args += ["-F", "pcapng" if pcapng else "pcap"]
    path = os.path.join(out, "v%05d.%s" % (index, "pcapng" if pcapng else "pcap"))
    done = subprocess.run(args + [source, path], capture_output=True, text=True)
    if done.returncode != 0:
        return None, " ".join(args[1:])
    os.chmod(path, 0o644)
    if os.geteuid() == 0:
        os.chown(path, NOBODY, NOBODY)
    return path, " ".join(args[1:])


def judge(result, kind):
    """('', '') when fine, else (finding kind, whose: 'ours' or 'wireshark')."""
    text = result.stderr
    if isinstance(result, Hung):
        # A hang of tshark is counted as ours: the plugin is the part under test.
        return "hang", "ours"
    bug = DISSECTOR_BUG.search(text)
    if bug:
        return "dissector-bug", "ours" if bug.group(1) in OUR_PROTOCOLS else "wireshark"
    crashed = result.returncode < 0 or result.returncode >= 128
    if SANITIZER.search(text) or crashed:
        ours = kind == "audit" or any(f in text for f in OUR_FRAMES)
        return "sanitizer" if SANITIZER.search(text) else "crash", \
            "ours" if ours else "wireshark"
    return "", ""


class Hung:
    """The result of a run that did not end in time (a finding: a hang)."""
    returncode = -9
    stderr = "timed out after %d s" % 300


def run_bounded(command, env, cwd=None, timeout=300):
    # What tshark prints (-V -x of every packet) is not judged: only stderr is kept.
    try:
        return subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True, errors="replace", env=env, cwd=cwd, timeout=timeout)
    except subprocess.TimeoutExpired:
        return Hung()


def run_one(home, runtime, pvtap, variant, tshark=True):
    findings = []
    if tshark:
        # In its HOME: tshark reads some files from its working folder (IOR.txt).
        result = run_bounded(home.tshark(["-nVxr", variant], runtime), None, home.dir)
        kind, whose = judge(result, "tshark")
        if kind:
            findings.append(("tshark", kind, whose, result.stderr))
    if pvtap:
        env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1:abort_on_error=1",
                   UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1")
        audit = run_bounded([pvtap, "audit", "--format", "jsonl", variant], env)
        kind, whose = judge(audit, "audit")
        if not kind and audit.returncode not in (0, 1, 2):
            kind, whose = "exit-%d" % audit.returncode, "ours"
        if kind:
            findings.append(("audit", kind, whose, audit.stderr))
    return findings


def run_batch(home, runtime, pvtap, variants):
    """Findings per variant: [(variant, findings)]. One tshark over all of them first."""
    if len(variants) > 1:
        merged = os.path.join(home.variants, "batch-" + os.path.basename(variants[0]) + ".pcapng")
        made = subprocess.run(["mergecap", "-a", "-F", "pcapng", "-w", merged] + variants,
                              capture_output=True, text=True)
        if made.returncode == 0:
            if os.geteuid() == 0:
                os.chown(merged, NOBODY, NOBODY)
            tshark = run_bounded(home.tshark(["-nVxr", merged], runtime), None, home.dir,
                                 timeout=300 + 20 * len(variants))
            os.remove(merged)
            if not judge(tshark, "tshark")[0]:
                return [(v, run_one(home, runtime, pvtap, v, tshark=False)) for v in variants]
        elif os.path.exists(merged):
            os.remove(merged)
    return [(v, run_one(home, runtime, pvtap, v)) for v in variants]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--plugin", required=True, help="the ASan+UBSan pvtap.so")
    p.add_argument("--pvtap", help="the ASan+UBSan pvtap (audit); left out: tshark only")
    p.add_argument("--variants", type=int, default=50, help="variants in all")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--jobs", type=int, default=1)
    p.add_argument("--batch", type=int, default=1,
                   help="variants of one capture per tshark run (see above; default 1)")
    p.add_argument("--out", default="campaign", help="where findings are kept")
    p.add_argument("--max-seconds", type=float, default=0,
                   help="start no new variant after this many seconds (0: no limit)")
    p.add_argument("captures", nargs="+", help="captures or folders of captures")
    a = p.parse_args()

    sources = []
    for c in a.captures:
        if os.path.isdir(c):
            sources += sorted(glob.glob(os.path.join(c, "*.pcap")) +
                              glob.glob(os.path.join(c, "*.pcapng")))
        else:
            sources.append(c)
    sources = [s for s in sources if os.path.getsize(s) > 24]
    runtime = asan_runtime()
    rng = random.Random(a.seed)
    home = Home(a.plugin)
    if not plugin_loaded(home, runtime):
        home.close()
        return 2
    os.makedirs(os.path.join(a.out, "findings"), exist_ok=True)
    counts = {}
    per_source = dict.fromkeys(sources, 0)
    deadline = time.monotonic() + a.max_seconds if a.max_seconds > 0 else None
    index = 0
    in_flight = dict.fromkeys(sources, 0)
    batch_size = dict.fromkeys(sources, a.batch)
    with ThreadPoolExecutor(max_workers=a.jobs) as pool:
        # Variants are made a batch at a time (same order, same seeds as all at once), so a
        # long campaign neither fills the disk first nor runs past its time.
        while index < a.variants and not (deadline and time.monotonic() > deadline):
            jobs = []
            for _ in range(a.jobs):
                if index >= a.variants:
                    break
                # A batch's variants come from one capture: the one with the fewest variants yet,
                # so that the captures stay even whatever their batch sizes.
                source = min(sources, key=lambda s: per_source[s] + in_flight[s])
                made = []
                for _ in range(min(batch_size[source], a.variants - index)):
                    variant, how = make_variant(rng, source, home.variants, index)
                    index += 1
                    if variant:
                        made.append((variant, how))
                in_flight[source] += len(made)
                if made:
                    jobs.append((source, made))
            batches = pool.map(lambda j: (j, run_batch(home, runtime, a.pvtap,
                                                       [v for v, _ in j[1]])), jobs)
            results = []
            for (source, made), found in batches:
                in_flight[source] -= len(made)
                results += [((source, variant, how), findings)
                            for (variant, how), (_, findings) in zip(made, found)]
                clean = not any(findings for _, findings in found)
                batch_size[source] = (min(a.batch, batch_size[source] * 2) if clean
                                      else max(1, batch_size[source] // 2))
            for (source, variant, how), findings in results:
                per_source[source] += 1
                for program, kind, whose, text in findings:
                    key = (program, kind, whose)
                    counts[key] = counts.get(key, 0) + 1
                    keep = os.path.join(a.out, "findings", "%s-%s-%s-%s" % (
                        whose, program, kind, os.path.basename(variant)))
                    shutil.copy(variant, keep)
                    with open(keep + ".txt", "w") as f:
                        f.write("source: %s\neditcap %s\n\n%s" % (source, how, text[-20000:]))
                    print("campaign: %s %s (%s) on %s: kept as %s" % (program, kind, whose,
                                                                      how, keep), flush=True)
                os.remove(variant)
            done = sum(per_source.values())
            if done % 100 < len(results):
                print("campaign: %d variants run" % done, flush=True)
    home.close()
    ours = sum(n for (_, _, whose), n in counts.items() if whose == "ours")
    theirs = sum(n for (_, _, whose), n in counts.items() if whose == "wireshark")
    done = sum(per_source.values())
    print("campaign: %d variants of %d captures; tshark -nVxr (ASan plugin)%s on each" % (
        done, len(sources), " and pvtap audit (ASan)" if a.pvtap else ""))
    print("campaign: variants per capture %d to %d" % (min(per_source.values()),
                                                       max(per_source.values())))
    print("campaign: findings ours %d, Wireshark's own %d" % (ours, theirs))
    for (program, kind, whose), n in sorted(counts.items()):
        print("campaign:   %-6s %-14s %-9s %d" % (program, kind, whose, n))
    return 1 if ours else 0


if __name__ == "__main__":
    sys.exit(main())
