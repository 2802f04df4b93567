// The dissector named "pvtap": records of link type 252 (exported PDU) written by the analyzer.
#pragma once

namespace pvtap::dissector {

// Registers the "pvtap" protocol and dissector; call at protocol registration.
void register_record_dissector();

}  // namespace pvtap::dissector
