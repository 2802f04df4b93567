// Serial captures in Wireshark: link types USER0-USER15 and RTAC serial payloads.
#pragma once

namespace pvtap::dissector {

// Registers the dissector of serial records and its preference; call at protocol registration.
void register_serial_link_types();

// Claims USER0-USER15 (unless the preference leaves them alone; applied again when it changes)
// and RTAC serial payloads (Decode As chooses another protocol for them); call at handoff.
void claim_serial_link_types();

}  // namespace pvtap::dissector
