// Register maps: what each register of a dialect means, loaded from TOML files.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/result.h"

namespace pvtap {

// RegisterKind: how the words of a register turn into a value.
enum class RegisterKind : std::uint8_t {
  Number,            // scaled integer of 1 or 2 words
  Raw,               // opaque or undocumented words, shown in hex
  Enum,              // integer with a text per known value
  Bits,              // up to 16 flags, each with a name
  Text,              // ASCII characters, two per word, high byte first
  Bcd,               // four BCD digits read as a decimal number
  BcdPhaseCapacity,  // BCD: first digit = phases, last three digits = capacity
  BcdYearMonth,      // BCD YYMM, year 20YY
  DeviceNumber,      // Hybrid device number: type code byte + 24-bit serial
};

// The kind's spelling in map files ("number", "bcd_year_month", ...).
std::string_view to_string(RegisterKind kind);
std::optional<RegisterKind> register_kind_from_string(std::string_view text);

// PairRule: how the two words of a 32-bit value combine (high word first on the wire).
enum class PairRule : std::uint8_t {
  Binary,       // high * 65536 + low
  Decimal,      // high * 10000 + low; the low part runs 0..9999
  FromOptions,  // left to DecoderOptions::pair_rule (the reference leaves it open)
};

// WordOrder: which word of a 2-word value comes first on the wire. Most devices send the high
// word first; some energy meters swap the two.
enum class WordOrder : std::uint8_t { HighFirst, LowFirst };

// NumberEncoding: how the words of a number register hold its value. A float32 register is a
// number to everything that shows or charts it; only its words are read differently.
enum class NumberEncoding : std::uint8_t {
  Integer,  // the words combined by the pair rule, signed if asked
  Float32,  // IEEE-754 single precision over two words (map files: kind = "float32")
};

// MapMode: whether a map stands alone or is laid over the built-in map of its dialect.
enum class MapMode : std::uint8_t { Replace, Extend };

// EnumText: one known value of an enumerated register.
struct EnumText {
  std::uint32_t value = 0;
  std::string_view text;
};

// BitName: the name of one flag of a bits register.
struct BitName {
  std::uint8_t index = 0;
  std::string_view name;
};

// RegisterDef: one register of a map, or a run of like one-word registers (a range).
// Its string views point into the RegisterMap that owns it and live as long as any copy
// of that map.
struct RegisterDef {
  std::uint16_t address = 0;  // as written in the map; GSL: the ID as printed (1050)
  std::uint16_t words = 1;    // width of one value in 16-bit words
  std::uint16_t repeat = 1;   // number of like registers; more than 1 for a range entry
  RegisterKind kind = RegisterKind::Number;
  bool is_signed = false;
  PairRule pair_rule = PairRule::FromOptions;         // used when words == 2
  WordOrder word_order = WordOrder::HighFirst;        // used when words == 2
  NumberEncoding encoding = NumberEncoding::Integer;  // kind number only
  std::uint8_t decimals = 0;                          // digits shown after the point
  double scale = 1.0;                                 // value = raw * scale
  std::string_view key;                               // stable field key, [a-z][a-z0-9_]*
  std::string_view name;                              // human name
  std::string_view unit;                              // of the scaled value; may be empty
  std::span<const EnumText> values;                   // sorted by value
  std::span<const BitName> bits;                      // sorted by index
  // The key of a one-word signed register whose value e scales this one by 10^e (SunSpec's
  // scale factors); empty when the scale is fixed. Its written address is scale_factor_address.
  std::string_view scale_factor;
  std::uint16_t scale_factor_address = 0;
  // The raw value a device sends for "no value" (SunSpec: 0xFFFF, 0x8000), when it has one.
  std::uint32_t no_value = 0;
  bool has_no_value = false;
  bool is_scale_factor = false;  // another entry names this one as its scale_factor
  std::uint32_t line = 0;        // where the entry starts in its map file

  bool is_range() const { return repeat > 1; }
  bool is_float() const { return encoding == NumberEncoding::Float32; }
  bool has_scale_factor() const { return !scale_factor.empty(); }
  std::string_view value_text(std::uint32_t value) const;  // empty when not listed
  std::string_view bit_name(unsigned index) const;         // empty when not listed
};

// CoilDef: a named coil ([[coil]]) or discrete input ([[discrete_input]]) of a map: one bit
// at one address. Its views live as long as the map, like a RegisterDef's.
struct CoilDef {
  std::uint16_t address = 0;
  std::string_view key;   // stable field key, unique among all entries of the map
  std::string_view name;  // human name
  std::uint32_t line = 0;
};

// RegisterSlot: the entry that covers one address, and which of its words that is.
struct RegisterSlot {
  const RegisterDef* def = nullptr;
  std::uint16_t word = 0;           // word of the value, 0 = first (high) word
  std::uint16_t instance = 0;       // which register of a range, 0 otherwise
  std::uint16_t value_address = 0;  // address of the value's first word
};

// Addresses of consecutive words of one read: 2 apart in the ASCII dialect, else 1 (each
// dialect's record says).
unsigned address_step(Dialect d);

// RegisterAddressText: an address as the reference writes it, in a fixed buffer.
struct RegisterAddressText {
  std::array<char, 8> chars{};
  std::uint8_t length = 0;
  std::string_view view() const { return {chars.data(), length}; }
};

// "0x1006" (Hybrid), "0x0020" (ASCII, four hex digits), "1056" (GSL, the written ID).
RegisterAddressText format_register_address(Dialect d, std::uint16_t written_address);
// "0x1050": a wire address, four hex digits, whatever the dialect.
RegisterAddressText format_wire_address(std::uint16_t wire_address);

// RegisterMap: the registers of one dialect, sorted by address. Cheap to copy (shared).
class RegisterMap {
 public:
  RegisterMap() = default;  // empty map of no particular dialect

  Dialect dialect() const;
  MapMode mode() const;
  std::string_view title() const;
  std::string_view source_name() const;
  std::span<const RegisterDef> registers() const;
  std::size_t size() const { return registers().size(); }
  bool empty() const { return registers().empty(); }

  const RegisterDef* find_key(std::string_view key) const;
  const RegisterDef* find_address(std::uint16_t address) const;  // the entry starting there
  // The entry covering a written address; a single entry wins over a range containing it.
  std::optional<RegisterSlot> locate(std::uint16_t address) const;
  const RegisterDef* find_kind(RegisterKind kind) const;  // the first entry of a kind
  bool has_scale_factors() const;  // an entry takes its scale from another's value

  // Named coils and discrete inputs (Modbus-family maps), each sorted by address.
  std::span<const CoilDef> coils() const;
  std::span<const CoilDef> discrete_inputs() const;
  const CoilDef* find_coil(std::uint16_t address) const;
  const CoilDef* find_discrete_input(std::uint16_t address) const;
  // The name of the coil or input at an address; empty when the map does not name it.
  std::string_view coil_name(std::uint16_t address) const;
  std::string_view input_name(std::uint16_t address) const;

  struct Data;  // defined by the library

 private:
  friend class RegisterMapBuilder;
  explicit RegisterMap(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

// MapDiagnostic: one problem of a map file, with where it is.
struct MapDiagnostic {
  std::string source;
  std::uint32_t line = 0;  // 1-based; 0 when the problem has no place in the file
  std::uint32_t column = 0;
  std::string message;
  std::string to_string() const;  // "hybrid.toml:42:3: message"
};

// One diagnostic per line.
std::string diagnostic_text(const std::vector<MapDiagnostic>& problems);

// RegisterMapResult: a loaded map, or the problems that prevented it (sorted by line).
using RegisterMapResult = Result<RegisterMap, std::vector<MapDiagnostic>>;

// Parses a map file's text; `source_name` names it in diagnostics. The core reads no files:
// the caller reads the file and hands its text here.
RegisterMapResult load_register_map(std::string_view toml_text, std::string_view source_name);

// The built-in map of a dialect, parsed once from the copy embedded in the library.
// Empty if the embedded copy does not load (load_builtin_register_map says why).
const RegisterMap& builtin_register_map(Dialect d);
RegisterMapResult load_builtin_register_map(Dialect d);

// Lays `overlay` over `base`: an overlay entry replaces every base entry that shares an
// address or the key with it; other entries of both are kept. Both must be of one dialect.
RegisterMapResult merge_register_maps(const RegisterMap& base, const RegisterMap& overlay);

// The map a user file asks for: itself (mode replace) or laid over the built-in map of its
// dialect (mode extend).
RegisterMapResult resolve_user_register_map(const RegisterMap& user);

// How user maps stack, the same in pvtap and the Wireshark plugin: files are taken in order
// (the plugin: by file name; pvtap: --map as given); a replace map stands alone, an extend map
// is laid over the map in effect so far (its dialect's built-in one, or what the files before
// it made), so several files may extend one dialect.
RegisterMapResult stack_register_map(const RegisterMap& in_effect, const RegisterMap& user);

}  // namespace pvtap
