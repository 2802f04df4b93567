#!/usr/bin/env bash
# Replies damaged in a data byte, each followed within 8-15 ms by the next request, on a bus
# of GSL and Hybrid stations; the USER0 capture read by a sniffer up to 8 ms late, so that one
# read can hold a reply's last bytes, the silence and the next request's first bytes. pvtap
# audit must find every damaged reply as a frame with a bad check, on all three carriers.
#
#   check_close_damaged_replies.sh PVTAP_SIM PYTHON CHECK_SAMPLE_AUDIT PVTAP SCRATCH_DIR
set -euo pipefail
sim=$1 python=$2 check=$3 pvtap=$4 scratch=$5
mkdir -p "$scratch"
cd "$scratch"
"$sim" --seed 1 --dialect gsl,hybrid --inverters 4 --duration 120 --read-delay 8 \
  --faults corrupt_data=20,corrupt=4,corrupt_request=6,missing=4,noise=4,duplicate=4 \
  --pdu close.pdu.pcap --gateway close.gateway.pcap --chunked close.user0.pcap \
  --truth close.truth.json
grep -q '"fault":"corrupt_data"' close.truth.json || { echo "no corrupt_data reply" >&2; exit 1; }
status=0
for carrier in pdu gateway user0; do
  "$python" "$check" "$pvtap" "close.$carrier.pcap" close.truth.json || status=1
done
exit $status
