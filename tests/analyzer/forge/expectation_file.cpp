#include "expectation_file.h"

#include <cstdio>
#include <stdexcept>

namespace pvtap::forge {
namespace {

std::string quoted(const std::string& s) {
  std::string out;
  out += '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

void write_expectation(const std::string& path, const Expected& e) {
  std::string j = "{\"args\":[";
  for (std::size_t i = 0; i < e.args.size(); ++i) {
    if (i > 0) j += ',';
    j += quoted(e.args[i]);
  }
  j += "],\n\"ordered\":";
  j += e.ordered ? "true" : "false";
  j += ",\n\"counts\":{";
  bool first = true;
  for (const auto& [key, value] : e.counts) {
    if (!first) j += ',';
    first = false;
    j += quoted(key);
    j += ':';
    j += std::to_string(value);
  }
  j += "},\n\"frames\":[";
  for (std::size_t i = 0; i < e.frames.size(); ++i) {
    const ExpectedFrame& f = e.frames[i];
    if (i > 0) j += ",\n";
    j += '[';
    j += quoted(f.raw_hex);
    j += f.role == Role::Request ? ",\"request\"," : ",\"response\",";
    j += f.check_ok ? "\"ok\"]" : "\"bad\"]";
  }
  j += "],\n\"values\":[";
  for (std::size_t i = 0; i < e.values.size(); ++i) {
    const ExpectedValue& v = e.values[i];
    char number[64];
    std::snprintf(number, sizeof number, "%.6f", v.value);
    if (i > 0) j += ',';
    j += "{\"station\":";
    j += quoted(v.station);
    j += ",\"register\":";
    j += quoted(v.register_text);
    j += ",\"value\":";
    j += number;
    j += '}';
  }
  j += "]}\n";
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write " + path);
  std::fputs(j.c_str(), f);
  std::fclose(f);
}

}  // namespace pvtap::forge
