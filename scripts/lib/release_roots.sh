# shellcheck shell=bash
# Debian roots of the other supported releases (made with mmdebstrap from the Debian
# registry), kept between runs outside the checkout, and running a command inside one.
# Source this file; it defines variables and functions only. Needs root.

PVTAP_ROOTS_DIR="${PVTAP_ROOTS_DIR:-/var/cache/pvtap-roots}"
# A root older than this is made anew, so that it follows the release's updates.
PVTAP_ROOT_MAX_AGE_DAYS="${PVTAP_ROOT_MAX_AGE_DAYS:-7}"

# Debian testing's Release files, as the registry here serves them, carry an expired
# Valid-Until; their signatures are still checked.
pvtap_root_apt_options() {
  case "$1" in
    forky) echo "--aptopt=Acquire::Check-Valid-Until \"false\"" ;;
  esac
}

# Installs mmdebstrap when missing (on this machine, not in a root).
pvtap_root_tools_ensure() {
  command -v mmdebstrap >/dev/null ||
    apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends mmdebstrap </dev/null
}

# Makes $PVTAP_ROOTS_DIR/SUITE when it is missing or older than the maximum age. A new root
# is made beside the old one and only replaces it once complete.
pvtap_root_ensure() {
  local suite="$1" root="$PVTAP_ROOTS_DIR/$1" stamp="$PVTAP_ROOTS_DIR/$1/.pvtap-made"
  if [[ -f "$stamp" ]] && [[ -z "$(find "$stamp" -mtime +"$PVTAP_ROOT_MAX_AGE_DAYS")" ]]; then
    return 0
  fi
  pvtap_root_tools_ensure
  echo "== releases: making the $suite root ($root)"
  mkdir -p "$PVTAP_ROOTS_DIR"
  rm -rf "$root.new"
  local apt_option
  apt_option="$(pvtap_root_apt_options "$suite")"
  mmdebstrap --quiet --variant=apt --include=ca-certificates ${apt_option:+"$apt_option"} \
    "$suite" "$root.new" http://deb.debian.org/debian
  date -u +%FT%TZ >"$root.new/.pvtap-made"
  rm -rf "$root.old"
  [[ -d "$root" ]] && mv "$root" "$root.old"
  mv "$root.new" "$root"
  rm -rf "$root.old"
}

# Runs COMMAND... as root inside the SUITE root, in a mount namespace of its own (so that
# /proc, /dev and /sys are unmounted when it ends, whatever happens), with this machine's
# name resolution and a clean environment.
pvtap_root_run() {
  local root="$PVTAP_ROOTS_DIR/$1"
  shift
  cp /etc/hosts "$root/etc/hosts"
  cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
  unshare --mount --propagation private -- bash -c '
    root="$1"; shift
    mount -t proc proc "$root/proc"
    mount --rbind /dev "$root/dev"
    mount --rbind /sys "$root/sys"
    mount -t tmpfs tmpfs "$root/tmp"
    exec chroot "$root" /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      HOME=/root LANG=C.UTF-8 CI="${CI:-}" TERM=dumb "$@"
  ' pvtap-root "$root" "$@"
}
