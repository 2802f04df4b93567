// What a plain Modbus frame carries besides register values: coil and input bits, diagnostics,
// and what a device says of itself, in words and as JSON.
#pragma once

#include <string>

#include "formatting/json_writer.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// "  coils 19-37: 12 on (19 21 22 ...)", "  diagnostics: return query data", ...; nothing for
// a frame that carries none of these (checked first, at the cost of a switch).
void append_contents_text(std::string& out, const SessionFrame& f);

// Members of the frame's object: "coils":{"start":19,"count":19,"on":[19,21]},
// "diagnostics":{...}, "device":{...}, "server_id":{...}; none for a frame that carries none.
void write_contents_json(JsonWriter& w, const SessionFrame& f);

}  // namespace pvtap::analyzer
