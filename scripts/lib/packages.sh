# shellcheck shell=bash
# The Debian packages pvtap needs on each supported release, in one place, and the install
# step shared by scripts/test, scripts/demo, scripts/package and scripts/fuzz. Source this
# file; it defines variables and functions only.

# What differs between the releases pvtap supports, by codename (VERSION_CODENAME of
# /etc/os-release). The Wireshark ABI package (libwireshark16, 18, 19) is not listed: it
# comes with wireshark-dev, and the .deb's dependency on it is read from the plugin's
# linkage (packaging/PackageDeb.cmake).
#   tag: the release tag in the package version (pvtap_<version>~deb13_amd64.deb)
#   clang: the clang series with libFuzzer and the sanitizer runtimes (scripts/fuzz)
declare -A PVTAP_RELEASE_NAME=([bookworm]="Debian 12" [trixie]="Debian 13" [forky]="Debian testing")
declare -A PVTAP_RELEASE_TAG=([bookworm]=deb12 [trixie]=deb13 [forky]=deb14)
declare -A PVTAP_RELEASE_CLANG=([bookworm]=14 [trixie]=19 [forky]=21)

# Build and test toolchain, the core's libraries, and what the analyzer and the
# Wireshark plugin need (wireshark-dev, tshark, libpcap-dev, libcli11-dev); python3 runs the
# analyzer's end-to-end checks.
PVTAP_PACKAGES=(
  build-essential
  cmake
  pkg-config
  libgtest-dev
  libgmock-dev
  libbenchmark-dev
  libtomlplusplus-dev
  clang-format
  wireshark-dev
  tshark
  libpcap-dev
  libcli11-dev
  python3
  # pvtap --version's test hides plugin files with unshare and mount --bind (mount left
  # Debian's essential set: a minimal root has unshare without it).
  mount
  # Packaging (scripts/package and its tests): man pages from --help, CPack's dependency
  # computation (dpkg-shlibdeps needs file), the package check, man, the completion test.
  help2man
  file
  lintian
  man-db
  bash-completion
  # scripts/fuzz: the libFuzzer targets are built with clang and its runtimes (the
  # release's clang-N and libclang-rt-N-dev, added by pvtap_packages); GNU time gives each
  # fuzzer's CPU time (and the benchmarks' peak RSS).
  time
  # The real-peer capture test (captures/real-peer/record): software we did not write.
  mbpoll
  python3-pymodbus
  python3-serial
  python3-serial-asyncio
  ser2net
  socat
  tcpdump
  # pvtap --html inlines Debian's dygraphs at build time; its test opens the page in a real
  # browser (headless chromium, driven over the DevTools pipe).
  libjs-dygraphs
  chromium
  # pvtap --mqtt (libmosquitto) and its tests: a real broker, its clients, certificates made
  # with openssl, and Debian's paho for the tests' subscriber.
  libmosquitto-dev
  mosquitto
  mosquitto-clients
  openssl
  python3-paho-mqtt
  # pvtap audit SESSION.sr reads logic-analyzer recordings with libsigrok; its tests and the
  # bench compare with sigrok-cli's own UART and Modbus decoders.
  libsigrok-dev
  sigrok-cli
  # pvtap-sim --sr writes sigrok sessions (a zip) with libzip.
  libzip-dev
  # The test of --values-format influx writes the line protocol into a real InfluxDB and
  # reads it back (influxd 1.6 on Debian 12, 13 and testing).
  influxdb
)

# The system's os-release file (PVTAP_OS_RELEASE lets the tests name another).
pvtap_os_release_file() {
  echo "${PVTAP_OS_RELEASE:-/etc/os-release}"
}

# The codename of the running Debian release if pvtap supports it; fails otherwise.
pvtap_release() {
  local codename="" id="" file
  file="$(pvtap_os_release_file)"
  if [[ -r "$file" ]]; then
    # shellcheck disable=SC1090
    codename="$(. "$file" && echo "${VERSION_CODENAME:-}")"
    # shellcheck disable=SC1090
    id="$(. "$file" && echo "${ID:-}")"
  fi
  [[ "$id" == debian && -n "$codename" && -n "${PVTAP_RELEASE_TAG[$codename]:-}" ]] || return 1
  echo "$codename"
}

# The package tag of the running release (deb12, deb13, deb14).
pvtap_release_tag() {
  local release
  release="$(pvtap_release)" || return 1
  echo "${PVTAP_RELEASE_TAG[$release]}"
}

# The CMake settings of a build the package can be made from (scripts/package): Debian's
# hardening flags (dpkg-buildflags, with CPPFLAGS where CMake reads them, and without -g: CPack
# strips the binaries), installed under /usr, tagged for the running release. Set as cache
# values, not through the environment, so that an existing build folder takes them too.
# Fills the array PVTAP_PACKAGE_CMAKE_ARGS.
pvtap_package_cmake_args() {
  local cppflags cflags cxxflags ldflags
  no_debug() { sed -e 's/\(^\| \)-g\( \|$\)/ /g' <<<"$1"; }
  cppflags="$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get CPPFLAGS)"
  cflags="$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get CFLAGS)"
  cxxflags="$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get CXXFLAGS)"
  ldflags="$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get LDFLAGS)"
  PVTAP_PACKAGE_CMAKE_ARGS=(
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr
    "-DPVTAP_PACKAGE_RELEASE_TAG=$(pvtap_release_tag)"
    "-DCMAKE_C_FLAGS=$(no_debug "$cppflags $cflags")"
    "-DCMAKE_CXX_FLAGS=$(no_debug "$cppflags $cxxflags")"
    "-DCMAKE_EXE_LINKER_FLAGS=$ldflags" "-DCMAKE_SHARED_LINKER_FLAGS=$ldflags"
    "-DCMAKE_MODULE_LINKER_FLAGS=$ldflags")
}

# The clang command of the running release (clang-14, clang-19, clang-21).
pvtap_clang() {
  local release
  release="$(pvtap_release)" || return 1
  echo "clang-${PVTAP_RELEASE_CLANG[$release]}"
}

# Prints every package pvtap needs on the running release, one per line.
pvtap_packages() {
  local release
  release="$(pvtap_release)" || return 1
  printf '%s\n' "${PVTAP_PACKAGES[@]}"
  printf '%s\n' "clang-${PVTAP_RELEASE_CLANG[$release]}" "libclang-rt-${PVTAP_RELEASE_CLANG[$release]}-dev"
}

# On a system that is not one of the supported releases: what pvtap needs, and exit 2.
pvtap_unsupported_system() {
  local pretty="an unknown system" release file
  file="$(pvtap_os_release_file)"
  # shellcheck disable=SC1090
  [[ -r "$file" ]] && pretty="$(. "$file" && echo "${PRETTY_NAME:-$pretty}")"
  {
    echo "pvtap: this is $pretty; the package step knows only these Debian releases:"
    for release in bookworm trixie forky; do
      echo "  ${PVTAP_RELEASE_NAME[$release]} ($release), clang-${PVTAP_RELEASE_CLANG[$release]}"
    done
    echo "pvtap: elsewhere, install the equivalents of these Debian packages yourself:"
    printf '%s\n' "${PVTAP_PACKAGES[@]}" "clang and its sanitizer/libFuzzer runtimes" | paste -sd' ' | fold -s -w 88 | sed 's/^/  /'
    echo "pvtap: needed: a C++20 compiler, CMake >= 3.25 and Wireshark 4.0, 4.2, 4.4 or 4.6 with its development files"
  } >&2
  exit 2
}

# Prints the packages pvtap needs that are not installed, one per line.
pvtap_missing_packages() {
  local pkg status
  for pkg in $(pvtap_packages); do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
    if [[ "$status" != "installed" ]]; then
      printf '%s\n' "$pkg"
    fi
  done
}

# Installs whatever is missing. As root it runs apt-get non-interactively (never
# prompting, also with no stdin); otherwise it prints the command to run and fails.
pvtap_ensure_packages() {
  local missing=()
  pvtap_release >/dev/null || pvtap_unsupported_system
  mapfile -t missing < <(pvtap_missing_packages)
  if ((${#missing[@]} == 0)); then
    return 0
  fi
  if [[ "$(id -u)" -ne 0 ]]; then
    echo "pvtap: missing Debian packages: ${missing[*]}" >&2
    echo "pvtap: install them with:" >&2
    echo "  sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
    return 1
  fi
  echo "pvtap: installing missing Debian packages: ${missing[*]}"
  # wireshark-common asks whether non-root users may capture; answer "no" up front.
  echo "wireshark-common wireshark-common/install-setuid boolean false" | debconf-set-selections
  export DEBIAN_FRONTEND=noninteractive
  apt-get -o DPkg::Lock::Timeout=600 update -qq
  apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}" </dev/null
}
