// Shows what the bus decided in the records of a serial capture (USER0-15, RTAC payloads).
#pragma once

#include <epan/packet.h>

#include "registration/inverter_protocol.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {

// Feeds one record to `bus` as pvtap audit feeds a serial capture's records (one bus, the
// direction read from the frames' structure) and shows the pieces it decided: a frame that
// began in earlier records is shown whole on the record that completes it, from a reassembled
// buffer. Returns the number of bytes taken (all of them).
int dissect_serial_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                          InverterProtocol& protocol, BusTrack& bus);

}  // namespace pvtap::dissector
