#!/bin/sh
# libsigrok is loaded only for logic recordings: with its shared object hidden (an empty file
# bound over it in a mount namespace of this test's own), a capture audit runs as before and a
# logic recording is refused in one line that names the library, exit 2.
# usage: check_without_libsigrok.sh PVTAP RECORDING CAPTURE
set -u
pvtap=$1 recording=$2 capture=$3
library=$(ldconfig -p | awk '/libsigrok\.so\.4 /{print $NF; exit}')
if [ -z "$library" ] || [ "$(id -u)" -ne 0 ] || ! command -v unshare >/dev/null; then
  echo "needs root, unshare and an installed libsigrok.so.4"
  exit 77
fi
if ldd "$pvtap" | grep -q libsigrok; then
  echo "FAIL: pvtap is linked with libsigrok"
  exit 1
fi
exec unshare --mount sh -c '
  mount --bind /dev/null "$1" || exit 77
  out=$("$2" audit "$3" 2>&1 >/dev/null); status=$?
  lines=$(printf "%s\n" "$out" | wc -l)
  failed=0
  [ "$status" -eq 2 ] || { echo "FAIL: exit $status for a recording without libsigrok"; failed=1; }
  [ "$lines" -eq 1 ] || { echo "FAIL: $lines lines: $out"; failed=1; }
  case $out in *libsigrok*apt-get\ install*) ;; *) echo "FAIL: no cause named: $out"; failed=1;; esac
  "$2" audit --summary-only "$4" >/dev/null || { echo "FAIL: a capture audit without libsigrok"; failed=1; }
  [ $failed -eq 0 ] && echo "1 passed, 0 failed"
  exit $failed' sh "$library" "$pvtap" "$recording" "$capture"
