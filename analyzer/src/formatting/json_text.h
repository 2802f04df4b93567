// JSON string literals appended to an output buffer: the escaping under JsonWriter.
#pragma once

#include <string>
#include <string_view>

namespace pvtap::analyzer {

// A JSON string literal with quotes and escapes.
void append_json_string(std::string& out, std::string_view text);

}  // namespace pvtap::analyzer
