#include "registers/map_node_reader.h"

#include <charconv>
#include <optional>

namespace pvtap::detail {
namespace {

// "12" or "0x1F": the keys of value and bit tables.
std::optional<std::int64_t> parse_number_key(std::string_view text) {
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    base = 16;
  }
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

}  // namespace

const toml::value<std::string>* MapNodeReader::expect_string(const toml::node& node,
                                                             std::string_view what) {
  const auto* s = node.as_string();
  if (s == nullptr) fail(node.source(), std::string(what) + " must be a string");
  return s;
}

const toml::value<std::int64_t>* MapNodeReader::expect_integer(const toml::node& node,
                                                               std::string_view what) {
  const auto* i = node.as_integer();
  if (i == nullptr) fail(node.source(), std::string(what) + " must be an integer");
  return i;
}

std::vector<SpecValue> MapNodeReader::read_number_table(const toml::table& table,
                                                        std::string_view what) {
  std::vector<SpecValue> out;
  for (const auto& [key, node] : table) {
    const auto number = parse_number_key(key.str());
    if (!number) {
      fail(key.source(), std::string(what) + " '" + std::string(key.str()) +
                             "' is not a number (write 3 or 0x1F)");
      continue;
    }
    const auto* text = expect_string(node, std::string(what) + " text");
    if (text == nullptr) continue;
    out.push_back(SpecValue{*number, text->get(), line_of(key.source()), column_of(key.source())});
  }
  return out;
}

}  // namespace pvtap::detail
