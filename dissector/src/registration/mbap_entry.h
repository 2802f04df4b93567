// invmbap: Modbus/TCP read with pvtap's dialects, maps and verdicts, offered by Decode As.
#pragma once

namespace pvtap::dissector {

// Registers the invmbap protocol, its header fields and its dissector; call at protocol
// registration, after invrtu (the frames inside go to invrtu).
void register_mbap_protocol();

// Offers invmbap on TCP ports through Decode As and a port preference, both empty by
// default: Wireshark's own mbtcp keeps port 502 unless the user chooses otherwise.
void register_mbap_handoff();

}  // namespace pvtap::dissector
