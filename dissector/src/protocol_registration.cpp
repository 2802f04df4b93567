#include "protocol_registration.h"

#include <epan/packet.h>

#include "bus_track.h"
#include "common_fields.h"
#include "inverter_protocol.h"
#include "preferences.h"
#include "record_dissector.h"
#include "register_fields.h"
#include "register_maps.h"
#include "response_time_stats.h"
#include "transport_entry.h"

namespace pvtap::dissector {
namespace {

void register_protocol(InverterProtocol& p) {
  p.proto = proto_register_protocol(p.name, p.short_name, p.filter_name);
  register_common_items(p);
  register_preferences(p);
  register_response_time_stats(p);
  register_transport_dissectors(p);
}

}  // namespace

void register_protocols() {
  // User maps decide which register fields exist, so they are read before any field.
  load_register_maps();
  register_protocol(rtu_protocol());
  register_protocol(ascii_protocol());
  register_register_fields(rtu_protocol().proto, Dialect::Hybrid);
  register_register_fields(rtu_protocol().proto, Dialect::Gsl);
  register_register_fields(ascii_protocol().proto, Dialect::Ascii);
  register_record_dissector();
  apply_preferences();
  register_cleanup_routine(release_bus_tracks);
}

void register_handoffs() {
  register_transport_handoffs(rtu_protocol());
  register_transport_handoffs(ascii_protocol());
}

}  // namespace pvtap::dissector
