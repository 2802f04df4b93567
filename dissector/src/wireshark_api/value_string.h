// value_string and its helpers, from wherever the series keeps them.
#pragma once

#include "wireshark_api/series.h"

// Wireshark 4.6 moved value_string.h from epan/ to wsutil/, with the same contents.
#if PVTAP_WIRESHARK_AT_LEAST(4, 6)
#include <wsutil/value_string.h>
#else
#include <epan/value_string.h>
#endif
