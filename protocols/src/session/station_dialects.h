// Which dialect each station speaks: GSL or plain Modbus for the codes they share (private).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::detail {

// StationDialects: labels frames of the codes GSL shares with Modbus (0x03 0x04 0x06 0x10
// and exceptions), which the framing reads once, and notes when a station changes dialect.
//
// The rule (README "GSL or plain Modbus"): GSL is Modbus RTU with KSTAR's registers, so a
// station is GSL when a request to it with a good check addresses only registers of the GSL
// map, and plain Modbus when such a request addresses one the GSL map does not have. That decides
// the station; until then a request is labelled by its own registers, a reply by the last request
// to its station, and a frame with nothing to go by is GSL, the earlier of the two in --dialect's
// order. Functions GSL does not use are plain Modbus on a station not decided as GSL. A station
// given a map of its own (--map STATION=FILE) speaks that map's dialect. A station decided one way
// whose requests later say the other is a dialect change: the frames follow their evidence and the
// change is reported, never silently followed.
class StationDialects {
 public:
  // Run: consecutive wire addresses first..last of a map.
  struct Run {
    std::uint16_t first = 0;
    std::uint16_t last = 0;
  };

  StationDialects(DialectSet enabled, const RegisterDecoder& decoder);

  struct Label {
    Dialect dialect = Dialect::Gsl;
    std::optional<Dialect> changed_from;  // the station's dialect before this frame
  };
  // The dialect of a parsed frame, and whether its station changed dialect with it.
  Label label(const Frame& frame, bool check_ok);

 private:
  // What is known of one station; kNone where nothing is. Kept together so that labelling a
  // frame touches one small record (it runs for every frame of an audit).
  static constexpr std::uint8_t kNone = 0xFF;
  struct Station {
    std::uint8_t decided = kNone;       // by a good request's registers
    std::uint8_t forced = kNone;        // by a map given for the station
    std::uint8_t last_request = kNone;  // the label of the last request to it
    std::uint8_t speaks = kNone;        // what its frames claimed last
    bool speaks_weakly = false;         // ... by its first frame alone
  };
  std::optional<Dialect> evidence(const Frame& frame) const;
  Dialect choose(const Frame& frame, Station& st, std::optional<Dialect> own, bool check_ok);
  static void note_claim(Station& st, Label& out, Dialect claim, bool weak);
  bool addresses_gsl_map(std::uint16_t start, std::uint16_t count) const;

  bool choose_ = false;               // both GSL and Modbus are enabled
  Dialect undecided_ = Dialect::Gsl;  // a shared code's label when nothing else decides
  std::vector<Run> gsl_runs_;         // the GSL map's wire addresses, sorted
  std::array<Station, 256> stations_{};
};

}  // namespace pvtap::detail
