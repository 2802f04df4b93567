// Turns the data words of frames into named register values, driven by the register maps.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_map.h"
#include "pvtap/registers/sunspec.h"

namespace pvtap {

// GslIdReading: how the GSL seed's written IDs go on the wire.
enum class GslIdReading : std::uint8_t {
  Decimal,  // ID 1050 is wire address 0x041A (the reference's decision)
  Hex,      // ID 1050 is wire address 0x1050
};

// DecoderOptions: the choices the reference leaves to the user.
struct DecoderOptions {
  GslIdReading gsl_ids = GslIdReading::Decimal;
  // Rule for 2-word entries whose map says combine = "option" (the GSL pairs).
  // FromOptions here means Binary.
  PairRule pair_rule = PairRule::Binary;
  // Learn the SunSpec model chain of a station without a map from the replies decoded, and
  // decode its registers by model.
  bool sunspec = true;
};

// The wire address of a written register address, and back. Only GSL IDs read as hex
// differ; a wire address with a hex digit above 9 has no written form then.
std::optional<std::uint16_t> wire_address_of(Dialect d, std::uint16_t written, GslIdReading ids);
std::optional<std::uint16_t> written_address_of(Dialect d, std::uint16_t wire, GslIdReading ids);

// ValueOrigin: where in the traffic a value was found.
enum class ValueOrigin : std::uint8_t {
  ReadReply,     // data of a read reply
  WriteRequest,  // value(s) a master writes (Hybrid 0x18, GSL 0x06, GSL 0x10)
  WriteReply,    // the inverter's echo of a write (Hybrid 0x18, GSL 0x06)
  DeviceHeader,  // the Hybrid device number at the start of every reply
};

// ValueWarning: a doubt about one value (bit flags of DecodedValue::warnings).
enum class ValueWarning : std::uint16_t {
  NotInMap = 1u << 0,          // no map entry covers the word; raw holds it
  Incomplete = 1u << 1,        // part of a multi-word value is outside the frame
  LowPartOver9999 = 1u << 2,   // decimal pair with a low part above 9999
  UnknownEnumValue = 1u << 3,  // the value has no text in the map
  UnnamedBitSet = 1u << 4,     // a set bit has no name in the map
  InvalidBcd = 1u << 5,        // a BCD digit above 9
  InvalidDate = 1u << 6,       // BCD month outside 1..12
  NonPrintableText = 1u << 7,  // text with characters outside printable ASCII (shown as '?')
  NoWrittenAddress = 1u << 8,  // GSL hex IDs: the wire address has a digit above 9
  NotFinite = 1u << 9,         // a float32 value that is NaN or infinite (value holds it)
  NoValue = 1u << 10,          // the raw value is the map's no_value mark (SunSpec 0xFFFF, 0x8000)
  NoScaleFactor = 1u << 11,    // its scale factor register was not read (or has no value):
                               // value is raw * scale, without the factor
};

// BcdParts: the parts of a BCD value (phase+capacity: phases, capacity in raw units;
// year-month: year, month; plain BCD: the decimal number, 0).
struct BcdParts {
  std::uint16_t first = 0;
  std::uint16_t second = 0;
};

// SetBits: the set bits of a bits value with their names (empty for unnamed bits).
class SetBits {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = BitName;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = BitName;

    iterator() = default;
    iterator(const RegisterDef* def, std::uint32_t mask) : def_(def), mask_(mask) {}
    BitName operator*() const {
      const auto index = static_cast<std::uint8_t>(std::countr_zero(mask_));
      return {index, def_ != nullptr ? def_->bit_name(index) : std::string_view{}};
    }
    iterator& operator++() {
      mask_ &= mask_ - 1;  // clears the lowest set bit
      return *this;
    }
    iterator operator++(int) {
      iterator before = *this;
      ++*this;
      return before;
    }
    bool operator==(const iterator& o) const { return mask_ == o.mask_; }

   private:
    const RegisterDef* def_ = nullptr;
    std::uint32_t mask_ = 0;
  };
  SetBits(const RegisterDef* def, std::uint32_t mask) : def_(def), mask_(mask) {}
  iterator begin() const { return {def_, mask_}; }
  iterator end() const { return {def_, 0}; }

 private:
  const RegisterDef* def_;
  std::uint32_t mask_;
};

// DecodedValue: one register value of a frame. Trivially copyable; its views point into the
// register map, so they live as long as the map.
struct DecodedValue {
  static constexpr std::size_t kTextCapacity = 32;

  // Provided, so that a new value (one per decoded register) is built member by member
  // instead of being zeroed whole first (value-initialization of an implicit constructor).
  DecodedValue() noexcept {}  // NOLINT(modernize-use-equals-default)

  const RegisterDef* def = nullptr;  // null when no map entry covers the word
  std::uint16_t address = 0;         // written address of the value's first word
  std::uint16_t wire_address = 0;    // wire address of the first word present
  std::uint16_t instance = 0;        // which register of a range entry
  std::uint8_t words_present = 0;
  ValueOrigin origin = ValueOrigin::ReadReply;
  std::uint16_t warnings = 0;   // ValueWarning bits
  std::uint32_t raw = 0;        // the words combined (pair rule applied); 0 if incomplete
  std::int32_t signed_raw = 0;  // raw read as two's complement when the entry is signed
  double value = 0.0;           // scaled; not computed when incomplete
  std::string_view enum_text;   // enum and device number: the text of the value
  BcdParts bcd;                 // BCD kinds
  DeviceNumber device;          // device number kind
  std::array<char, kTextCapacity> text_chars{};
  std::uint8_t text_length = 0;
  // Digits after the point its scale factor gives (10^-3: 3), shown when the map's are fewer.
  std::uint8_t scale_decimals = 0;

  bool complete() const { return !has(ValueWarning::Incomplete); }
  bool has(ValueWarning w) const { return (warnings & static_cast<std::uint16_t>(w)) != 0; }
  void add(ValueWarning w) {
    warnings = static_cast<std::uint16_t>(warnings | static_cast<std::uint16_t>(w));
  }
  std::string_view key() const { return def ? def->key : std::string_view{}; }
  std::string_view name() const { return def ? def->name : std::string_view{}; }
  std::string_view unit() const { return def ? def->unit : std::string_view{}; }
  std::string_view text() const { return {text_chars.data(), text_length}; }
  SetBits set_bits() const {
    const bool bits = def != nullptr && def->kind == RegisterKind::Bits && complete();
    return {def, bits ? raw : 0u};
  }
};

// DecodeStatus: whether a frame's register words could be placed.
enum class DecodeStatus : std::uint8_t {
  Decoded,         // values were appended
  NoRegisterData,  // the frame carries no register values (read request, exception, ...)
  StartUnknown,    // register words whose start address is unknown: nothing was placed
};

// DecodeReport: what decode() did with one frame.
struct DecodeReport {
  DecodeStatus status = DecodeStatus::NoRegisterData;
  ValueOrigin origin = ValueOrigin::ReadReply;
  std::uint16_t start = 0;        // wire address of the first word
  bool start_assumed = false;     // Hybrid reply without its request: the seed's default start
  bool request_unusable = false;  // a request was given but does not match this reply
  bool count_mismatch = false;    // the reply's word count differs from the request's count
  std::size_t first = 0;          // the appended values are out[first, first + count)
  std::size_t count = 0;
};

// Why the status is what it is, in words ("GSL read reply without its request: ...").
std::string_view describe(const DecodeReport& report);

// RegisterDecoder: one table-driven decoder for every dialect. Holds one map per dialect
// (the built-in ones unless replaced, each parsed the first time a frame of its dialect asks
// for it); decoding does not allocate except to grow `out`.
class RegisterDecoder {
 public:
  explicit RegisterDecoder(DecoderOptions options = {});

  void use_map(const RegisterMap& map);  // replaces the map of map.dialect()
  // Replaces the map of `d` (an empty map has no dialect of its own).
  void use_map(Dialect d, const RegisterMap& map) { own_maps_[static_cast<std::size_t>(d)] = map; }
  const RegisterMap& map(Dialect d) const {
    const std::optional<RegisterMap>& own = own_maps_[static_cast<std::size_t>(d)];
    return own ? *own : builtin_register_map(d);
  }
  // Decodes the GSL and plain Modbus frames of `station` with `map` (a meter's own map on a
  // bus of inverters), whatever the dialect; its values are addressed in map.dialect().
  void use_station_map(std::uint8_t station, const RegisterMap& map);
  // A station's own map: the one given, or else the one its SunSpec chain made (learned).
  const RegisterMap* station_map(std::uint8_t station) const {
    if (const std::uint8_t i = station_map_of_[station]; i != 0) return &station_maps_[i - 1];
    return learned_->map(station);
  }
  const DecoderOptions& options() const { return options_; }

  // Learns what a read reply shows of its station's SunSpec chain (decode() does it too). The
  // learned state is shared by copies of this decoder; forget_learned() clears it, for a new
  // capture. Single-threaded, as decoding is.
  void learn(const Frame& reply, const Frame* request) const;
  void forget_learned() const { learned_->clear(); }
  // The SunSpec chain learned for a station; null when it showed none.
  const SunSpecChain* sunspec_chain(std::uint8_t station) const { return learned_->chain(station); }

  // Appends the register values a frame carries. `request` is the matching request of a
  // reply, or null; Hybrid and GSL read replies need it for their start address.
  DecodeReport decode(const Frame& frame, const Frame* request,
                      std::vector<DecodedValue>& out) const;

  // Appends the values of `words` read or written at a known wire start address.
  std::size_t decode_block(Dialect d, std::uint16_t wire_start,
                           std::span<const std::uint16_t> words, ValueOrigin origin,
                           std::vector<DecodedValue>& out) const;

  // The Hybrid device number of a reply header (type code text from table H5).
  DecodedValue decode_device_number(const DeviceNumber& device) const;

  // For each dialect's value rules (protocols/src/dialects): appends the values of `words`
  // at wire address `start` by `d`'s map (or `map`), and applies a station's scale factors.
  DecodeReport place(Dialect d, std::uint16_t start, std::span<const std::uint16_t> words,
                     ValueOrigin origin, std::vector<DecodedValue>& out) const;
  DecodeReport place(const RegisterMap& map, Dialect d, std::uint16_t start,
                     std::span<const std::uint16_t> words, ValueOrigin origin,
                     std::vector<DecodedValue>& out) const;
  void apply_scale_factors(const RegisterMap& m, std::uint8_t station, const DecodeReport& report,
                           std::vector<DecodedValue>& out) const;

 private:
  std::array<std::optional<RegisterMap>, kDialectCount> own_maps_;  // replacing the built-in
  std::shared_ptr<SunSpecStations> learned_;  // what the traffic taught; not part of the value
  std::vector<RegisterMap> station_maps_;
  std::array<std::uint8_t, 256> station_map_of_{};  // index + 1 into station_maps_; 0: none
  DecoderOptions options_;
};

}  // namespace pvtap
