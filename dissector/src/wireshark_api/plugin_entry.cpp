// The symbols Wireshark 4.0 looks up when it loads pvtap.so as an epan plugin.
#include <epan/proto.h>
#include <ws_symbol_export.h>

#include "protocol_registration.h"

extern "C" {
WS_DLL_PUBLIC_DEF extern const char plugin_version[];
WS_DLL_PUBLIC_DEF extern const int plugin_want_major;
WS_DLL_PUBLIC_DEF extern const int plugin_want_minor;
WS_DLL_PUBLIC_DEF void plugin_register(void);
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
