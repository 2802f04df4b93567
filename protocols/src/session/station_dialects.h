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
  struct Claim {
    Dialect dialect = Dialect::Gsl;
    bool weak = false;
  };
  std::optional<Dialect> evidence(const Frame& frame) const;
  Claim claim_of(const Frame& frame, Dialect label) const;
  void note_claim(std::uint8_t station, Label& out, Claim claim);
  bool addresses_gsl_map(std::uint16_t start, std::uint16_t count) const;

  bool choose_ = false;        // both GSL and Modbus are enabled
  std::vector<Run> gsl_runs_;  // the GSL map's wire addresses, sorted
  static constexpr std::size_t kStations = 256;
  std::array<std::optional<Dialect>, kStations> decided_{};
  std::array<std::optional<Dialect>, kStations> forced_{};  // by a map given for the station
  std::array<std::optional<Dialect>, kStations> last_request_{};
  std::array<std::optional<Claim>, kStations> station_{};  // what each station speaks
};

}  // namespace pvtap::detail
