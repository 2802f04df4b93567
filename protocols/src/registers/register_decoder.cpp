#include "pvtap/registers/register_decoder.h"

#include <algorithm>
#include <cmath>

#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"
#include "registers/register_entry_rules.h"
#include "registers/register_value_conversion.h"
#include "registers/value_placement.h"

namespace pvtap {
namespace {

// One block of words at a known wire start, being turned into values.
struct Block {
  Dialect dialect;
  const RegisterMap& map;
  const DecoderOptions& options;
  std::uint16_t wire_start;
  std::span<const std::uint16_t> words;
  ValueOrigin origin;
  unsigned step;
  // Only IDs read as hex (GSL's) map addresses; for every other block the wire address is the
  // written one, without a call per word.
  bool identity;

  std::uint32_t wire_of(std::size_t index) const {
    return wire_start + static_cast<std::uint32_t>(index) * step;
  }
  std::optional<std::uint16_t> written_of(std::uint16_t wire) const {
    return identity ? wire : written_address_of(dialect, wire, options.gsl_ids);
  }
  // Whether the word of written address `written` is on the wire at `wire`. A bool, not the
  // optional wire address: an optional built and read back per word stalled the store
  // forwarding (two narrow stores read as one word), 45 % of place()'s samples in perf.
  bool written_at(std::uint16_t written, std::uint32_t wire) const {
    if (identity) return written == wire;
    const std::optional<std::uint16_t> at = wire_address_of(dialect, written, options.gsl_ids);
    return at && *at == wire;
  }
};

// A word no entry covers is still reported, so that nothing on the wire goes unseen.
void append_unmapped(const Block& b, std::size_t index, std::optional<std::uint16_t> written,
                     std::vector<DecodedValue>& out) {
  DecodedValue& v = out.emplace_back();
  v.origin = b.origin;
  v.wire_address = static_cast<std::uint16_t>(b.wire_of(index));
  v.address = written.value_or(v.wire_address);
  v.words_present = 1;
  v.raw = b.words[index];
  v.signed_raw = static_cast<std::int32_t>(v.raw);
  v.value = v.raw;
  v.add(ValueWarning::NotInMap);
  if (!written) v.add(ValueWarning::NoWrittenAddress);
}

// Appends the value whose word is at `index`; returns how many words of the block it used.
std::size_t append_value(const Block& b, std::size_t index, std::vector<DecodedValue>& out) {
  const std::uint32_t wire = b.wire_of(index);
  std::optional<std::uint16_t> written;
  if (wire <= 0xFFFF) {
    written = b.written_of(static_cast<std::uint16_t>(wire));
  }
  const std::optional<RegisterSlot> slot = written ? b.map.locate(*written) : std::nullopt;
  if (!slot) {
    append_unmapped(b, index, written, out);
    return 1;
  }
  const RegisterDef& def = *slot->def;
  DecodedValue& v = out.emplace_back();  // filled in place: a value is over 100 bytes
  v.def = &def;
  v.origin = b.origin;
  v.address = slot->value_address;
  v.wire_address = static_cast<std::uint16_t>(wire);
  v.instance = slot->instance;

  // The value's words must follow one another on the wire; a pair split by the end of the
  // block (or by a hex-ID gap) is reported as incomplete rather than guessed.
  std::array<std::uint16_t, detail::kMaxTextWords> parts{};
  std::size_t present = 0;
  for (std::size_t k = slot->word; k < def.words; ++k) {
    const std::size_t j = index + (k - slot->word);
    if (j >= b.words.size()) break;
    if (!b.written_at(static_cast<std::uint16_t>(v.address + k * b.step), b.wire_of(j))) break;
    parts[k] = b.words[j];
    ++present;
  }
  present = std::max<std::size_t>(present, 1);
  v.words_present = static_cast<std::uint8_t>(present);
  if (slot->word == 0 && present == def.words) {
    detail::convert_words(def, std::span<const std::uint16_t>(parts.data(), def.words),
                          b.options.pair_rule, v);
  } else {
    v.add(ValueWarning::Incomplete);
  }
  return present;
}

}  // namespace

DecodeReport RegisterDecoder::decode(const Frame& frame, const Frame* request,
                                     std::vector<DecodedValue>& out) const {
  return detail::dialect_module(frame.dialect).decode_values(*this, frame, request, out);
}

RegisterDecoder::RegisterDecoder(DecoderOptions options)
    : learned_(std::make_shared<SunSpecStations>()), options_(options) {}

void RegisterDecoder::use_map(const RegisterMap& map) {
  own_maps_[static_cast<std::size_t>(map.dialect())] = map;
}

void RegisterDecoder::use_station_map(std::uint8_t station, const RegisterMap& map) {
  std::uint8_t& index = station_map_of_[station];
  if (index != 0) {
    station_maps_[index - 1u] = map;
    return;
  }
  station_maps_.push_back(map);
  index = static_cast<std::uint8_t>(station_maps_.size());
}

// SunSpec devices answer holding-register reads; a station given a map is not second-guessed.
void RegisterDecoder::learn(const Frame& reply, const Frame* request) const {
  if (!options_.sunspec || reply.role != Role::Response || station_map_of_[reply.station] != 0 ||
      (reply.function != fc::kGslReadHolding && reply.function != fc::kReadWriteMultiple) ||
      !detail::is_request_for(request, reply) || !modbus_family(reply.dialect)) {
    return;
  }
  learned_->learn(reply.station, *request->start, reply.words.span());
}

// A scale factor read in the same reply is the newest; one read before is remembered per
// station (a master may read a model's scale factors once and its values often).
void RegisterDecoder::apply_scale_factors(const RegisterMap& m, std::uint8_t station,
                                          const DecodeReport& report,
                                          std::vector<DecodedValue>& out) const {
  if (!m.has_scale_factors() || report.status != DecodeStatus::Decoded) return;
  const std::span<DecodedValue> placed(out.data() + report.first, report.count);
  for (const DecodedValue& v : placed) {
    if (v.def != nullptr && v.def->is_scale_factor && v.complete() &&
        !v.has(ValueWarning::NoValue)) {
      learned_->remember_scale_factor(station, v.address, static_cast<std::int16_t>(v.signed_raw));
    }
  }
  for (DecodedValue& v : placed) {
    if (v.def == nullptr || !v.def->has_scale_factor() || !v.complete() ||
        v.has(ValueWarning::NoValue)) {
      continue;
    }
    std::int16_t exponent = 0;
    // SunSpec allows -10..10; anything else is a damaged or misread register.
    if (!learned_->scale_factor(station, v.def->scale_factor_address, exponent) || exponent < -10 ||
        exponent > 10) {
      v.add(ValueWarning::NoScaleFactor);
      continue;
    }
    v.value *= std::pow(10.0, exponent);
    if (exponent < 0) v.scale_decimals = static_cast<std::uint8_t>(-exponent);
  }
}

namespace {

std::size_t decode_with(const RegisterMap& map, Dialect d, const DecoderOptions& options,
                        std::uint16_t wire_start, std::span<const std::uint16_t> words,
                        ValueOrigin origin, std::vector<DecodedValue>& out) {
  const bool identity =
      !detail::dialect_module(d).decimal_register_ids || options.gsl_ids == GslIdReading::Decimal;
  const Block block{d, map, options, wire_start, words, origin, address_step(d), identity};
  const std::size_t before = out.size();
  for (std::size_t i = 0; i < words.size();) i += append_value(block, i, out);
  return out.size() - before;
}

}  // namespace

std::size_t RegisterDecoder::decode_block(Dialect d, std::uint16_t wire_start,
                                          std::span<const std::uint16_t> words, ValueOrigin origin,
                                          std::vector<DecodedValue>& out) const {
  return place(map(d), d, wire_start, words, origin, out).count;
}

DecodeReport RegisterDecoder::place(Dialect d, std::uint16_t start,
                                    std::span<const std::uint16_t> words, ValueOrigin origin,
                                    std::vector<DecodedValue>& out) const {
  return place(map(d), d, start, words, origin, out);
}

DecodeReport RegisterDecoder::place(const RegisterMap& m, Dialect d, std::uint16_t start,
                                    std::span<const std::uint16_t> words, ValueOrigin origin,
                                    std::vector<DecodedValue>& out) const {
  DecodeReport report;
  report.status = DecodeStatus::Decoded;
  report.origin = origin;
  report.start = start;
  report.first = out.size();
  report.count = decode_with(m, d, options_, start, words, origin, out);
  return report;
}

std::string_view describe(const DecodeReport& report) {
  switch (report.status) {
    case DecodeStatus::Decoded:
      if (report.start_assumed) {
        return "decoded; no matching request, so the start address is the seed's default for "
               "this function code (assumed)";
      }
      return report.count_mismatch ? "decoded; the word count differs from the request's count"
                                   : "decoded";
    case DecodeStatus::NoRegisterData:
      return "the frame carries no register values";
    case DecodeStatus::StartUnknown:
      return "register words without a known start address (a GSL read reply needs its "
             "request): nothing placed";
  }
  return "?";
}

}  // namespace pvtap
