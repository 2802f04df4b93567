#include "registration/protocol_registration.h"

#include <epan/packet.h>

#include "carriers/solarman_v5_protocol.h"
#include "carriers/solarman_v5_track.h"
#include "fields/common_fields.h"
#include "fields/modbus_fields.h"
#include "fields/register_fields.h"
#include "protocol/inverter_protocol.h"
#include "registration/mbap_entry.h"
#include "registration/record_dissector.h"
#include "registration/serial_link_types.h"
#include "registration/transport_entry.h"
#include "settings/preferences.h"
#include "settings/register_maps.h"
#include "statistics/response_time_stats.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {
namespace {

void register_protocol(InverterProtocol& p) {
  p.proto = proto_register_protocol(p.name, p.short_name, p.filter_name);
  register_common_items(p);
  if (p.dialects.contains(Dialect::Modbus)) register_modbus_items(p);
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
  // The RTU protocol's dialects first, in the order their fields have always had.
  for (const bool rtu : {true, false}) {
    for (const Dialect d : kAllDialects) {
      if (rtu_framed(d) == rtu) register_register_fields(protocol_of(d).proto, d);
    }
  }
  register_record_dissector();
  register_mbap_protocol();
  register_serial_link_types();
  register_v5_protocol();
  apply_preferences();
  register_cleanup_routine(release_bus_tracks);
  register_cleanup_routine(release_v5_tracks);
}

void register_handoffs() {
  register_transport_handoffs(rtu_protocol());
  register_transport_handoffs(ascii_protocol());
  register_mbap_handoff();
  claim_serial_link_types();
  register_v5_handoff();
}

}  // namespace pvtap::dissector
