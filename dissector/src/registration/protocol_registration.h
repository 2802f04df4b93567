// The plugin's two registration steps, called by Wireshark through plugin_register().
#pragma once

namespace pvtap::dissector {

// Registers invascii, invrtu and pvtap with their fields, preferences and statistics.
void register_protocols();

// Attaches them to TCP, UDP and RTAC serial.
void register_handoffs();

}  // namespace pvtap::dissector
