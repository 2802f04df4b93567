#include "stream/station_names.h"

#include <epan/wmem_scopes.h>

#include <string>

#include "pvtap/session/device_naming.h"

namespace pvtap::dissector {

const char* StationNames::note(const SessionFrame& f) {
  if (f.frame == nullptr) return nullptr;
  const std::uint8_t station = f.frame->station;
  if (learn_device_name(said_[station], f)) {
    const std::string text = said_[station].text();
    text_[station] = text.empty() ? nullptr : wmem_strdup(wmem_file_scope(), text.c_str());
  }
  return text_[station];
}

}  // namespace pvtap::dissector
