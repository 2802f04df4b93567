// Which Wireshark series the plugin is being built for, as the adapters of this folder ask it.
#pragma once

// PVTAP_WIRESHARK_MAJOR/MINOR come from the Wireshark that CMake found (dissector/CMakeLists.txt),
// so one source tree builds for whichever series is installed. Only the headers of this folder
// test them: the dissector itself is written once, against the names they define.
#define PVTAP_WIRESHARK_AT_LEAST(major, minor) \
  (PVTAP_WIRESHARK_MAJOR > (major) ||          \
   (PVTAP_WIRESHARK_MAJOR == (major) && PVTAP_WIRESHARK_MINOR >= (minor)))
