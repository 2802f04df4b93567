#include "pvtap/codec/device_identification.h"
#include "pvtap/session/bus_report.h"
#include "pvtap/session/device_naming.h"

namespace pvtap {
namespace {

bool keep(std::string& kept, std::string_view said) {
  if (said.empty() || kept == said) return false;
  kept.assign(said);
  return true;
}

}  // namespace

std::string DeviceName::text() const {
  std::string out;
  for (const std::string* part : {&vendor, &product, &revision}) {
    if (part->empty()) continue;
    if (!out.empty()) out += ' ';
    out += *part;
  }
  return out.empty() ? server_id : out;
}

bool learn_device_name(DeviceName& name, const SessionFrame& f) {
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

}  // namespace pvtap
