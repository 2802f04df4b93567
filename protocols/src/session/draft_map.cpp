#include "pvtap/session/draft_map.h"

#include <array>
#include <charconv>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap {
namespace {

// A comment that stays on its lines: no line break of the evidence escapes the '#'.
void comment(std::string& o, std::string_view text) {
  o += "# ";
  for (const char c : text) o += c == '\n' ? ' ' : c;
  o += '\n';
}

std::string number(double x, int decimals) {
  std::array<char, 64> buf{};
  const auto end =
      std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::fixed, decimals).ptr;
  return {buf.data(), end};
}

// TOML basic string: quotes and backslashes escaped, control characters dropped.
std::string quoted(std::string_view text) {
  std::string o = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) o += c;
  }
  return o + '"';
}

// The entry's kind and width lines for an inferred value.
void kind_lines(std::string& o, const InferredValue& v) {
  switch (v.kind) {
    case InferredKind::U16:
      o += "kind = \"number\"\n";
      return;
    case InferredKind::S16:
      o += "kind = \"number\"\nsigned = true\n";
      return;
    case InferredKind::U32:
    case InferredKind::S32:
      o += "kind = \"number\"\nwords = 2\ncombine = \"binary\"\n";
      if (v.kind == InferredKind::S32) o += "signed = true\n";
      break;
    case InferredKind::Float32:
      o += "kind = \"float32\"\n";
      break;
    case InferredKind::Text:
      o += "kind = \"text\"\nwords = " + std::to_string(v.words) + "\n";
      return;
    case InferredKind::Bits:
      // The flags seen to change, unnamed until their meaning is known.
      o += "kind = \"bits\"\n[register.bits]\n";
      for (unsigned b = 0; b < 16; ++b) {
        if ((v.changed_bits >> b & 1u) != 0) {
          o += std::to_string(b) + " = \"bit " + std::to_string(b) + "\"\n";
        }
      }
      return;
    case InferredKind::Unused:
      o += "kind = \"raw\"\n";
      return;
  }
  if (v.order == WordOrder::LowFirst) o += "word_order = \"low_first\"\n";
}

std::string value_name(const InferredBlock& b, const InferredValue& v, std::uint16_t address) {
  std::string name(table_name(b.table));
  name += ' ';
  name += format_register_address(b.dialect, address).view();
  name += " (";
  name += to_string(v.kind);
  if (v.counter) name += " counter";
  if (v.kind == InferredKind::Unused) name += ", fill";
  return name + ')';
}

// The chain a SunSpec station showed, so that a capture that starts after the master's scan
// decodes its models too.
void sunspec_table(std::string& o, const SunSpecChain& chain) {
  o += "\n";
  comment(o, "The SunSpec model chain the station showed: with it, its models' points are named");
  comment(o, "from the published models, even in a capture that starts after the master's scan.");
  o += "[sunspec]\nbase = ";
  o += std::to_string(chain.base);
  o += "\nmodels = [";
  for (std::size_t i = 0; i < chain.models.size(); ++i) {
    o += i > 0 ? ", [" : "[";
    o += std::to_string(chain.models[i].id);
    o += ", ";
    o += std::to_string(chain.models[i].length);
    o += ']';
  }
  o += "]\n";
  if (chain.ended) o += "ended = true\n";
}

}  // namespace

std::string draft_register_map(const StationSummary& station, std::string_view source) {
  if (station.inferred.empty() && !station.sunspec) return {};
  const Dialect dialect = station.sunspec ? kSunSpecDialect : station.inferred.front().dialect;
  std::string o;
  comment(o, "Draft register map of station " + std::to_string(station.station) +
                 ", written by pvtap audit --draft-map from " + std::string(source) + ".");
  comment(o,
          "Every entry is a guess from the values the capture showed: its type, word order "
          "and width are inferred,");
  comment(o,
          "with the evidence above it. Rename the keys and names, add scales and units, "
          "and check it against");
  comment(o, "the maker's register table. Load it with  pvtap audit --map " +
                 std::to_string(station.station) + "=FILE ...");
  if (!station.device.empty()) comment(o, "The device names itself " + station.device.text());
  o += "\ndialect = \"";
  o += to_string(dialect);
  o += "\"\ntitle = ";
  o += quoted("station " + std::to_string(station.station) + " (draft)");
  // An inverter's draft lies over its dialect's built-in map, whose registers stay named; a
  // plain Modbus device has no built-in map to lie over.
  o += builtin_register_map(dialect).empty() ? "\n" : "\nmode = \"extend\"\n";
  if (station.sunspec) sunspec_table(o, *station.sunspec);
  // A map does not tell holding and input registers apart: an address is written once.
  std::vector<bool> taken(0x10000, false);
  for (const InferredBlock& b : station.inferred) {
    if (b.dialect != dialect) continue;  // a station speaks one dialect; a map has one
    o += "\n";
    comment(o, std::string(table_name(b.table)) + "s at " +
                   std::string(format_register_address(b.dialect, b.start).view()) + ", " +
                   std::to_string(b.count) + " words, " + std::to_string(b.replies) + " replies");
    const unsigned step = address_step(b.dialect);
    for (const InferredValue& v : b.values) {
      const auto address = static_cast<std::uint16_t>(b.start + v.offset * step);
      bool free = true;
      for (unsigned k = 0; k < v.words; ++k) free = free && !taken[(address + k * step) & 0xFFFFu];
      const std::string where(format_register_address(b.dialect, address).view());
      if (!free) {
        comment(o, where + " " + std::string(to_string(v.kind)) +
                       ": left out, an entry above covers this address");
        continue;
      }
      for (unsigned k = 0; k < v.words; ++k) taken[(address + k * step) & 0xFFFFu] = true;
      o += '\n';
      comment(o, v.evidence + " (confidence " + number(v.confidence * 100, 0) + " %)");
      if (v.kind != InferredKind::Text && v.kind != InferredKind::Unused) {
        const int decimals = v.kind == InferredKind::Float32 ? 3 : 0;
        comment(o, "range " + number(v.min, decimals) + ".." + number(v.max, decimals) + ", last " +
                       number(v.last, decimals));
      }
      if (v.kind == InferredKind::Text) comment(o, "last text " + quoted(v.text));
      if (!v.hint.empty()) comment(o, "hint: " + v.hint);
      o += "[[register]]\naddress = ";
      o += where;
      o += "\nkey = ";
      o += quoted(unmapped_key(b.table, address).view());
      o += "\nname = ";
      o += quoted(value_name(b, v, address));
      o += '\n';
      kind_lines(o, v);
    }
  }
  return o;
}

}  // namespace pvtap
