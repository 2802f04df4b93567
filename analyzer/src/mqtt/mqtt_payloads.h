// Payloads of the value, state and station-event topics. The value objects inside them are
// those of --format jsonl (frame_findings.h, value_json_cache.h), so that a consumer reads
// one shape whichever way it gets pvtap's output.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "pvtap/registers/register_decoder.h"

namespace pvtap::analyzer {

class ValueJsonCache;
struct StationState;

// The payload of a value topic: the number as in jsonl's "value" ("52.3", enum and bits as
// their raw number), text registers as plain text (no quotes).
void append_value_payload(std::string& out, const DecodedValue& v);

// {"ts":...,"station":1,"dialect":"gsl","values":{"battery_voltage":{jsonl value},...},
//  "bus":"..."}: ts is the time of the station's newest reply; bus only when named.
void append_state_json(std::string& out, const StationState& s, std::string_view bus,
                       ValueJsonCache& values);

// A station that stopped answering or answers again, in the shape of jsonl's events:
// {"type":"station_offline","ts":...,"station":1,"last_reply_ts":...,"bus":"..."}.
void append_station_event_json(std::string& out, bool online, double now, const StationState& s,
                               std::string_view bus);

}  // namespace pvtap::analyzer
