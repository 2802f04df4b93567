// The published SunSpec models (embedded from protocols/maps/sunspec/models.toml) and the
// register map a device's chain makes of them.
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <optional>
#include <set>

#include "pvtap/registers/sunspec.h"
#include "registers/register_entry_rules.h"
#include "registers/register_map_builder.h"

namespace pvtap::embedded {
extern const unsigned char sunspec_models[];
extern const std::size_t sunspec_models_size;
}  // namespace pvtap::embedded

namespace pvtap {
namespace {

using detail::RegisterSpec;

struct Point {
  std::uint16_t offset = 0;
  std::uint16_t size = 1;
  std::string id;
  std::string name;
  std::string type;
  std::string units;
  std::string sf;
  std::vector<detail::SpecValue> symbols;
};

struct ModelDef {
  std::vector<std::uint16_t> ids;
  std::vector<std::string> names;
  std::uint16_t length = 0;
  std::vector<Point> points;
  std::uint16_t repeat_length = 0;  // 0: no repeating group
  std::vector<Point> repeat_points;
};

std::uint16_t size_of_type(std::string_view type) {
  static constexpr std::string_view kTwoWords[] = {"uint32",     "int32",   "acc32", "enum32",
                                                   "bitfield32", "float32", "ipaddr"};
  static constexpr std::string_view kFourWords[] = {"uint64", "int64", "acc64"};
  if (std::find(std::begin(kTwoWords), std::end(kTwoWords), type) != std::end(kTwoWords)) return 2;
  if (std::find(std::begin(kFourWords), std::end(kFourWords), type) != std::end(kFourWords)) {
    return 4;
  }
  return 1;
}

Point read_point(const toml::table& t) {
  Point p;
  p.offset = static_cast<std::uint16_t>(t["offset"].value_or(std::int64_t{0}));
  p.id = t["id"].value_or(std::string{});
  p.name = t["name"].value_or(std::string{});
  p.type = t["type"].value_or(std::string{});
  p.units = t["units"].value_or(std::string{});
  p.sf = t["sf"].value_or(std::string{});
  p.size = static_cast<std::uint16_t>(t["size"].value_or(std::int64_t{size_of_type(p.type)}));
  if (const toml::table* symbols = t["symbols"].as_table()) {
    for (const auto& [key, text] : *symbols) {
      std::int64_t number = 0;
      const std::string_view k = key.str();
      std::from_chars(k.data(), k.data() + k.size(), number);
      p.symbols.push_back({number, text.value_or(std::string{}), 0, 0});
    }
  }
  return p;
}

std::vector<Point> read_points(const toml::node_view<const toml::node> node) {
  std::vector<Point> points;
  if (const toml::array* a = node.as_array()) {
    for (const toml::node& n : *a) {
      if (const toml::table* t = n.as_table()) points.push_back(read_point(*t));
    }
  }
  return points;
}

std::vector<ModelDef> parse_models() {
  const std::string_view text(reinterpret_cast<const char*>(embedded::sunspec_models),
                              embedded::sunspec_models_size);
  std::vector<ModelDef> models;
  toml::table root;
  try {
    root = toml::parse(text, std::string_view("builtin:sunspec/models.toml"));
  } catch (const toml::parse_error&) {
    return models;  // the build's test of the file says why
  }
  const toml::array* entries = root["model"].as_array();
  if (entries == nullptr) return models;
  for (const toml::node& n : *entries) {
    const toml::table* t = n.as_table();
    if (t == nullptr) continue;
    ModelDef m;
    if (const toml::array* ids = (*t)["ids"].as_array()) {
      for (const toml::node& id : *ids) m.ids.push_back(static_cast<std::uint16_t>(id.value_or(0)));
    }
    if (const toml::array* names = (*t)["names"].as_array()) {
      for (const toml::node& name : *names) m.names.push_back(name.value_or(std::string{}));
    }
    m.length = static_cast<std::uint16_t>((*t)["length"].value_or(std::int64_t{0}));
    m.points = read_points((*t)["point"]);
    if (const toml::array* repeats = (*t)["repeat"].as_array(); repeats && !repeats->empty()) {
      if (const toml::table* r = repeats->front().as_table()) {
        m.repeat_length = static_cast<std::uint16_t>((*r)["length"].value_or(std::int64_t{0}));
        m.repeat_points = read_points((*r)["point"]);
      }
    }
    models.push_back(std::move(m));
  }
  return models;
}

const std::vector<ModelDef>& models() {
  static const std::vector<ModelDef> parsed = parse_models();
  return parsed;
}

// The model's layout and its name, or null when pvtap does not know the id.
const ModelDef* find_model(std::uint16_t id, std::string_view* name = nullptr) {
  for (const ModelDef& m : models()) {
    for (std::size_t i = 0; i < m.ids.size(); ++i) {
      if (m.ids[i] != id) continue;
      if (name != nullptr) *name = i < m.names.size() ? m.names[i] : std::string_view{};
      return &m;
    }
  }
  return nullptr;
}

std::string lowercase(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c >= 'A' && c <= 'Z') {
      out += static_cast<char>(c - 'A' + 'a');
    } else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) {
      out += c;
    } else {
      out += '_';
    }
  }
  return out;
}

// SunSpec's unit names as pvtap writes units elsewhere.
std::string unit_of(std::string_view units) {
  if (units == "C") return "°C";
  if (units == "Secs") return "s";
  if (units == "Pct") return "%";
  if (units == "cos()") return "";
  return std::string(units);
}

// How a point's type reads as a map entry; false for a type no entry can hold as one value,
// which then becomes a raw range of its words.
bool set_kind(const Point& p, RegisterSpec& spec) {
  const std::string_view t = p.type;
  spec.words = p.size;
  if (t == "uint16" || t == "count" || t == "acc16") {
    spec.kind = RegisterKind::Number;
    if (t == "uint16") spec.no_value = 0xFFFF;
  } else if (t == "int16" || t == "sunssf") {
    spec.kind = RegisterKind::Number;
    spec.is_signed = true;
    spec.no_value = 0x8000;
  } else if (t == "uint32" || t == "acc32" || t == "int32") {
    spec.kind = RegisterKind::Number;
    spec.pair_rule = PairRule::Binary;
    spec.is_signed = t == "int32";
    if (t != "acc32") spec.no_value = t == "int32" ? 0x80000000LL : 0xFFFFFFFFLL;
  } else if (t == "float32") {
    spec.kind = RegisterKind::Number;
    spec.float32 = true;
  } else if (t == "enum16" || t == "enum32") {
    // A vendor's enum (StVnd) publishes no symbols: its number is all there is.
    spec.kind = p.symbols.empty() ? RegisterKind::Number : RegisterKind::Enum;
    spec.values = p.symbols;
    if (t == "enum32") spec.pair_rule = PairRule::Binary;
    spec.no_value = t == "enum16" ? 0xFFFFLL : 0xFFFFFFFFLL;
  } else if (t == "bitfield16") {
    spec.kind = p.symbols.empty() ? RegisterKind::Raw : RegisterKind::Bits;
    spec.bits = p.symbols;
    spec.no_value = 0xFFFF;
  } else if (t == "bitfield32") {
    spec.kind = RegisterKind::Raw;  // bits entries are one word wide
    spec.no_value = 0xFFFFFFFFLL;
  } else if (t == "string" && p.size <= detail::kMaxTextWords) {
    spec.kind = RegisterKind::Text;
  } else if (p.size <= 2) {
    spec.kind = RegisterKind::Raw;  // pad, ipaddr
  } else {
    return false;
  }
  return true;
}

// MapOfChain: the entries of every model of a chain, with keys unique in the map.
class MapOfChain {
 public:
  std::vector<RegisterSpec> specs;

  void add_header(std::uint16_t base) {
    RegisterSpec s;
    s.address = base;
    s.words = 2;
    s.kind = RegisterKind::Text;
    s.key = "sunspec_marker";
    s.name = "SunSpec marker";
    specs.push_back(std::move(s));
  }

  void add_model_header(std::uint16_t address, const std::string& prefix, const std::string& name) {
    add_number(address, prefix + "_id", name + ": model id");
    add_number(address + 1u, prefix + "_l", name + ": model length");
  }

  void add_points(const std::vector<Point>& points, std::uint32_t first, const std::string& prefix,
                  const std::string& sf_prefix, const std::string& name, std::uint32_t room) {
    for (const Point& p : points) {
      if (p.offset + p.size > room) break;  // the device's L is shorter than published
      RegisterSpec s;
      s.address = first + p.offset;
      s.key = key(prefix + "_" + lowercase(p.id));
      s.name = name + ": " + p.name;
      s.unit = unit_of(p.units);
      if (!p.sf.empty()) {
        s.scale_factor = key_of_sf(sf_prefix + "_" + lowercase(p.sf));
      }
      if (!set_kind(p, s)) {
        s.kind = RegisterKind::Raw;
        s.words = 1;
        s.repeat = p.size;
        s.no_value.reset();
      }
      specs.push_back(std::move(s));
    }
  }

 private:
  void add_number(std::uint32_t address, std::string k, std::string name) {
    RegisterSpec s;
    s.address = address;
    s.key = key(std::move(k));
    s.name = std::move(name);
    specs.push_back(std::move(s));
  }

  // A point id that two points of a model share gets the second one's offset appended.
  std::string key(std::string k) {
    if (k.size() > 60) k.resize(60);
    std::string unique = k;
    for (unsigned n = 2; used_.count(unique) != 0; ++n) unique = k + "_" + std::to_string(n);
    used_.insert(unique);
    return unique;
  }
  static std::string key_of_sf(std::string k) {
    if (k.size() > 60) k.resize(60);
    return k;
  }

  std::set<std::string> used_;
};

void add_model(MapOfChain& out, const SunSpecModel& model, unsigned instance) {
  std::string_view known_name;
  const ModelDef* def = find_model(model.id, &known_name);
  std::string prefix = "m" + std::to_string(model.id);
  if (instance > 1) prefix += "x" + std::to_string(instance);
  std::string name = def != nullptr ? std::string(known_name) : "model " + std::to_string(model.id);
  if (instance > 1) name += " " + std::to_string(instance);
  out.add_model_header(model.address, prefix, name);
  if (def == nullptr) return;  // its words stay unmapped: inference reads them
  const std::uint32_t first = model.address + 2u;
  out.add_points(def->points, first, prefix, prefix, name, model.length);
  if (def->repeat_length == 0 || model.length <= def->length) return;
  // A damaged or hostile length must not make thousands of entries: real devices have a few
  // MPPT modules, never more than kMaxRepeats.
  constexpr unsigned kMaxRepeats = 64;
  const unsigned groups =
      std::min(kMaxRepeats, static_cast<unsigned>(model.length - def->length) / def->repeat_length);
  for (unsigned g = 0; g < groups; ++g) {
    const std::uint32_t at = first + def->length + g * def->repeat_length;
    out.add_points(def->repeat_points, at, prefix + "_" + std::to_string(g + 1), prefix,
                   name + " module " + std::to_string(g + 1), def->repeat_length);
  }
}

}  // namespace

std::string_view sunspec_model_name(std::uint16_t id) {
  std::string_view name;
  return find_model(id, &name) != nullptr ? name : std::string_view{};
}

RegisterMapResult sunspec_register_map(const SunSpecChain& chain, std::string_view source_name) {
  MapOfChain entries;
  entries.add_header(chain.base);
  std::map<std::uint16_t, unsigned> seen;
  for (const SunSpecModel& m : chain.models) add_model(entries, m, ++seen[m.id]);
  if (chain.ended) {
    SunSpecModel end{kSunSpecEndModel, 0, static_cast<std::uint16_t>(chain.next_header())};
    if (chain.next_header() + 1u <= 0xFFFFu)
      entries.add_model_header(end.address, "sunspec_end", "end of the models");
  }
  detail::MapHeaderSpec header;
  header.dialect = kSunSpecDialect;
  header.title = "SunSpec device";
  header.source_name = std::string(source_name);
  RegisterMapBuilder builder(std::move(header));
  for (RegisterSpec& s : entries.specs) builder.add(std::move(s));
  return std::move(builder).build();
}

}  // namespace pvtap
