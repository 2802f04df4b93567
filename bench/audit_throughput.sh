#!/usr/bin/env bash
# Throughput of `pvtap audit` on a large generated gateway capture, with peak memory, and the
# same capture through tshark with Wireshark's built-in Modbus RTU dissector for comparison.
#
#   bench/audit_throughput.sh [MEGABYTES]      (default 200; Release build in build/)
#
# Environment: BUILD (build directory, default build), CAPTURE (where the capture is written,
# default /tmp/pvtap-bench.pcap), RUNS (runs per measurement, the median is reported; 3),
# TSHARK=0 to skip the tshark comparison. Figures go to stdout; record them in bench/README.md.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
megabytes="${1:-200}"
build="${BUILD:-build}"
capture="${CAPTURE:-/tmp/pvtap-bench.pcap}"
runs="${RUNS:-3}"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target pvtap pvtap-capture-gen >/dev/null
pvtap="$build/analyzer/pvtap"

echo "== generating a ${megabytes} MB gateway capture: $capture"
"$build/tests/analyzer/pvtap-capture-gen" bench "$capture" "$megabytes"
bytes=$(stat -c %s "$capture")
echo "capture: $bytes bytes"

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
  local what="$1" seconds="$2" rss="$3"
  awk -v w="$what" -v s="$seconds" -v b="$bytes" -v r="$rss" 'BEGIN {
    printf "%-34s %7.2f s  %8.1f MB/s  peak RSS %6.1f MB\n", w, s, b / 1e6 / s, r / 1024 }'
}

read -r s_summary rss_summary < <(measure "$pvtap" audit --summary-only "$capture")
report "pvtap audit --summary-only" "$s_summary" "$rss_summary"
read -r s_jsonl rss_jsonl < <(measure "$pvtap" audit --format jsonl "$capture")
report "pvtap audit --format jsonl" "$s_jsonl" "$rss_jsonl"

if [[ "${TSHARK:-1}" != 0 ]] && command -v tshark >/dev/null; then
  # One run: tshark takes minutes on a capture this size.
  runs=1
  read -r s_tshark rss_tshark < <(measure tshark -r "$capture" -d tcp.port==4001,mbrtu \
    -Y mbrtu -T fields -e frame.number)
  report "tshark -d tcp.port==4001,mbrtu" "$s_tshark" "$rss_tshark"
  awk -v t="$s_tshark" -v p="$s_summary" -v j="$s_jsonl" 'BEGIN {
    printf "pvtap is %.0fx (summary-only) and %.0fx (jsonl) faster than tshark\n", t / p, t / j }'
fi
