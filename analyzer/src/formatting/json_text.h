// JSON members and string literals appended to an output buffer (jsonl lines, the summary).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace pvtap::analyzer {

// A JSON string literal with quotes and escapes.
void append_json_string(std::string& out, std::string_view text);

// The next member's name of a JSON object already open: `,"name":`.
void append_json_key(std::string& out, std::string_view name);

// `,"name":123`.
void append_json_count(std::string& out, std::string_view name, std::uint64_t value);

}  // namespace pvtap::analyzer
