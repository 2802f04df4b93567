#include "logic/input/sigrok_library.h"

#include <dlfcn.h>

namespace pvtap::analyzer {
namespace {

// The shared object's name as Debian 12, 13 and testing install it (libsigrok4, libsigrok4t64).
constexpr const char* kSoname = "libsigrok.so.4";

struct Loaded {
  SigrokLibrary library{};
  std::string error;
};

// dlsym on libsigrok's handle also finds the glib that libsigrok was linked with.
template <typename Function>
bool resolve(void* handle, const char* name, Function& function, std::string& error) {
  function = reinterpret_cast<Function>(::dlsym(handle, name));
  if (function == nullptr && error.empty()) {
    error = std::string("libsigrok lacks ") + name + " (" + kSoname + ")";
  }
  return function != nullptr;
}

Loaded load() {
  Loaded loaded;
  void* handle = ::dlopen(kSoname, RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = ::dlerror();
    loaded.error =
        std::string("logic recordings need libsigrok, which did not load (") +
        (why != nullptr ? why : kSoname) +
        "); on Debian: apt-get install libsigrok4 (libsigrok4t64 on Debian 13 and testing)";
    return loaded;
  }
  SigrokLibrary& l = loaded.library;
  std::string& e = loaded.error;
  resolve(handle, "sr_init", l.init, e);
  resolve(handle, "sr_exit", l.exit, e);
  resolve(handle, "sr_log_loglevel_set", l.log_loglevel_set, e);
  resolve(handle, "sr_session_load", l.session_load, e);
  resolve(handle, "sr_session_new", l.session_new, e);
  resolve(handle, "sr_session_destroy", l.session_destroy, e);
  resolve(handle, "sr_session_dev_add", l.session_dev_add, e);
  resolve(handle, "sr_session_datafeed_callback_add", l.session_datafeed_callback_add, e);
  resolve(handle, "sr_session_start", l.session_start, e);
  resolve(handle, "sr_session_run", l.session_run, e);
  resolve(handle, "sr_session_stop", l.session_stop, e);
  resolve(handle, "sr_input_scan_file", l.input_scan_file, e);
  resolve(handle, "sr_input_send", l.input_send, e);
  resolve(handle, "sr_input_end", l.input_end, e);
  resolve(handle, "sr_input_free", l.input_free, e);
  resolve(handle, "sr_input_dev_inst_get", l.input_dev_inst_get, e);
  resolve(handle, "sr_dev_inst_driver_get", l.dev_inst_driver_get, e);
  resolve(handle, "sr_dev_inst_channels_get", l.dev_inst_channels_get, e);
  resolve(handle, "sr_config_get", l.config_get, e);
  resolve(handle, "g_variant_get_uint64", l.variant_get_uint64, e);
  resolve(handle, "g_variant_unref", l.variant_unref, e);
  resolve(handle, "g_string_sized_new", l.string_sized_new, e);
  resolve(handle, "g_string_truncate", l.string_truncate, e);
  resolve(handle, "g_string_append_len", l.string_append_len, e);
  resolve(handle, "g_string_free", l.string_free, e);
  return loaded;  // the handle stays open for the process's life, as a linked library would
}

}  // namespace

const SigrokLibrary* sigrok_library(std::string& error) {
  static const Loaded loaded = load();
  error = loaded.error;
  return loaded.error.empty() ? &loaded.library : nullptr;
}

}  // namespace pvtap::analyzer
