#!/usr/bin/env bash
# The Debian package for real: lintian, dpkg -i, the installed pvtap, plugin, capture interface,
# man pages and completion checked as an unprivileged user (check_installed.py), then dpkg -r
# and a check that none of the package's files is left.
#
# Usage (as root): check_install.sh PVTAP_DEB [BUILD_TREE_PLUGIN]
#   BUILD_TREE_PLUGIN: the build's pvtap.so; with it, a plugin test run while the package is
#   installed must fail with the "system-wide pvtap.so" explanation.
#
# A system-wide pvtap.so makes every other tshark test on the machine load the plugin twice,
# so the package is installed for as short a time as possible and removed whatever happens (a
# trap). Where the kernel allows it, the whole test runs in a private mount namespace whose
# /usr, /var and /etc are overlays on a tmpfs: then no other process ever sees the package.
# scripts/test runs this after every other test.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
deb="$(realpath "$1")"
build_plugin="${2:-}"
[[ -n "$build_plugin" ]] && build_plugin="$(realpath "$build_plugin")"

if [[ "$(id -u)" -ne 0 ]]; then
  echo "check_install: needs root (dpkg -i)" >&2
  exit 1
fi

# Into a private mount namespace, once.
if [[ -z "${PVTAP_INSTALL_NAMESPACE-}" ]]; then
  if unshare --mount --propagation private true 2>/dev/null; then
    exec unshare --mount --propagation private env PVTAP_INSTALL_NAMESPACE=1 \
      bash "${BASH_SOURCE[0]}" "$@"
  fi
  PVTAP_INSTALL_NAMESPACE=0
fi

scratch="$(mktemp -d /tmp/pvtap-install-test.XXXXXX)"
chmod 755 "$scratch"  # the unprivileged user's HOME is inside
installed=0
overlaid=()

remove_package() {
  if dpkg-query -W -f='${db:Status-Status}' pvtap 2>/dev/null | grep -qv '^not-installed$'; then
    echo "== check_install: dpkg --purge pvtap"
    dpkg --purge pvtap >/dev/null
  fi
}

cleanup() {
  local status=$?
  ((installed)) && remove_package
  local dir
  for dir in "${overlaid[@]}"; do umount "$dir" 2>/dev/null || umount -l "$dir" || true; done
  umount "$scratch" 2>/dev/null || true
  rm -rf "$scratch"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# /usr, /var and /etc as overlays in this namespace: all of them or none (the dpkg database
# and the files must go to the same place).
sandbox() {
  mount -t tmpfs -o mode=0755 pvtap-install-test "$scratch" || return 1
  local dir
  for dir in /usr /var /etc; do
    mkdir -p "$scratch/upper$dir" "$scratch/work$dir"
    if ! mount -t overlay overlay \
      -o "lowerdir=$dir,upperdir=$scratch/upper$dir,workdir=$scratch/work$dir" "$dir"; then
      for dir in "${overlaid[@]}"; do umount "$dir"; done
      overlaid=()
      umount "$scratch"
      return 1
    fi
    overlaid+=("$dir")
  done
}
if [[ "$PVTAP_INSTALL_NAMESPACE" == 1 ]] && sandbox; then
  echo "== check_install: in a private mount namespace (/usr, /var, /etc overlaid)"
else
  echo "== check_install: no private mount namespace; installing system-wide for the test"
fi
mkdir -p "$scratch/home"

contents() { dpkg-deb --fsys-tarfile "$deb" | tar -t | sed -e 's|^\./|/|' -e 's|/$||' | grep -v '^$' | grep -v '^/$'; }
plugin_file="$(contents | grep '/epan/pvtap\.so$')"
version="$(dpkg-deb -f "$deb" Version)"
# pvtap --version prints the upstream version, without the Debian release tag (0.1.0~deb12).
upstream_version="${version%%~*}"

echo "== check_install: lintian"
# Errors fail the test; warnings are listed.
lintian_status=0
lintian --fail-on error --display-level '>=warning' "$deb" >"$scratch/lintian.txt" 2>&1 ||
  lintian_status=$?
grep -v 'running with root privileges' "$scratch/lintian.txt" || true
if ((lintian_status != 0)); then
  echo "check_install: lintian reports errors (exit status $lintian_status)" >&2
  exit 1
fi

echo "== check_install: before installing"
if dpkg-query -W -f='${db:Status-Status}' pvtap 2>/dev/null | grep -q '^installed$'; then
  echo "check_install: a pvtap package is already installed; this test would remove it" >&2
  exit 1
fi
if [[ -e "$plugin_file" ]]; then
  echo "check_install: $plugin_file exists already (cmake --install?); remove it first" >&2
  exit 1
fi
# Directories that exist before the install must survive the removal; the others must go.
existing_dirs="$scratch/existing-dirs"
contents | while read -r path; do [[ -d "$path" ]] && echo "$path"; done >"$existing_dirs" || true

echo "== check_install: dpkg -i $(basename "$deb")"
installed=1
dpkg -i "$deb"

python3 "$here/check_installed.py" --version "$upstream_version" --home "$scratch/home"

if [[ -n "$build_plugin" ]]; then
  echo "== check_install: a plugin test refuses to run next to the installed plugin"
  refused="$scratch/refused.txt"
  if (cd "$here/../dissector" && PVTAP_PLUGIN="$build_plugin" PYTHONDONTWRITEBYTECODE=1 \
    python3 -m unittest test_exported_pdu) >"$refused" 2>&1; then
    echo "check_install: the plugin test ran although pvtap.so is installed system-wide" >&2
    exit 1
  fi
  if ! grep -q "a system-wide pvtap.so is installed" "$refused"; then
    echo "check_install: the plugin test failed without the system-wide explanation:" >&2
    cat "$refused" >&2
    exit 1
  fi
  echo "ok: the plugin test stops with: $(grep -o 'a system-wide pvtap.so is installed[^:]*' "$refused" | head -1)"
fi

echo "== check_install: dpkg -r pvtap"
dpkg -r pvtap
remove_package
installed=0
if dpkg-query -W -f='${db:Status-Status}' pvtap 2>/dev/null | grep -qv '^not-installed$'; then
  echo "check_install: dpkg still knows pvtap after the purge" >&2
  exit 1
fi
left=0
while read -r path; do
  if [[ -L "$path" || -e "$path" ]] && ! grep -qxF "$path" "$existing_dirs"; then
    echo "check_install: left behind: $path" >&2
    left=1
  fi
done < <(contents)
((left == 0)) || exit 1
echo "ok: dpkg -r left none of the package's $(contents | wc -l) paths behind"
echo "== check_install: all checks hold"
