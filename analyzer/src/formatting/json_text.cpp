#include "formatting/json_text.h"

#include "formatting/number_text.h"

namespace pvtap::analyzer {
namespace {

constexpr char kHexDigits[] = "0123456789abcdef";

}  // namespace

void append_json_key(std::string& out, std::string_view name) {
  out += ",\"";
  out += name;
  out += "\":";
}

void append_json_count(std::string& out, std::string_view name, std::uint64_t value) {
  append_json_key(out, name);
  append_uint(out, value);
}

void append_json_string(std::string& out, std::string_view text) {
  out += '"';
  // Names and units rarely need escapes: copy runs of plain characters at once.
  std::size_t run = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(text.data() + run, i - run);
    run = i + 1;
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        out += "\\u00";
        out += kHexDigits[c >> 4];
        out += kHexDigits[c & 0xF];
    }
  }
  out.append(text.data() + run, text.size() - run);
  out += '"';
}

}  // namespace pvtap::analyzer
