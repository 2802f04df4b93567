#!/usr/bin/env bash
# Throughput of `pvtap audit` on a large generated gateway capture against libpcap's own
# read rate (`tcpdump -r FILE -w /dev/null`, timed in every round next to the audits), with
# peak memory; optionally the same capture through tshark with Wireshark's built-in Modbus
# RTU dissector. Audit and tcpdump times are CPU seconds (user + system), medians of RUNS
# rounds; MB/s are capture bytes per CPU second (one core); tshark's is wall time.
#
#   bench/audit_throughput.sh [MEGABYTES]      (default 200; Release build in build/)
#   bench/audit_throughput.sh --big            a 2 GB capture: peak RSS must stay under 64 MB
#
# Environment: BUILD (build directory, default build), PVTAP (the binary to time, default
# $BUILD/analyzer/pvtap), OLD (a second pvtap binary, timed round by round alternating with
# PVTAP, to compare two builds on a noisy machine), CAPTURE (where the capture is written,
# default /tmp/pvtap-bench.pcap; one made earlier for the same MEGABYTES is reused), RUNS
# (rounds, the median is reported; 3, 1 with --big), TSHARK=0 to skip the tshark comparison,
# NO_BUILD=1 to time the binaries as they are. Figures go to stdout; record them in
# bench/README.md.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
big=0
if [[ "${1:-}" == --big ]]; then
  big=1
  shift
fi
megabytes="${1:-200}"
((big)) && megabytes=2048
build="${BUILD:-build}"
capture="${CAPTURE:-/tmp/pvtap-bench.pcap}"
runs="${RUNS:-3}"
((big)) && runs="${RUNS:-1}"

if [[ "${NO_BUILD:-0}" == 0 ]]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j "$(nproc)" --target pvtap pvtap-capture-gen >/dev/null
fi
pvtap="$(realpath "${PVTAP:-$build/analyzer/pvtap}")"
old="${OLD:+$(realpath "$OLD")}"

# The generator writes at least MEGABYTES; a capture left by an earlier run of the same
# size request is reused (its size is noted beside it).
if [[ ! -f "$capture" || "$(cat "$capture.request" 2>/dev/null)" != "$megabytes" ]]; then
  echo "== generating a ${megabytes} MB gateway capture: $capture"
  "$build/tests/analyzer/pvtap-capture-gen" bench "$capture" "$megabytes"
  echo "$megabytes" >"$capture.request"
fi
bytes=$(stat -c %s "$capture")
echo "capture: $capture, $bytes bytes; load: $(uptime | sed 's/.*load average: //')"

# Runs a command $runs times; prints the median wall time (s) and the largest peak RSS (KiB).
measure() {
  local times=() rss=0 line stats
  stats="$(mktemp)"
  for ((i = 0; i < runs; i++)); do
    /usr/bin/time -f "%e %M" -o "$stats" "$@" >/dev/null 2>&1
    line="$(tail -1 "$stats")"
    times+=("${line% *}")
    if ((${line#* } > rss)); then rss=${line#* }; fi
  done
  rm -f "$stats"
  printf '%s %s\n' "$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((runs + 1) / 2))p")" "$rss"
}

report() {
  local what="$1" seconds="$2" rss="$3" base="${4:-}"
  awk -v w="$what" -v s="$seconds" -v b="$bytes" -v r="$rss" -v t="$base" 'BEGIN {
    printf "%-40s %7.2f s CPU  %8.1f MB/s  peak RSS %6.1f MB", w, s, b / 1e6 / s, r / 1024
    if (t != "" && t > 0) printf "  %5.2fx tcpdump", s / t
    printf "\n" }'
}

# A first read brings the capture into the page cache for every later run.
tcpdump -r "$capture" -w /dev/null 2>/dev/null
tcpdump_t=()
tcpdump_rss=0
lines=()

# CPU time (user + system, s) and peak RSS (KiB) of one run. CPU time, not wall time: on a
# shared machine a run gets a varying share of a core, and its CPU time varies far less.
time_once() {
  local stats
  stats="$(mktemp)"
  /usr/bin/time -f "%U %S %M" -o "$stats" "$@" >/dev/null 2>&1
  tail -1 "$stats" | awk '{ printf "%.2f %s\n", $1 + $2, $3 }'
  rm -f "$stats"
}

median() { printf '%s\n' "$@" | sort -n | sed -n "$((($# + 1) / 2))p"; }

# One kind of audit ($2...) by the binary (and by OLD, alternating run by run so that both
# see the same load); sets s_<name> (and s_<name>_old) to the median times.
audit_pair() {
  local name="$1" new_t=() old_t=() new_rss=0 old_rss=0 t r
  shift
  for ((i = 0; i < runs; i++)); do
    # tcpdump in every round: the ratios compare runs that saw the same load.
    read -r t r < <(time_once tcpdump -r "$capture" -w /dev/null)
    tcpdump_t+=("$t")
    ((r > tcpdump_rss)) && tcpdump_rss=$r
    if [[ -n "$old" ]]; then
      read -r t r < <(time_once "$old" audit "$@" "$capture")
      old_t+=("$t")
      ((r > old_rss)) && old_rss=$r
    fi
    read -r t r < <(time_once "$pvtap" audit "$@" "$capture")
    new_t+=("$t")
    ((r > new_rss)) && new_rss=$r
  done
  if [[ -n "$old" ]]; then
    eval "s_${name}_old=$(median "${old_t[@]}")"
    lines+=("old: audit $*|$(median "${old_t[@]}")|$old_rss")
  fi
  eval "s_${name}=$(median "${new_t[@]}")"
  lines+=("${old:+new: }audit $*|$(median "${new_t[@]}")|$new_rss")
}

audit_pair summary --summary-only
audit_pair jsonl --format jsonl
audit_pair csv --format csv
s_tcpdump="$(median "${tcpdump_t[@]}")"
report "tcpdump -r FILE -w /dev/null" "$s_tcpdump" "$tcpdump_rss"
for line in "${lines[@]}"; do
  IFS='|' read -r what t r <<<"$line"
  report "$what" "$t" "$r" "$s_tcpdump"
done
if [[ -n "$old" ]]; then
  awk -v a="$s_summary_old" -v b="$s_summary" -v c="$s_jsonl_old" -v d="$s_jsonl" \
    -v e="$s_csv_old" -v f="$s_csv" 'BEGIN {
    printf "new/old time: summary-only %.2f, jsonl %.2f, csv %.2f\n", b / a, d / c, f / e }'
fi
awk -v t="$s_tcpdump" -v p="$s_summary" -v j="$s_jsonl" -v b="$bytes" 'BEGIN {
  printf "ratios: summary-only/tcpdump %.2f (target <= 2.5), jsonl/tcpdump %.2f (target <= 6), ", p / t, j / t
  printf "jsonl %.1f MB/s (target >= 150)\n", b / 1e6 / j }'
if ((big)); then
  echo "peak RSS must stay under 64 MB (the figures above)"
fi

if ((!big)) && [[ "${TSHARK:-1}" != 0 ]] && command -v tshark >/dev/null; then
  # One run: tshark takes minutes on a capture this size.
  runs=1
  read -r s_tshark rss_tshark < <(measure tshark -r "$capture" -d tcp.port==4001,mbrtu \
    -Y mbrtu -T fields -e frame.number)
  report "tshark -d tcp.port==4001,mbrtu" "$s_tshark" "$rss_tshark"
  awk -v t="$s_tshark" -v p="$s_summary" -v j="$s_jsonl" 'BEGIN {
    printf "pvtap is %.0fx (summary-only) and %.0fx (jsonl) faster than tshark\n", t / p, t / j }'
fi
