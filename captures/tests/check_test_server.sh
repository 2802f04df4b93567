#!/usr/bin/env bash
# A Modbus library's test suite heard on the bus beside Hybrid and GSL inverters: its report
# server ID and read/write multiple registers replies fit Hybrid V2.2's layouts of 0x11 and 0x17
# as well, and only their requests tell. pvtap audit must read every frame in the dialect the
# ground truth gives, name the server by its server ID, find the late reply that a peer put on
# the line for a station nobody has, take a read broadcast to address 0 and a write whose byte
# count disagrees with its quantity for findings, and a write whose byte count says fewer bytes
# than it carries for a malformed frame paired with its exception, and frame a user-defined
# function's request, on all three carriers.
#
#   check_test_server.sh PVTAP_SIM PYTHON CHECK_SAMPLE_AUDIT PVTAP SCRATCH_DIR
set -euo pipefail
sim=$1 python=$2 check=$3 pvtap=$4 scratch=$5
mkdir -p "$scratch"
cd "$scratch"
"$sim" --seed 2 --dialect hybrid,gsl --inverters 2 --test-server 17 --duration 120 \
  --faults missing=4,corrupt=4,error_reply=4,noise=4 \
  --pdu suite.pdu.pcap --gateway suite.gateway.pcap --chunked suite.user0.pcap \
  --truth suite.truth.json
# The replies that fit both layouts (an even byte count of at least 4) and the late reply.
"$python" - suite.truth.json <<'PY'
import json, sys
events = json.load(open(sys.argv[1]))["events"]
def both(e):
    n = bytes.fromhex(e["hex"])[2]
    return e["type"] == "frame" and e["role"] == "response" and e["dialect"] == "modbus" \
        and e["function"] in (0x11, 0x17) and n >= 4 and n % 2 == 0
faults = {e.get("fault") for e in events}
wanted = {"late_reply", "broadcast_read", "write_count_mismatch", "byte_count_lies",
          "user_defined_function"}
if not any(both(e) for e in events) or not wanted <= faults:
    sys.exit(f"the ground truth lacks a reply that fits Hybrid too, or one of {wanted}")
PY
status=0
for carrier in pdu gateway user0; do
  "$python" "$check" "$pvtap" "suite.$carrier.pcap" suite.truth.json || status=1
done
exit $status
