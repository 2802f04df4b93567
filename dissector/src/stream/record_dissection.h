// Shows what the bus decided in the records of a serial capture (USER0-15, RTAC payloads).
#pragma once

#include <epan/packet.h>

#include "protocol/inverter_protocol.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {

// SerialRecordFields: what the serial layer registered to show a record whose bytes wait.
struct SerialRecordFields {
  int proto = -1;
  int waiting = -1;       // pvtap_serial.waiting: bytes of the record a later record shows
  int completed_in = -1;  // pvtap_serial.completed_in: that record
  int ett = -1;
};

// Feeds one record to `bus` as pvtap audit feeds a serial capture's records (one bus, the
// direction read from the frames' structure) and shows the pieces it decided: a frame that
// began in earlier records is shown whole on the record that completes it, from a reassembled
// buffer. A record whose last byte waits for a later record says so, with the record that
// completes it once the first pass has seen that one. The Source and Destination columns name
// the talkers of the frames shown. Returns the number of bytes taken (all of them).
int dissect_serial_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                          InverterProtocol& protocol, BusTrack& bus,
                          const SerialRecordFields& fields);

}  // namespace pvtap::dissector
