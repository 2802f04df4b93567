#!/usr/bin/env bash
# Throughput of `pvtap audit` on a large generated gateway capture against libpcap's own
# read rate (`tcpdump -r FILE -w /dev/null`, timed in every round next to the audits), with
# peak memory; optionally the same capture through tshark with Wireshark's built-in Modbus
# RTU dissector. Every time is printed as wall time and CPU time (user + system), medians of
# RUNS rounds; MB/s are capture bytes per CPU second (one core). Each audit runs as by
# default (reading ahead on a second thread) and, for the one-core figures, with --threads 1.
#
#   bench/audit_throughput.sh [MEGABYTES]      (default 200; Release build in build/)
#   bench/audit_throughput.sh --big [GB]       a GB-gigabyte capture (default 10): summary-only
#                                              and jsonl only, peak RSS must stay under 64 MB
#
# Environment: BUILD (build directory, default build), PVTAP (the binary to time, default
# $BUILD/analyzer/pvtap), OLD (a second pvtap binary, timed round by round alternating with
# PVTAP, to compare two builds on a noisy machine), CAPTURE (where the capture is written,
# default /tmp/pvtap-bench.pcap; one made earlier for the same MEGABYTES is reused), RUNS
# (rounds, the median is reported; 3, 1 with --big), TSHARK=0 to skip the tshark comparison,
# NO_BUILD=1 to time the binaries as they are, KIND=v5 for the same poll rounds through a
# Solarman V5 logger stick (pvtap-capture-gen bench-v5; default capture
# /tmp/pvtap-bench-v5.pcap; no tshark run). Figures go to stdout; record them in
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
((big)) && megabytes=$((${1:-10} * 1024))
build="${BUILD:-build}"
kind="${KIND:-gateway}"
generator=bench
capture="${CAPTURE:-/tmp/pvtap-bench.pcap}"
if [[ "$kind" == v5 ]]; then
  generator=bench-v5
  capture="${CAPTURE:-/tmp/pvtap-bench-v5.pcap}"
fi
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
  echo "== generating a ${megabytes} MB $kind capture: $capture"
  "$build/tests/analyzer/pvtap-capture-gen" "$generator" "$capture" "$megabytes"
  echo "$megabytes" >"$capture.request"
fi
bytes=$(stat -c %s "$capture")
echo "capture: $capture, $bytes bytes; load: $(uptime | sed 's/.*load average: //')"

# A first read brings the capture into the page cache for every later run.
tcpdump -r "$capture" -w /dev/null 2>/dev/null
tcpdump_rss=0
lines=()
old_threads=0
if [[ -n "$old" ]] && "$old" audit --help 2>/dev/null | grep -q -- --threads; then old_threads=1; fi

# Wall time (s), CPU time (user + system, s) and peak RSS (KiB) of one run. Both times: the
# audit reads ahead on a second thread, so its wall time is what a user waits, and its CPU
# time what it costs on one core; on a shared machine CPU time also varies far less.
time_once() {
  local stats
  stats="$(mktemp)"
  /usr/bin/time -f "%e %U %S %M" -o "$stats" "$@" >/dev/null 2>&1
  tail -1 "$stats" | awk '{ printf "%.2f %.2f %s\n", $1, $2 + $3, $4 }'
  rm -f "$stats"
}

median() { printf '%s\n' "$@" | sort -n | sed -n "$((($# + 1) / 2))p"; }

# One kind of audit ($2...) by the binary (and by OLD, alternating run by run so that both
# see the same load); sets w_<name>/c_<name> (and w_<name>_old/c_<name>_old) to the median
# wall and CPU times.
audit_pair() {
  local name="$1" new_w=() new_c=() old_w=() old_c=() new_rss=0 old_rss=0 w c r
  shift
  # A build older than --threads reads on one thread anyway: it gets the other options.
  local old_args=() skip=0 arg
  for arg in "$@"; do
    if ((skip)); then skip=0; continue; fi
    if [[ "$arg" == --threads && "$old_threads" == 0 ]]; then skip=1; continue; fi
    old_args+=("$arg")
  done
  for ((i = 0; i < runs; i++)); do
    # tcpdump in every round: the ratios compare runs that saw the same load.
    read -r w c r < <(time_once tcpdump -r "$capture" -w /dev/null)
    tcpdump_w+=("$w")
    tcpdump_c+=("$c")
    ((r > tcpdump_rss)) && tcpdump_rss=$r
    if [[ -n "$old" ]]; then
      read -r w c r < <(time_once "$old" audit "${old_args[@]}" "$capture")
      old_w+=("$w")
      old_c+=("$c")
      ((r > old_rss)) && old_rss=$r
    fi
    read -r w c r < <(time_once "$pvtap" audit "$@" "$capture")
    new_w+=("$w")
    new_c+=("$c")
    ((r > new_rss)) && new_rss=$r
  done
  if [[ -n "$old" ]]; then
    eval "w_${name}_old=$(median "${old_w[@]}") c_${name}_old=$(median "${old_c[@]}")"
    lines+=("old: audit $*|$(median "${old_w[@]}")|$(median "${old_c[@]}")|$old_rss")
  fi
  eval "w_${name}=$(median "${new_w[@]}") c_${name}=$(median "${new_c[@]}")"
  lines+=("${old:+new: }audit $*|$(median "${new_w[@]}")|$(median "${new_c[@]}")|$new_rss")
}

report() {
  local what="$1" wall="$2" cpu="$3" rss="$4"
  awk -v w="$what" -v s="$wall" -v c="$cpu" -v b="$bytes" -v r="$rss" -v tw="$w_tcpdump" \
    -v tc="$c_tcpdump" 'BEGIN {
    printf "%-44s %5.2f s wall %5.2fx | %5.2f s CPU %6.1f MB/s %5.2fx | RSS %5.1f MB\n", w, s,
      s / tw, c, b / 1e6 / c, c / tc, r / 1024 }'
}

tcpdump_w=()
tcpdump_c=()
audit_pair summary --summary-only
audit_pair summary1 --summary-only --threads 1
audit_pair jsonl --format jsonl
# At tens of gigabytes each run takes minutes: the big run is about memory, which the three
# above show; the one-core jsonl and csv figures come from the ordinary runs.
if ((!big)); then
  audit_pair jsonl1 --format jsonl --threads 1
  audit_pair csv --format csv
fi
w_tcpdump="$(median "${tcpdump_w[@]}")"
c_tcpdump="$(median "${tcpdump_c[@]}")"
echo "(wall: elapsed time and its multiple of tcpdump's; CPU: user + system, capture MB per CPU"
echo " second, i.e. on one core, and its multiple of tcpdump's CPU time)"
report "tcpdump -r FILE -w /dev/null" "$w_tcpdump" "$c_tcpdump" "$tcpdump_rss"
for line in "${lines[@]}"; do
  IFS='|' read -r what w c r <<<"$line"
  report "$what" "$w" "$c" "$r"
done
if [[ -n "$old" ]] && ((!big)); then
  awk -v a="$w_summary_old" -v b="$w_summary" -v c="$c_jsonl1_old" -v d="$c_jsonl1" \
    -v e="$c_csv_old" -v f="$c_csv" 'BEGIN {
    printf "new/old: summary-only wall %.2f, jsonl --threads 1 CPU %.2f, csv CPU %.2f\n", b / a, d / c, f / e }'
fi
awk -v t="$w_tcpdump" -v p="$w_summary" -v j="$w_jsonl" -v c="${c_jsonl1:-0}" -v b="$bytes" 'BEGIN {
  printf "targets: summary-only/tcpdump %.2f (wall, <= 2.5), jsonl/tcpdump %.2f (wall, <= 6)", p / t, j / t
  if (c > 0) printf ", jsonl on one core %.1f MB/s (--threads 1, CPU, >= 150)", b / 1e6 / c
  printf "\n" }'
if ((big)); then
  echo "peak RSS must stay under 64 MB (the figures above)"
fi

if ((!big)) && [[ "$kind" != v5 && "${TSHARK:-1}" != 0 ]] && command -v tshark >/dev/null; then
  # One run: tshark takes minutes on a capture this size.
  read -r w_tshark c_tshark rss_tshark < <(time_once tshark -r "$capture" \
    -d tcp.port==4001,mbrtu -Y mbrtu -T fields -e frame.number)
  report "tshark -d tcp.port==4001,mbrtu" "$w_tshark" "$c_tshark" "$rss_tshark"
  awk -v t="$w_tshark" -v p="$w_summary" -v j="$w_jsonl" 'BEGIN {
    printf "pvtap is %.0fx (summary-only) and %.0fx (jsonl) faster than tshark (wall)\n", t / p, t / j }'
fi
