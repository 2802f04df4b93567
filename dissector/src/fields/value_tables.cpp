#include "fields/value_tables.h"

#include <string>
#include <vector>

#include "pvtap/codec/function_codes.h"

namespace pvtap::dissector {

// Registration data lives as long as Wireshark, so the tables are never freed.
const value_string* persist_value_strings(
    const std::vector<std::pair<std::uint32_t, std::string>>& entries) {
  auto* table = g_new0(value_string, entries.size() + 1);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    table[i].value = entries[i].first;
    table[i].strptr = g_strndup(entries[i].second.data(), entries[i].second.size());
  }
  return table;
}

namespace {

std::string function_text(Dialect d, std::uint8_t f) {
  if (modbus_family(d) && fc::is_gsl_exception(f)) {
    const auto base = static_cast<std::uint8_t>(f & ~fc::kExceptionFlag);
    return "exception (" + std::string(fc::function_name(d, base)) + ")";
  }
  return std::string(fc::function_name(d, f));
}

}  // namespace

const value_string* dialect_names() {
  static const value_string* names = [] {
    std::vector<std::pair<std::uint32_t, std::string>> entries;
    for (const Dialect d : kAllDialects) {
      entries.emplace_back(static_cast<std::uint32_t>(d), std::string(dialect_title(d)));
    }
    return persist_value_strings(entries);
  }();
  return names;
}

const value_string* role_names() {
  static const value_string names[] = {
      {static_cast<guint32>(Role::Request), "request"},
      {static_cast<guint32>(Role::Response), "response"},
      {0, nullptr},
  };
  return names;
}

const value_string* function_names(DialectSet dialects) {
  std::vector<std::pair<std::uint32_t, std::string>> entries;
  for (unsigned f = 0; f <= 0xFF; ++f) {
    const auto code = static_cast<std::uint8_t>(f);
    if (dialects.contains(Dialect::Ascii) && code == fc::kAsciiRead) {
      entries.emplace_back(f, function_text(Dialect::Ascii, code));
    }
    const auto rtu = fc::rtu_dialect_of(code);
    if (rtu && dialects.contains(*rtu)) entries.emplace_back(f, function_text(*rtu, code));
  }
  return persist_value_strings(entries);
}

const value_string* exception_names() {
  static const value_string* names = [] {
    std::vector<std::pair<std::uint32_t, std::string>> entries;
    // The seed's texts for the codes GSL uses, Modbus's for the others.
    for (const unsigned code : {0x01u, 0x02u, 0x03u, 0x04u, 0x05u, 0x06u, 0x08u, 0x0Au, 0x0Bu}) {
      const bool gsl = code == 0x01 || code == 0x02 || code == 0x03 || code == 0x06;
      entries.emplace_back(
          code,
          std::string(gsl ? fc::exception_name(static_cast<std::uint8_t>(code))
                          : fc::exception_name(Dialect::Modbus, static_cast<std::uint8_t>(code))));
    }
    return persist_value_strings(entries);
  }();
  return names;
}

const value_string* register_value_names(const RegisterDef& def) {
  if (def.values.empty()) return nullptr;
  std::vector<std::pair<std::uint32_t, std::string>> entries;
  for (const EnumText& e : def.values) entries.emplace_back(e.value, std::string(e.text));
  return persist_value_strings(entries);
}

}  // namespace pvtap::dissector
