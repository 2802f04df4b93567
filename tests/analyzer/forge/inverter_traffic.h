// The frames of a small solar site: what a data logger asks and what its inverters answer,
// with values that change a little from one poll round to the next.
#pragma once

#include <cstdint>
#include <optional>

#include "bus_plan.h"
#include "pvtap/codec/frame.h"

namespace pvtap::forge {

// The site: GSL inverters 1 and 2, a Hybrid inverter at 6, an ASCII inverter at 3.
inline constexpr std::uint8_t kGslStation = 1;
inline constexpr std::uint8_t kGslStation2 = 2;
inline constexpr std::uint8_t kHybridStation = 6;
inline constexpr std::uint8_t kAsciiStation = 3;

Frame gsl_read(std::uint8_t station, std::uint16_t first_id, std::uint16_t count);
Frame gsl_reply(std::uint8_t station, const WordList& words);
Frame gsl_exception(std::uint8_t station, std::uint8_t function, std::uint8_t code);
Frame hybrid_read(std::uint8_t station, std::uint8_t function, std::uint16_t start,
                  std::uint16_t count);
Frame hybrid_reply(std::uint8_t station, std::uint8_t function, const WordList& words);
Frame hybrid_error(std::uint8_t station);
Frame ascii_read(std::uint8_t station, std::uint16_t start, std::uint16_t count);
Frame ascii_reply(std::uint8_t station, std::uint16_t start, const WordList& words);

// The words a station reports in round `round`.
WordList gsl_measurements(unsigned round);     // IDs 1050..1072 (23 words)
WordList gsl_alarms(unsigned round);           // IDs 1030..1033
WordList hybrid_running_data(unsigned round);  // 0x1000..0x1023 (36 words)
WordList ascii_pv(unsigned round);             // 0x0020, 0x0022

// RoundFaults: what goes wrong in one poll round.
struct RoundFaults {
  bool hybrid_bad_crc = false;  // the Hybrid reply is corrupted on the line
  bool gsl2_silent = false;     // station 2 does not answer: a timeout
  bool gsl2_exception = false;  // station 2 refuses: exception 0x02
  bool hybrid_error_reply = false;
  bool noise_after_ascii = false;  // line noise after the ASCII exchange
};

// One poll round of the whole site starting at `at`; returns when the bus is quiet again.
// Latencies differ per station and vary with the round, so statistics have some spread.
double poll_round(BusPlan& plan, double at, unsigned round, const RoundFaults& faults = {});

// The values the summary must show after `last_round` was the last complete round.
void expect_round_values(BusPlan& plan, unsigned last_round);

}  // namespace pvtap::forge
