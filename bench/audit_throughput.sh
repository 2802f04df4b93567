#!/usr/bin/env bash
# Throughput of `pvtap audit` on a large generated gateway capture, against libpcap's own read
# rate (`tcpdump -r FILE -w /dev/null`, timed in the same run), with peak memory; optionally
# the same capture through tshark with Wireshark's built-in Modbus RTU dissector.
#
#   bench/audit_throughput.sh [MEGABYTES]      (default 200; Release build in build/)
#   bench/audit_throughput.sh --big            a 2 GB capture: peak RSS must stay under 64 MB
#
# Environment: BUILD (build directory, default build), PVTAP (the binary to time, default
# $BUILD/analyzer/pvtap), OLD (a second pvtap binary timed in the same run, alternating with
# PVTAP, to compare two builds on a noisy machine), CAPTURE (where the capture is written,
# default /tmp/pvtap-bench.pcap; an existing file of the right size is reused), RUNS (runs
# per measurement, the median is reported; 3), TSHARK=0 to skip the tshark comparison,
# NO_BUILD=1 to time the binaries as they are.
# Figures go to stdout; record them in bench/README.md.
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
    printf "%-40s %7.2f s  %8.1f MB/s  peak RSS %6.1f MB", w, s, b / 1e6 / s, r / 1024
    if (t != "" && t > 0) printf "  %5.2fx tcpdump", s / t
    printf "\n" }'
}

# tcpdump first (it also brings the capture into the page cache for every later run).
measure tcpdump -r "$capture" -w /dev/null >/dev/null
read -r s_tcpdump rss_tcpdump < <(measure tcpdump -r "$capture" -w /dev/null)
report "tcpdump -r FILE -w /dev/null" "$s_tcpdump" "$rss_tcpdump"

# One binary's three runs: summary-only, jsonl, csv; `label` names the binary in the lines.
audit_runs() {
  local binary="$1" label="$2" s rss
  read -r s rss < <(measure "$binary" audit --summary-only "$capture")
  report "${label}audit --summary-only" "$s" "$rss" "$s_tcpdump"
  eval "s_summary${3}=$s"
  read -r s rss < <(measure "$binary" audit --format jsonl "$capture")
  report "${label}audit --format jsonl" "$s" "$rss" "$s_tcpdump"
  eval "s_jsonl${3}=$s"
  read -r s rss < <(measure "$binary" audit --format csv "$capture")
  report "${label}audit --format csv" "$s" "$rss" "$s_tcpdump"
}

if [[ -n "$old" ]]; then
  audit_runs "$old" "old: " _old
  audit_runs "$pvtap" "new: " ""
  awk -v a="$s_summary_old" -v b="$s_summary" -v c="$s_jsonl_old" -v d="$s_jsonl" 'BEGIN {
    printf "new/old time: summary-only %.2f, jsonl %.2f\n", b / a, d / c }'
else
  audit_runs "$pvtap" "pvtap " ""
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
