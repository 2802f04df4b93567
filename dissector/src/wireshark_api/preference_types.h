// The C type Wireshark writes a boolean preference through, per series.
#pragma once

#include <glib.h>

#include "wireshark_api/series.h"

namespace pvtap::dissector {

// Wireshark 4.2 moved its API from glib's gboolean to C's bool:
// prefs_register_bool_preference takes a bool* from 4.2 on, a gboolean* before.
#if PVTAP_WIRESHARK_AT_LEAST(4, 2)
using PreferenceBool = bool;
#else
using PreferenceBool = gboolean;
#endif

}  // namespace pvtap::dissector
