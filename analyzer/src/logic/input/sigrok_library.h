// libsigrok (and the glib calls its API needs), loaded when a logic recording is read rather
// than at every start: a capture audit binds none of its libraries.
#pragma once

#include <libsigrok/libsigrok.h>

#include <string>

namespace pvtap::analyzer {

// SigrokLibrary: the libsigrok and glib functions pvtap calls, resolved from libsigrok's
// shared object and the glib it brings. Named apart from the C functions, some of which glib
// also defines as macros.
struct SigrokLibrary {
  // libsigrok
  decltype(&::sr_init) init;
  decltype(&::sr_exit) exit;
  decltype(&::sr_log_loglevel_set) log_loglevel_set;
  decltype(&::sr_session_load) session_load;
  decltype(&::sr_session_new) session_new;
  decltype(&::sr_session_destroy) session_destroy;
  decltype(&::sr_session_dev_add) session_dev_add;
  decltype(&::sr_session_datafeed_callback_add) session_datafeed_callback_add;
  decltype(&::sr_session_start) session_start;
  decltype(&::sr_session_run) session_run;
  decltype(&::sr_session_stop) session_stop;
  decltype(&::sr_input_scan_file) input_scan_file;
  decltype(&::sr_input_send) input_send;
  decltype(&::sr_input_end) input_end;
  decltype(&::sr_input_free) input_free;
  decltype(&::sr_input_dev_inst_get) input_dev_inst_get;
  decltype(&::sr_dev_inst_driver_get) dev_inst_driver_get;
  decltype(&::sr_dev_inst_channels_get) dev_inst_channels_get;
  decltype(&::sr_config_get) config_get;
  // glib (the names are not followed by a parenthesis, so glib's macros of them stay unused)
  decltype(&::g_variant_get_uint64) variant_get_uint64;
  decltype(&::g_variant_unref) variant_unref;
  decltype(&::g_string_sized_new) string_sized_new;
  decltype(&::g_string_truncate) string_truncate;
  decltype(&::g_string_append_len) string_append_len;
  decltype(&::g_string_free) string_free;
};

// The library, loaded on the first call; nullptr with `error` set to a one-line reason (not
// installed, or a version without a function pvtap calls).
const SigrokLibrary* sigrok_library(std::string& error);

}  // namespace pvtap::analyzer
