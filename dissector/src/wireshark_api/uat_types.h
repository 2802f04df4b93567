// The C type a user access table's callbacks answer with, per series.
#pragma once

#include <glib.h>

#include "wireshark_api/series.h"

namespace pvtap::dissector {

// Wireshark 4.2 moved its API from glib's gboolean to C's bool: a UAT's field check and
// update callbacks (uat_fld_chk_cb_t, uat_update_cb_t) return bool from 4.2 on.
#if PVTAP_WIRESHARK_AT_LEAST(4, 2)
using UatVerdict = bool;
#else
using UatVerdict = gboolean;
#endif

}  // namespace pvtap::dissector
