#!/usr/bin/env bash
# The package step of scripts/lib/packages.sh, read against os-release files of each release
# and of a system it does not know: the names it picks, and the message and exit status 2
# elsewhere (before any apt call).
#
#   check_package_step.sh REPOSITORY_ROOT
set -uo pipefail

lib="$1/scripts/lib/packages.sh"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
passes=0
failures=0
check() {  # NAME CONDITION...
  local name="$1"
  shift
  if "$@"; then
    echo "ok: $name"
    passes=$((passes + 1))
  else
    echo "FAILED: $name"
    failures=$((failures + 1))
  fi
}

os_release() {  # ID CODENAME PRETTY -> a file
  local file="$scratch/$1-$2"
  printf 'ID=%s\nVERSION_CODENAME=%s\nPRETTY_NAME="%s"\n' "$1" "$2" "$3" >"$file"
  echo "$file"
}

in_release() {  # FILE COMMAND: runs a function of the library against that os-release file
  PVTAP_OS_RELEASE="$1" bash -c "source '$lib'; $2" 2>&1
}

bookworm="$(os_release debian bookworm 'Debian GNU/Linux 12 (bookworm)')"
trixie="$(os_release debian trixie 'Debian GNU/Linux 13 (trixie)')"
forky="$(os_release debian forky 'Debian GNU/Linux forky/sid')"
ubuntu="$(os_release ubuntu noble 'Ubuntu 24.04 LTS')"

check "Debian 12: clang-14 and its runtimes" \
  grep -qx 'libclang-rt-14-dev' <(in_release "$bookworm" pvtap_packages)
check "Debian 12: tag deb12" test "$(in_release "$bookworm" pvtap_release_tag)" = deb12
check "Debian 13: clang-19, not clang-14" \
  bash -c '[[ "$1" == *clang-19* && "$1" != *clang-14* ]]' _ "$(in_release "$trixie" pvtap_packages)"
check "Debian 13: tag deb13" test "$(in_release "$trixie" pvtap_release_tag)" = deb13
check "testing: clang-21" test "$(in_release "$forky" pvtap_clang)" = clang-21
check "every release: wireshark-dev" \
  bash -c 'for f in "$@"; do PVTAP_OS_RELEASE="$f" bash -c "source '"'$lib'"'; pvtap_packages" |
           grep -qx wireshark-dev || exit 1; done' _ "$bookworm" "$trixie" "$forky"

message="$(in_release "$ubuntu" pvtap_ensure_packages)"
status=$(PVTAP_OS_RELEASE="$ubuntu" bash -c "source '$lib'; pvtap_ensure_packages" >/dev/null 2>&1; echo $?)
check "another system: exit status 2 (got $status)" test "$status" -eq 2
check "another system: named" grep -q 'Ubuntu 24.04 LTS' <<<"$message"
check "another system: the needed packages listed" grep -q 'wireshark-dev' <<<"$message"
check "another system: no apt call" bash -c '! grep -qi "apt-get\|E: Unable" <<<"$1"' _ "$message"

echo "$passes passed, $failures failed"
((failures == 0))
