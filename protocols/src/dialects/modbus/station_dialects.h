// Which dialect each station speaks: GSL or plain Modbus for the codes they share (private).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/codec/function_codes.h"
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
  // The dialect of a parsed frame, and whether its station changed dialect with it. Inline
  // for the frames that change nothing, most of an audit's: a frame of a dialect of its own
  // that its station already speaks, or a bad one (see label_in_full for why both are no-ops).
  // A good reply to a station whose dialect is decided is also one: its label is the
  // station's, and a reply's claim is weak.
  Label label(const Frame& frame, bool check_ok) {
    const Station& st = stations_[frame.station];
    if (!modbus_family(frame.dialect)) {
      if (!check_ok ||
          (st.speaks == static_cast<std::uint8_t>(frame.dialect) && !st.speaks_weakly)) {
        return Label{frame.dialect, std::nullopt};
      }
    } else if (choose_ && check_ok && frame.role == Role::Response && st.forced == kNone &&
               st.decided != kNone && st.speaks != kNone) {
      return Label{own_codes_only(static_cast<Dialect>(st.decided), frame.function, check_ok),
                   std::nullopt};
    }
    return label_in_full(frame, check_ok);
  }

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
  Label label_in_full(const Frame& frame, bool check_ok);
  // GSL names only its own codes; another Modbus function of a GSL station is plain Modbus.
  // A frame with a bad check keeps its station's label: its function may be the damaged byte.
  static Dialect own_codes_only(Dialect d, std::uint8_t function, bool check_ok) {
    if (check_ok && d == Dialect::Gsl && !fc::is_gsl_function(function) &&
        (fc::is_modbus_function(function) || fc::is_user_defined_function(function))) {
      return Dialect::Modbus;
    }
    return d;
  }
  std::optional<Dialect> evidence(const Frame& frame);
  Dialect choose(const Frame& frame, Station& st, std::optional<Dialect> own, bool check_ok);
  static void note_claim(Station& st, Label& out, Dialect claim, bool weak);
  bool addresses_gsl_map(std::uint16_t start, std::uint16_t count);
  bool search_gsl_map(std::uint16_t start, std::uint16_t count) const;

  // The answers for the ranges a logger polls, which repeat: a search per request cost as much
  // as the rest of the labelling.
  struct RangeMemo {
    std::uint32_t range = 0;  // start << 16 | count
    bool known = false;
    bool gsl = false;
  };
  static constexpr std::size_t kMemoSize = 16;

  bool choose_ = false;               // both GSL and Modbus are enabled
  Dialect undecided_ = Dialect::Gsl;  // a shared code's label when nothing else decides
  std::vector<Run> gsl_runs_;         // the GSL map's wire addresses, sorted
  std::array<Station, 256> stations_{};
  std::array<RangeMemo, kMemoSize> memo_{};
};

}  // namespace pvtap::detail
