// What the generic core asks of a wire dialect, one record per dialect in one table (private).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::detail {

// DialectModule: the facts of one dialect that code outside dialects/ needs, as functions the
// dialect's folder defines. Codec, names and maps ask dialect_module(d) instead of switching on
// the dialect, so a dialect is its folder and one line of dialect_table.cpp.
struct DialectModule {
  Dialect dialect;
  std::string_view title;             // dialect_title()
  std::string_view short_title;       // dialect_short_title()
  std::string_view check_name;        // check_name()
  std::string_view error_reply_name;  // error_reply_name()
  bool rtu_framed;                    // rtu_framed()
  // A whole frame's bytes (check included) read into `out`; why not, or empty.
  std::string_view (*parse)(std::span<const std::uint8_t> bytes, Role role, Frame& out);
  // The station and function by their position alone (frame_header in frame_codec.h).
  void (*read_header)(std::span<const std::uint8_t> bytes, Frame& out);
  FrameCheck (*verify_check)(std::span<const std::uint8_t> bytes);
  // The check as the wire carries `expected`, appended to `out`.
  void (*check_wire_bytes)(std::uint16_t expected, std::vector<std::uint8_t>& out);
  // Appends the frame with its check; false, appending nothing, when its fields do not fit.
  bool (*encode)(const Frame& frame, std::vector<std::uint8_t>& out);
  std::string_view (*function_name)(std::uint8_t function);
  std::string_view (*exception_name)(std::uint8_t code);
  // The built-in register map (TOML text), empty when the dialect's devices bring their own.
  std::string_view (*builtin_map_text)();

  // Matching (matching/reply_rules.cpp). The dialect a reply of this one may answer a
  // request of: its own, GSL for plain Modbus (a station's label may be settled only after
  // its first request).
  Dialect reply_family;
  // A reply's kind by its function: an error reply, an exception or data.
  ReplyKind (*reply_kind)(std::uint8_t function);
  // Whether a gateway's exception answers a request of this dialect that it could not forward.
  bool answered_by_gateway_exception;
  // Whether a reply must repeat its request's start address (ASCII).
  bool reply_repeats_start;
  // Whether the normal reply of `function` repeats its request unchanged.
  bool (*reply_is_echo)(std::uint8_t function);
  // The length a normal reply to `request` should have, against the one `reply` has.
  std::optional<CountComparison> (*compare_reply_count)(const FrameSummary& request,
                                                        const FrameSummary& reply);

  // Whether the seed writes register IDs as decimal numbers (GSL: 1050), which --gsl-ids may
  // read as the digits of a hex wire address (0x1050): registers/register_addressing.cpp and
  // the address's text (register_map.cpp).
  bool decimal_register_ids;
  // How far apart the addresses of neighbouring registers are (ASCII counts bytes: 2).
  unsigned register_address_step;
  // An address besides 0 that every station hears and one of them answers (Hybrid's 0xFF),
  // or -1: the matcher keeps such a request apart from every station's own.
  int answered_broadcast_station;
  // Whether a reply read as this dialect may also read as a reply of the Modbus family
  // (Hybrid's, PROTOCOLS.md section 6): the session reads such a reply to a station last asked
  // in the Modbus family again by what it was asked.
  bool reply_may_be_modbus_family;
  // Values (registers/register_decoder.cpp): appends the register values `frame` carries;
  // `request` is a reply's matching request, or null.
  DecodeReport (*decode_values)(const RegisterDecoder& decoder, const Frame& frame,
                                const Frame* request, std::vector<DecodedValue>& out);
};

// The records in the enum's order (dialect_table.cpp).
extern const std::array<const DialectModule*, kDialectCount> kDialectTable;

// The module of `d`; its `dialect` is `d`. Inline: the codec asks it once per frame.
inline const DialectModule& dialect_module(Dialect d) {
  return *kDialectTable[static_cast<std::size_t>(d)];
}

// Whether `station` is an address besides 0 that every station of dialect `d` hears and one
// of them answers (Hybrid's 0xFF). Inline: the matcher asks for every frame.
inline bool answered_broadcast(Dialect d, std::uint8_t station) {
  return dialect_module(d).answered_broadcast_station == int{station};
}

}  // namespace pvtap::detail
