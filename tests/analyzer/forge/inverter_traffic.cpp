#include "inverter_traffic.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::forge {
namespace {

constexpr double kBetweenExchanges = 0.050;
constexpr double kMasterTimeout = 1.2;  // the logger waits this long for a silent inverter
constexpr DeviceNumber kHybridDevice{0x32, 4711};

}  // namespace

Frame gsl_read(std::uint8_t station, std::uint16_t first_id, std::uint16_t count) {
  Frame f = make_frame(Dialect::Gsl, Role::Request, station, fc::kGslReadHolding);
  f.start = first_id;  // decimal IDs: ID 1050 is wire address 1050 (0x041A)
  f.count = count;
  return f;
}

Frame gsl_reply(std::uint8_t station, const WordList& words) {
  Frame f = make_frame(Dialect::Gsl, Role::Response, station, fc::kGslReadHolding);
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return f;
}

Frame gsl_exception(std::uint8_t station, std::uint8_t function, std::uint8_t code) {
  Frame f = make_frame(Dialect::Gsl, Role::Response, station,
                       static_cast<std::uint8_t>(function | fc::kExceptionFlag));
  f.exception_code = code;
  return f;
}

Frame hybrid_read(std::uint8_t station, std::uint8_t function, std::uint16_t start,
                  std::uint16_t count) {
  Frame f = make_frame(Dialect::Hybrid, Role::Request, station, function);
  f.start = start;
  f.count = count;
  return f;
}

Frame hybrid_reply(std::uint8_t station, std::uint8_t function, const WordList& words) {
  Frame f = make_frame(Dialect::Hybrid, Role::Response, station, function);
  f.byte_count = static_cast<std::uint8_t>(4 + 2 * words.size());
  f.device = kHybridDevice;
  f.words = words;
  return f;
}

Frame hybrid_error(std::uint8_t station) {
  Frame f = make_frame(Dialect::Hybrid, Role::Response, station, fc::kHybridError);
  f.byte_count = 8;
  f.device = kHybridDevice;
  f.start = 0x1000;
  f.count = 0x00FF;
  return f;
}

Frame ascii_read(std::uint8_t station, std::uint16_t start, std::uint16_t count) {
  Frame f = make_frame(Dialect::Ascii, Role::Request, station, fc::kAsciiRead);
  f.start = start;
  f.count = count;
  return f;
}

Frame ascii_reply(std::uint8_t station, std::uint16_t start, const WordList& words) {
  Frame f = make_frame(Dialect::Ascii, Role::Response, station, fc::kAsciiRead);
  f.start = start;
  f.words = words;
  return f;
}

WordList gsl_measurements(unsigned round) {
  const auto w = [](unsigned v) { return static_cast<std::uint16_t>(v); };
  return {w(4000 + round),
          w(4001),
          w(3999),  // line voltages AB BC CA
          w(120 + round),
          w(121),
          w(119),               // phase currents
          w(5000 + round % 3),  // grid frequency
          w(99),
          w(99),
          w(98),  // power factors
          w(80 + round % 5),
          w(81),
          w(79),  // active power per phase
          w(1),
          w(1),
          w(2),  // reactive power per phase
          w(6000 + 3 * round),
          w(420),
          w(252),  // PV voltage, current, power
          w(100 + round),
          w(975),
          w(123),
          w(450 + round)};  // today, efficiency, year, temp
}

WordList gsl_alarms(unsigned round) {
  return {0, 0, static_cast<std::uint16_t>(round == 2 ? 0x0040 : 0), 0x0830};
}

WordList hybrid_running_data(unsigned round) {
  const auto w = [](unsigned v) { return static_cast<std::uint16_t>(v); };
  return {w(2300),
          w(2310),
          w(2295),
          w(5000),
          w(1),
          w(435),
          w(523 + round),
          w(356),
          w(2),
          w(1250),
          w(4999),
          w(1),
          w(3),
          w(0x0460),
          w(0),
          w(12345 + round),
          w(1000 + 10 * round),
          w(4),
          w(3),
          w(0),
          w(25),
          w(0),
          w(1),
          w(5000),
          w(2300),
          w(480),
          w(10000),
          w(0x0102),
          w(0),
          w(0),
          w(0),
          w(1),
          w(3605),
          w(125),
          w(1),
          w(45000)};
}

WordList ascii_pv(unsigned round) {
  return {static_cast<std::uint16_t>(266 + round % 2), 57};
}

double poll_round(BusPlan& plan, double at, unsigned round, const RoundFaults& faults) {
  double t = at;
  t = plan.exchange(t, gsl_read(kGslStation, 1050, 23),
                    gsl_reply(kGslStation, gsl_measurements(round)), 0.025 + 0.003 * (round % 4));
  t += kBetweenExchanges;
  if (faults.gsl2_silent) {
    t = plan.exchange(t, gsl_read(kGslStation2, 1030, 4), std::nullopt, 0) + kMasterTimeout;
  } else if (faults.gsl2_exception) {
    t = plan.exchange(t, gsl_read(kGslStation2, 1030, 4),
                      gsl_exception(kGslStation2, fc::kGslReadHolding, 0x02), 0.041);
  } else {
    t = plan.exchange(t, gsl_read(kGslStation2, 1030, 4),
                      gsl_reply(kGslStation2, gsl_alarms(round)), 0.040 + 0.002 * (round % 3));
  }
  t += kBetweenExchanges;
  const Frame hybrid_request = hybrid_read(kHybridStation, fc::kHybridRunningData, 0x1000, 0x24);
  const Frame hybrid_answer =
      faults.hybrid_error_reply
          ? hybrid_error(kHybridStation)
          : hybrid_reply(kHybridStation, fc::kHybridRunningData, hybrid_running_data(round));
  t = plan.exchange(t, hybrid_request, hybrid_answer, 0.060 + 0.001 * (round % 5),
                    faults.hybrid_bad_crc);
  t += kBetweenExchanges;
  t = plan.exchange(t, ascii_read(kAsciiStation, 0x0020, 2),
                    ascii_reply(kAsciiStation, 0x0020, ascii_pv(round)),
                    0.030 + 0.004 * (round % 2));
  if (faults.noise_after_ascii) t = plan.noise(t + 0.020, {0x00, 0xFF, 0x00});
  return t + kBetweenExchanges;
}

void expect_round_values(BusPlan& plan, unsigned last_round) {
  plan.expect_value("1", "1056", (5000 + last_round % 3) / 100.0);
  plan.expect_value("1", "1066", (6000 + 3 * last_round) / 10.0);
  plan.expect_value("2", "1033", 0x0830);
  plan.expect_value("6", "0x1006", (523 + last_round) / 10.0);
  plan.expect_value("3", "0x0020", 266 + last_round % 2);
}

}  // namespace pvtap::forge
