// SolarmanV5Protocol: invv5, the logger stick's V5 frames on TCP around invrtu's frames.
#pragma once

#include <epan/expert.h>
#include <epan/packet.h>

#include <cstdint>

namespace pvtap::dissector {

// V5Fields: the ids of invv5's fields.
struct V5Fields {
  int length = -1;
  int control = -1;
  int sequence = -1;
  int serial = -1;
  int frame_type = -1;
  int sensor_type = -1;
  int status = -1;
  int total_working_time = -1;
  int power_on_time = -1;
  int offset_time = -1;
  int payload = -1;  // a stick frame's payload, or one too short for its fixed fields
  int rtu = -1;      // the RTU frame, handed to invrtu
  int quirk = -1;    // the two zeros some sticks append after the RTU CRC
  int checksum = -1;
  int checksum_status = -1;
  int broken = -1;  // a run that starts like a V5 frame but is none
  int claimed_length = -1;
  int noise = -1;
  int stick_code = -1;  // the stick's code in place of an RTU frame
};

// V5Experts: the expert infos invv5 raises.
struct V5Experts {
  expert_field bad_checksum = EI_INIT;
  expert_field truncated = EI_INIT;
  expert_field length_mismatch = EI_INIT;
  expert_field payload_short = EI_INIT;
  expert_field quirk = EI_INIT;
  expert_field noise = EI_INIT;
  expert_field stick_no_reply = EI_INIT;  // code 05: a timeout on the bus behind the stick
  expert_field stick_refused = EI_INIT;   // code 06: a request to another logger serial
  expert_field stick_code = EI_INIT;      // any other code
};

struct SolarmanV5Protocol {
  int proto = -1;
  V5Fields hf{};
  V5Experts ei{};
  int ett_frame = -1;
  dissector_handle_t handle = nullptr;
};

SolarmanV5Protocol& v5_protocol();
// The name of a control code, for the tree and the Info column.
const char* v5_control_name(std::uint16_t control);

// Registers invv5 (its fields, expert infos, subtree and handle); call at registration.
void register_v5_protocol();
// Attaches invv5 to TCP: a heuristic, and a port preference (empty) for Decode As.
void register_v5_handoff();

}  // namespace pvtap::dissector
