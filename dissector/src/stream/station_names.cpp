#include "stream/station_names.h"

#include <epan/wmem_scopes.h>

#include <string>

#include "pvtap/codec/device_identification.h"

namespace pvtap::dissector {
namespace {

// Whether `kept` took what the device said (it differs and is not empty).
bool keep(std::string& kept, std::string_view said) {
  if (said.empty() || kept == said) return false;
  kept.assign(said);
  return true;
}

// The same rule as the session's station table: a good reply in which the station names
// itself; the server ID only from a station of the Modbus family.
bool learn(DeviceName& name, const SessionFrame& f) {
  if (!f.check.ok || f.frame == nullptr || f.role != Role::Response) return false;
  if (const auto id = read_device_identification(*f.frame)) {
    bool changed = keep(name.vendor, id->vendor());
    changed = keep(name.product, id->product()) || changed;
    return keep(name.revision, id->revision()) || changed;
  }
  if (!modbus_family(f.dialect)) return false;
  const auto server = read_server_id(*f.frame);
  return server && keep(name.server_id, server->text);
}

}  // namespace

const char* StationNames::note(const SessionFrame& f) {
  if (f.frame == nullptr) return nullptr;
  const std::uint8_t station = f.frame->station;
  if (learn(said_[station], f)) {
    const std::string text = said_[station].text();
    text_[station] = text.empty() ? nullptr : wmem_strdup(wmem_file_scope(), text.c_str());
  }
  return text_[station];
}

}  // namespace pvtap::dissector
