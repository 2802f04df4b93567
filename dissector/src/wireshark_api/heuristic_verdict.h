// What a heuristic dissector returns, per series.
#pragma once

#include <glib.h>

#include "wireshark_api/series.h"

namespace pvtap::dissector {

// heur_dissector_t returns bool from Wireshark 4.2 on (gboolean before); a function of the
// other type does not convert to the callback type, so the type is chosen here.
#if PVTAP_WIRESHARK_AT_LEAST(4, 2)
using HeuristicVerdict = bool;
inline constexpr HeuristicVerdict kClaimed = true;
inline constexpr HeuristicVerdict kDeclined = false;
#else
using HeuristicVerdict = gboolean;
inline constexpr HeuristicVerdict kClaimed = TRUE;
inline constexpr HeuristicVerdict kDeclined = FALSE;
#endif

}  // namespace pvtap::dissector
