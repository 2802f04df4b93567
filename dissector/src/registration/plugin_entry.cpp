// The symbols Wireshark looks up when it loads pvtap.so as an epan plugin, per series.
#include <epan/proto.h>
#include <ws_symbol_export.h>

#include <cstdint>

#include "registration/protocol_registration.h"
#include "wireshark_api/series.h"

#if PVTAP_WIRESHARK_AT_LEAST(4, 4)
#include <wsutil/plugins.h>
#endif

// Every series from 4.0 on looks up the version strings and plugin_register(). From 4.4 on,
// Wireshark also asks a plugin what it is (plugin_describe) and refuses one that cannot say.
extern "C" {
WS_DLL_PUBLIC_DEF extern const char plugin_version[];
WS_DLL_PUBLIC_DEF extern const int plugin_want_major;
WS_DLL_PUBLIC_DEF extern const int plugin_want_minor;
WS_DLL_PUBLIC_DEF void plugin_register(void);
#if PVTAP_WIRESHARK_AT_LEAST(4, 4)
WS_DLL_PUBLIC_DEF std::uint32_t plugin_describe(void);
#endif
}

// From CMake: project(VERSION) and the Wireshark found at configure time.
const char plugin_version[] = PVTAP_VERSION;
const int plugin_want_major = PVTAP_WIRESHARK_MAJOR;
const int plugin_want_minor = PVTAP_WIRESHARK_MINOR;

void plugin_register(void) {
  static const proto_plugin plugin = {pvtap::dissector::register_protocols,
                                      pvtap::dissector::register_handoffs};
  proto_register_plugin(&plugin);
}

#if PVTAP_WIRESHARK_AT_LEAST(4, 4)
// pvtap.so holds dissectors only (invascii, invrtu and pvtap for link type 252).
std::uint32_t plugin_describe(void) {
  return WS_PLUGIN_DESC_DISSECTOR;
}
#endif
