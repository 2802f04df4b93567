#!/usr/bin/env bash
# Regenerates the sample library into a scratch folder and requires every file to be
# byte for byte the committed one, with no file missing or extra on either side.
#
#   check_regenerate.sh SOURCE_DIR PVTAP_SIM SCRATCH_DIR
set -euo pipefail
source_dir=$1 sim=$2 scratch=$3
rm -rf "$scratch"
mkdir -p "$scratch"
"$source_dir/captures/regenerate" "$scratch" "$sim"
committed="$source_dir/captures/samples"
status=0
names() { (cd "$1" && printf '%s\n' *.pcap *.sr *.json | sort); }
diff <(names "$committed") <(names "$scratch") || status=1
for f in "$scratch"/*; do
  name=$(basename "$f")
  if ! cmp -s "$f" "$committed/$name"; then
    echo "differs from the committed file: captures/samples/$name"
    status=1
  fi
done
exit $status
