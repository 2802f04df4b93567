# shellcheck shell=bash
# The Debian 12 packages pvtap needs, in one place, and the install step shared by
# scripts/test and scripts/demo. Source this file; it defines functions only.

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
  # Packaging (scripts/package and its tests): man pages from --help, CPack's dependency
  # computation (dpkg-shlibdeps needs file), the package check, man, the completion test.
  help2man
  file
  lintian
  man-db
  bash-completion
  # scripts/fuzz: the libFuzzer targets are built with clang and its runtimes.
  clang-14
  libclang-rt-14-dev
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
)

# Prints the packages of PVTAP_PACKAGES that are not installed, one per line.
pvtap_missing_packages() {
  local pkg status
  for pkg in "${PVTAP_PACKAGES[@]}"; do
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
