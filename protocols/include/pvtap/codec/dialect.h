// Wire dialects, frame roles and direction hints shared by every part of the core.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace pvtap {

// Dialect: one of the wire dialects of PROTOCOLS.md. GSL and Modbus share every rule of the
// wire (GSL is Modbus RTU with KSTAR's registers); they differ in the map that names a
// station's registers (dialects/modbus/station_dialects.h says which a station is).
enum class Dialect : std::uint8_t { Ascii = 0, Hybrid = 1, Gsl = 2, Modbus = 3 };

inline constexpr std::size_t kDialectCount = 4;

// What a frame of a code GSL shares with Modbus is read as unless told otherwise (PROTOCOLS.md
// section 6), and so what a record holds until its dialect is known.
inline constexpr Dialect kDefaultDialect = Dialect::Gsl;

// What a SunSpec device speaks (plain Modbus: its models are its map, read from the device).
inline constexpr Dialect kSunSpecDialect = Dialect::Modbus;

// What the frames a Modbus/TCP gateway or a logger stick carries are read as until the bus
// session decides otherwise: plain Modbus, the protocol both carriers were made for.
inline constexpr Dialect kCarriedDialect = Dialect::Modbus;

// Whether `d` is framed by the Modbus application protocol's rules (GSL or plain Modbus).
constexpr bool modbus_family(Dialect d) {
  return d == Dialect::Gsl || d == Dialect::Modbus;
}

// Role: who sent a frame. A master sends requests, an inverter sends responses.
enum class Role : std::uint8_t { Request = 0, Response = 1 };

// RoleHint: what the caller knows about the sender of some bytes.
enum class RoleHint : std::uint8_t { Unknown = 0, Request = 1, Response = 2 };

// DialectSet: the dialects a decoder should recognize (all of them unless told).
class DialectSet {
 public:
  constexpr DialectSet() = default;
  static constexpr DialectSet all() { return DialectSet(0b1111); }
  static constexpr DialectSet only(Dialect d) { return DialectSet(bit(d)); }
  static constexpr DialectSet none() { return DialectSet(0); }
  constexpr bool contains(Dialect d) const { return (bits_ & bit(d)) != 0; }
  constexpr bool rtu() const {
    return contains(Dialect::Hybrid) || contains(Dialect::Gsl) || contains(Dialect::Modbus);
  }
  constexpr bool modbus_family() const {
    return contains(Dialect::Gsl) || contains(Dialect::Modbus);
  }
  constexpr DialectSet with(Dialect d) const {
    return DialectSet(static_cast<std::uint8_t>(bits_ | bit(d)));
  }
  // PROTOCOLS.md section 6 labels a frame of a code GSL shares with Modbus that nothing else
  // decides as the earlier of the two in --dialect's order: GSL unless told otherwise.
  constexpr DialectSet preferring_modbus() const {
    return DialectSet(static_cast<std::uint8_t>(bits_ | kPreferModbus));
  }
  constexpr bool prefers_modbus() const { return (bits_ & kPreferModbus) != 0; }
  // What a carried frame that no reading fits is labelled, so that the Modbus family's rules
  // name what is wrong with it: plain Modbus, or GSL when GSL is enabled and plain Modbus not.
  constexpr Dialect carried_fallback() const {
    return contains(Dialect::Modbus) || !contains(Dialect::Gsl) ? Dialect::Modbus : Dialect::Gsl;
  }
  // `d` added as the next of a list in its reader's order (--dialect modbus,gsl): of GSL and
  // plain Modbus, the one named first takes a shared code nothing else decides.
  constexpr DialectSet then(Dialect d) const {
    const bool modbus_first = d == Dialect::Modbus && !contains(Dialect::Gsl);
    return (modbus_first ? preferring_modbus() : *this).with(d);
  }
  constexpr bool operator==(const DialectSet&) const = default;

 private:
  static constexpr std::uint8_t kPreferModbus = 0x80;
  constexpr explicit DialectSet(std::uint8_t bits) : bits_(bits) {}
  static constexpr std::uint8_t bit(Dialect d) {
    return static_cast<std::uint8_t>(1u << static_cast<unsigned>(d));
  }
  std::uint8_t bits_ = 0b1111;
};

constexpr std::string_view to_string(Dialect d) {
  switch (d) {
    case Dialect::Ascii:
      return "ascii";
    case Dialect::Hybrid:
      return "hybrid";
    case Dialect::Gsl:
      return "gsl";
    case Dialect::Modbus:
      return "modbus";
  }
  return "?";
}

// Every dialect, in the enum's order: code that treats each dialect alike iterates this and
// names none (protocols/src/dialects/ holds what is particular to each).
inline constexpr std::array<Dialect, kDialectCount> kAllDialects{Dialect::Ascii, Dialect::Hybrid,
                                                                 Dialect::Gsl, Dialect::Modbus};

// The dialect `name` spells as to_string does ("gsl"), or nullopt.
constexpr std::optional<Dialect> dialect_named(std::string_view name) {
  for (const Dialect d : kAllDialects) {
    if (to_string(d) == name) return d;
  }
  return std::nullopt;
}

// A dialect's name for people ("Hybrid V2.2", "GSL (Modbus RTU)").
std::string_view dialect_title(Dialect d);

// Its name inside a sentence ("GSL until this frame, now plain Modbus").
std::string_view dialect_short_title(Dialect d);

// What a dialect's frames end with, as a sentence names it: "CRC" or "checksum".
std::string_view check_name(Dialect d);

// A dialect whose error reply carries no exception code names it whole ("hybrid error reply
// (0xFF)"); empty for a dialect whose exceptions carry their code.
std::string_view error_reply_name(Dialect d);

// Whether the seed of a dialect writes register IDs as decimal numbers (GSL: 1050 for the
// wire's 0x1050 when read as hex).
bool decimal_register_ids(Dialect d);

// Whether a dialect's frames are RTU frames (station, function, body, CRC), which one
// Wireshark protocol shows, or frames of their own (ASCII).
bool rtu_framed(Dialect d);

constexpr std::string_view to_string(Role r) {
  return r == Role::Request ? "request" : "response";
}

}  // namespace pvtap
