// Unit tests of the simulator's parts: register images read back through the core's decoder,
// fault plans, determinism, frames that the core parses as sent, and damage that a reader can
// still delimit (requests and replies, any byte, in runs, pinned at both ends).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <fstream>
#include <iterator>

#include "bus/bus_master.h"
#include "bus/frame_shapes.h"
#include "bus/poll_blocks.h"
#include "devices/battery.h"
#include "faults/fault_plan.h"
#include "faults/frame_damage.h"
#include "outputs/ground_truth.h"
#include "plant/register_image.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::sim {
namespace {

// The value the core's decoder reads for `key` out of a block of the image.
double decoded(Dialect d, const RegisterImage& image, std::uint16_t start, std::uint16_t count,
               std::string_view key) {
  const WordList words = image.block(start, count);
  std::vector<DecodedValue> out;
  RegisterDecoder{}.decode_block(d, start, words.span(), ValueOrigin::ReadReply, out);
  const auto it = std::find_if(out.begin(), out.end(), [&](auto& v) { return v.key() == key; });
  return it == out.end() ? -1.0 : it->value;
}

TEST(RegisterImage, ScaledValuesReadBackThroughTheCoreDecoder) {
  RegisterImage ascii(Dialect::Ascii);
  ascii.set_value("cumulative_energy", 570.23);  // a decimal pair: high 57, low 230
  EXPECT_DOUBLE_EQ(decoded(Dialect::Ascii, ascii, 0x0060, 8, "cumulative_energy"), 570.23);
  EXPECT_EQ(ascii.block(0x0062, 2), (WordList{57, 230}));

  RegisterImage gsl(Dialect::Gsl);
  gsl.set_value("total_energy", 12345.6);  // a binary pair of 0.1 kWh
  EXPECT_NEAR(decoded(Dialect::Gsl, gsl, 1086, 2, "total_energy"), 12345.6, 1e-9);
  gsl.set_value("grid_frequency", 50.02);
  EXPECT_NEAR(decoded(Dialect::Gsl, gsl, 1050, 46, "grid_frequency"), 50.02, 1e-9);
}

TEST(RegisterImage, TruthNamesEveryRegisterOfTheBlock) {
  RegisterImage hybrid(Dialect::Hybrid);
  hybrid.set_value("battery_voltage", 52.3);
  const auto truth = hybrid.truth(0x1000, 0x24);
  const auto it =
      std::find_if(truth.begin(), truth.end(), [](auto& t) { return t.key == "battery_voltage"; });
  ASSERT_NE(it, truth.end());
  EXPECT_EQ(it->address, "0x1006");
  EXPECT_EQ(it->raw, 523u);
  EXPECT_NEAR(it->value, 52.3, 1e-9);
}

TEST(FaultPlan, ParsesKindsAndRejectsUnknownOnes) {
  std::string error;
  const auto plan = parse_fault_plan("corrupt=5,duplicate=2", error);
  ASSERT_TRUE(plan);
  EXPECT_EQ((*plan)[FaultKind::Corrupt], 5u);
  EXPECT_EQ((*plan)[FaultKind::Duplicate], 2u);
  EXPECT_EQ((*plan)[FaultKind::Missing], 0u);
  const auto requests = parse_fault_plan("corrupt_request=7", error);
  ASSERT_TRUE(requests);
  EXPECT_EQ((*requests)[FaultKind::CorruptRequest], 7u);
  EXPECT_EQ((*requests)[FaultKind::Corrupt], 0u);
  const auto all = parse_fault_plan("all", error);
  ASSERT_TRUE(all);
  for (unsigned k = 0; k < kFirstOptInKind; ++k) EXPECT_EQ(all->percent[k], 4u);
  EXPECT_EQ((*all)[FaultKind::CorruptRequest], 4u);
  EXPECT_EQ((*all)[FaultKind::CorruptData], 0u) << "opt-in kinds stay out of \"all\"";
  EXPECT_FALSE(all->drawn(FaultKind::CorruptData));
  const auto data = parse_fault_plan("corrupt_data=9", error);
  ASSERT_TRUE(data);
  EXPECT_EQ((*data)[FaultKind::CorruptData], 9u);
  EXPECT_TRUE(data->drawn(FaultKind::CorruptData));
  EXPECT_TRUE(data->drawn(FaultKind::Missing)) << "the first kinds are always drawn";
  EXPECT_FALSE(parse_fault_plan("lightning=5", error));
  EXPECT_FALSE(parse_fault_plan("corrupt=101", error));
  EXPECT_FALSE(parse_fault_plan("corrupt=", error));
}

SimConfig faulty_bus(std::uint64_t seed) {
  SimConfig c;
  c.seed = seed;
  c.dialects = {Dialect::Gsl, Dialect::Hybrid, Dialect::Ascii};
  c.duration_s = 30;
  std::string error;
  c.faults = *parse_fault_plan("all", error);
  return c;
}

TEST(BusMaster, OneSeedGivesOneBus) {
  const BusTimeline a = BusMaster(faulty_bus(3)).run();
  const BusTimeline b = BusMaster(faulty_bus(3)).run();
  const BusTimeline c = BusMaster(faulty_bus(4)).run();
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(a.events[i].bytes, b.events[i].bytes);
    EXPECT_EQ(a.events[i].start, b.events[i].start);
  }
  const bool same = a.events.size() == c.events.size() &&
                    std::equal(a.events.begin(), a.events.end(), c.events.begin(),
                               [](auto& x, auto& y) { return x.bytes == y.bytes; });
  EXPECT_FALSE(same);
}

TEST(BusMaster, FramesParseAsSentAndChecksMatchTheTruth) {
  const BusTimeline t = BusMaster(faulty_bus(11)).run();
  Micros previous_end = 0;
  for (const BusEvent& e : t.events) {
    EXPECT_GE(e.start, previous_end) << "two things on the bus at once";
    previous_end = e.end;
    if (e.kind == BusEvent::Kind::Noise) continue;
    EXPECT_EQ(verify_check(e.bytes, e.dialect).ok, e.check_ok);
    // A damaged header need not parse at all: the truth says what its bytes say.
    EXPECT_EQ(wire_station(e.bytes, e.dialect), e.station);
    EXPECT_EQ(wire_function(e.bytes, e.dialect), e.function);
    if (!e.check_ok) continue;
    const ParseOutcome parsed = parse_frame(e.bytes, e.dialect, e.role);
    ASSERT_TRUE(parsed) << parsed.diagnostics();
    EXPECT_EQ(parsed->station, e.station);
    EXPECT_EQ(parsed->function, e.function);
  }
}

std::vector<std::uint8_t> request_bytes(Dialect d) {
  return encode_frame(read_request(d, 2, poll_blocks(d).back()));
}

TEST(FrameDamage, HitsEveryByteOfARequestWithABitOrAByte) {
  for (const Dialect d : {Dialect::Gsl, Dialect::Hybrid, Dialect::Ascii}) {
    const std::vector<std::uint8_t> original = request_bytes(d);
    std::vector<unsigned> hits(original.size());
    unsigned single_bits = 0, whole_bytes = 0;
    SimRandom random(17);
    for (int draw = 0; draw < 3000; ++draw) {
      std::vector<std::uint8_t> bytes = original;
      const FrameDamage damage = damage_frame(bytes, d, Role::Request, random);
      ++hits[damage.at];
      unsigned changed = 0;
      for (std::size_t i = 0; i < bytes.size(); ++i) changed += bytes[i] != original[i];
      ASSERT_EQ(changed, 1u) << "one byte, and only one, changes";
      ++(std::popcount(unsigned(bytes[damage.at] ^ original[damage.at])) == 1 ? single_bits
                                                                              : whole_bytes);
      if (damage.reading == DamageReading::BadCheckFrame) {
        EXPECT_FALSE(verify_check(bytes, d).ok);
      }
      if (d != Dialect::Ascii) {
        EXPECT_EQ(damage.reading, DamageReading::BadCheckFrame);
      }
    }
    for (std::size_t i = 0; i < hits.size(); ++i)
      EXPECT_GT(hits[i], 0u) << to_string(d) << " byte " << i << " never damaged";
    EXPECT_GT(single_bits, 600u);
    EXPECT_GT(whole_bytes, 600u);
  }
}

TEST(FrameDamage, AsciiFramesStayFramesOnlyWithTheirDelimitersAndHexDigits) {
  const std::vector<std::uint8_t> good = request_bytes(Dialect::Ascii);
  auto reading = [&](std::size_t at, std::uint8_t value) {
    std::vector<std::uint8_t> bytes = good;
    bytes[at] = value;
    return reading_of(good, bytes, Dialect::Ascii);
  };
  EXPECT_EQ(reading(1, good[1] == '0' ? '1' : '0'), DamageReading::BadCheckFrame);  // station
  EXPECT_EQ(reading(6, 'f'), DamageReading::BadCheckFrame);                         // address digit
  EXPECT_EQ(reading(3, 'S'), DamageReading::Noise);                                 // the command
  EXPECT_EQ(reading(0, 0x45), DamageReading::Noise);                                // ENQ
  EXPECT_EQ(reading(14, 0x14), DamageReading::Noise);                               // EOT
  EXPECT_EQ(reading(8, 'g'), DamageReading::Noise);  // not a hex digit
  EXPECT_EQ(reading(8, 0x05), std::nullopt) << "a new ENQ inside: drawn again";
  EXPECT_EQ(reading(2, 0x04), std::nullopt) << "a new EOT inside: drawn again";
  // Station 2, 0x01E0 x3 has checksum "020d": flipping the case of its letter keeps the check.
  std::size_t letters = 0;
  for (std::size_t at = 10; at < 14; ++at) {
    if (good[at] < 'a') continue;
    ++letters;
    EXPECT_EQ(reading(at, static_cast<std::uint8_t>(good[at] - 0x20)), std::nullopt);
  }
  EXPECT_EQ(letters, 1u);
}

SimConfig bus_with(std::uint64_t seed, std::vector<Dialect> dialects, const char* faults) {
  SimConfig c;
  c.seed = seed;
  c.dialects = std::move(dialects);
  c.duration_s = 120;
  std::string error;
  c.faults = *parse_fault_plan(faults, error);
  return c;
}

const std::vector<Dialect> kMixed{Dialect::Gsl, Dialect::Hybrid, Dialect::Ascii};

bool is_damaged_frame(const BusEvent& e) {
  return e.kind == BusEvent::Kind::Frame && !e.check_ok;
}

bool lists(const std::vector<TimeoutTruth>& list, const BusEvent& request) {
  return std::any_of(list.begin(), list.end(),
                     [&](const TimeoutTruth& t) { return t.request_start == request.start; });
}

TEST(BusMaster, DamagedRequestsGoUnansweredAndAreNoTimeouts) {
  std::size_t damaged = 0, station_hit = 0, function_hit = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const SimConfig c = bus_with(seed, kMixed, "corrupt_request=15,missing=5,corrupt=5");
    const BusTimeline t = BusMaster(c).run();
    std::size_t listed = 0;
    for (std::size_t i = 0; i < t.events.size(); ++i) {
      const BusEvent& e = t.events[i];
      if (e.role != Role::Request || !is_damaged_frame(e)) continue;
      ++damaged;
      ++listed;
      EXPECT_EQ(e.fault, "corrupt_request");
      EXPECT_TRUE(lists(t.unanswered_damaged_requests, e));
      EXPECT_FALSE(lists(t.timeouts, e));
      EXPECT_FALSE(lists(t.unanswered_at_end, e));
      ASSERT_LT(i + 1, t.events.size()) << "a capture never ends on a damaged request";
      const BusEvent& next = t.events[i + 1];
      EXPECT_EQ(next.role, Role::Request) << "the slave stays silent";
      EXPECT_GE(next.start - e.end, static_cast<Micros>(c.timeout_s * 1e6)) << "master waits";
      if (e.dialect != Dialect::Ascii) {
        station_hit += e.station < 1 || e.station > 3;
        const auto blocks = poll_blocks(e.dialect);
        function_hit += std::none_of(blocks.begin(), blocks.end(),
                                     [&](const PollBlock& b) { return b.function == e.function; });
      }
    }
    EXPECT_EQ(listed, t.unanswered_damaged_requests.size());
  }
  EXPECT_GT(damaged, 50u);
  EXPECT_GT(station_hit, 0u) << "the station byte is damaged too";
  EXPECT_GT(function_hit, 0u) << "the function code is damaged too";
}

TEST(BusMaster, DamagedRequestsComeInRuns) {
  std::size_t runs = 0, retries = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BusTimeline t = BusMaster(bus_with(seed, kMixed, "corrupt_request=10")).run();
    for (std::size_t i = 1; i < t.events.size(); ++i) {
      const BusEvent &a = t.events[i - 1], &b = t.events[i];
      if (is_damaged_frame(a) && is_damaged_frame(b) && a.role == Role::Request &&
          b.role == Role::Request) {
        ++runs;
        EXPECT_GE(b.start - a.end, 1'000'000) << "a second of silence between them";
        // The master's retry of the same block: one damaged byte each, at most two differ.
        if (a.bytes.size() != b.bytes.size()) continue;
        std::size_t differ = 0;
        for (std::size_t k = 0; k < a.bytes.size(); ++k) differ += a.bytes[k] != b.bytes[k];
        retries += differ <= 2;
      }
    }
  }
  EXPECT_GT(runs, 2u);
  EXPECT_GT(retries, 2u);
}

TEST(BusMaster, CorruptRepliesHitTheByteCountAndKeepTheirLatency) {
  std::size_t damaged = 0, count_hit = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BusTimeline t =
        BusMaster(bus_with(seed, {Dialect::Gsl, Dialect::Hybrid}, "corrupt=20")).run();
    for (std::size_t i = 0; i < t.events.size(); ++i) {
      const BusEvent& e = t.events[i];
      if (e.role != Role::Response || !is_damaged_frame(e)) continue;
      ++damaged;
      EXPECT_EQ(e.fault, "corrupt");
      EXPECT_TRUE(e.values.empty());
      EXPECT_EQ(e.start - t.events[i - 1].end, e.latency);
      EXPECT_FALSE(lists(t.timeouts, t.events[i - 1])) << "a damaged reply is no timeout";
      count_hit += e.bytes[2] + 5u != e.bytes.size();
    }
  }
  EXPECT_GT(damaged, 100u);
  EXPECT_GT(count_hit, 0u) << "the byte count is damaged too";
}

// A reply damaged in its data keeps the length its header gives, and the master's next request,
// always a good one, follows within 8-15 ms (or the next round's, later): that request alone
// pins its end.
TEST(BusMaster, RepliesDamagedInTheirDataAreFollowedCloselyByAGoodRequest) {
  std::size_t damaged = 0, close = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BusTimeline t =
        BusMaster(bus_with(seed, kMixed, "corrupt_data=15,corrupt_request=15")).run();
    for (std::size_t i = 0; i < t.events.size(); ++i) {
      const BusEvent& e = t.events[i];
      if (e.fault != "corrupt_data" || e.kind != BusEvent::Kind::Frame) continue;
      ++damaged;
      EXPECT_EQ(e.role, Role::Response);
      EXPECT_FALSE(e.check_ok);
      EXPECT_GE(e.station, 1u);
      EXPECT_LE(e.station, 3u);
      if (e.dialect != Dialect::Ascii) {
        EXPECT_EQ(e.bytes[2] + 5u, e.bytes.size());
      }
      EXPECT_FALSE(lists(t.timeouts, t.events[i - 1])) << "a damaged reply is no timeout";
      if (i + 1 == t.events.size()) continue;
      const BusEvent& next = t.events[i + 1];
      EXPECT_EQ(next.kind, BusEvent::Kind::Frame);
      EXPECT_EQ(next.role, Role::Request);
      EXPECT_TRUE(next.check_ok) << "the request that pins it is good";
      EXPECT_GE(next.start - e.end, 8'000);
      close += next.start - e.end <= 15'000;
    }
  }
  EXPECT_GT(damaged, 50u);
  EXPECT_GT(close, damaged / 2);
}

// Both ends of every damaged frame pinned: it follows a frame, never noise (a reply not even
// noise from the slave side), and is followed by a good frame or by at least 100 ms of silence.
TEST(BusMaster, DamagedFramesArePinnedAtBothEnds) {
  std::size_t checked = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BusTimeline t = BusMaster(bus_with(seed, kMixed,
                                             "corrupt=8,corrupt_request=8,noise=15,missing=4,"
                                             "duplicate=4,slow=4,error_reply=4"))
                              .run();
    for (std::size_t i = 0; i < t.events.size(); ++i) {
      const BusEvent& e = t.events[i];
      if (!is_damaged_frame(e)) continue;
      ++checked;
      ASSERT_GT(i, 0u);
      EXPECT_EQ(t.events[i - 1].kind, BusEvent::Kind::Frame) << "damaged frame after noise";
      for (std::size_t j = i; e.role == Role::Response && j-- > 0;) {
        if (t.events[j].role == Role::Request) continue;
        EXPECT_EQ(t.events[j].kind, BusEvent::Kind::Frame) << "slave-side noise before it";
        break;
      }
      if (i + 1 == t.events.size()) continue;  // the end of the capture pins it
      const BusEvent& next = t.events[i + 1];
      const bool good_frame = next.kind == BusEvent::Kind::Frame && next.check_ok;
      EXPECT_TRUE(good_frame || next.start - e.end >= 100'000)
          << "damaged frame at " << e.start << " not pinned at its end";
    }
  }
  EXPECT_GT(checked, 50u);
}

TEST(BusMaster, AsciiDamageThatBreaksAFrameIsNoiseInTheTruth) {
  std::size_t request_noise = 0, reply_noise = 0, bad_frames = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BusTimeline t =
        BusMaster(bus_with(seed, {Dialect::Ascii}, "corrupt=15,corrupt_request=15")).run();
    for (std::size_t i = 0; i < t.events.size(); ++i) {
      const BusEvent& e = t.events[i];
      if (is_damaged_frame(e)) {
        ++bad_frames;
        // Its check is bad, and its delimiters and hex digits are all there.
        EXPECT_EQ(reading_of(e.bytes, e.bytes, Dialect::Ascii), DamageReading::BadCheckFrame);
        EXPECT_EQ(e.bytes[0], e.role == Role::Request ? 0x05 : 0x06);
        EXPECT_TRUE(e.bytes[3] == 'R' && e.bytes.back() == 0x04);
      }
      if (e.kind != BusEvent::Kind::Noise) continue;
      ASSERT_NE(e.fault, "noise") << "no noise fault in this plan";
      if (e.fault == "corrupt_request") {
        // No request to a reader: neither a timeout nor an unanswered damaged request.
        ++request_noise;
        EXPECT_EQ(e.bytes.size(), 15u);
        EXPECT_EQ(e.role, Role::Request);
        EXPECT_FALSE(lists(t.timeouts, e));
        EXPECT_FALSE(lists(t.unanswered_damaged_requests, e));
      } else {
        // No reply to a reader: its request timed out.
        ++reply_noise;
        EXPECT_EQ(e.fault, "corrupt");
        const BusEvent& request = t.events[i - 1];
        EXPECT_TRUE(lists(t.timeouts, request) || lists(t.unanswered_at_end, request));
      }
    }
  }
  EXPECT_GT(request_noise, 10u);
  EXPECT_GT(reply_noise, 10u);
  EXPECT_GT(bad_frames, 10u);
}

std::string slurp(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(GroundTruth, KeepsTimeoutsDamagedRepliesAndIgnoredRequestsApart) {
  const SimConfig c = bus_with(5, kMixed, "corrupt=8,corrupt_request=8,missing=8");
  const BusTimeline t = BusMaster(c).run();
  std::size_t damaged_replies = 0;
  for (const BusEvent& e : t.events)
    damaged_replies += is_damaged_frame(e) && e.role == Role::Response;
  const std::string path = ::testing::TempDir() + "sim_truth.json";
  ASSERT_EQ(write_ground_truth(t, c, path), "");
  const std::string json = slurp(path);
  auto has = [&](const std::string& text) { return json.find(text) != std::string::npos; };
  EXPECT_TRUE(has("\"timeouts\":" + std::to_string(t.timeouts.size()) + ","));
  EXPECT_TRUE(has("\"damaged_replies\":" + std::to_string(damaged_replies) + ","));
  EXPECT_TRUE(has("\"unanswered_damaged_requests\":" +
                  std::to_string(t.unanswered_damaged_requests.size()) + ","));
  EXPECT_TRUE(has("\"unanswered_damaged_requests\":[\n{\"request_ts\":"));
  EXPECT_TRUE(has("\"fault\":\"corrupt_request\""));
  EXPECT_GT(damaged_replies, 0u);
  EXPECT_GT(t.unanswered_damaged_requests.size(), 0u);
}

}  // namespace
}  // namespace pvtap::sim

namespace pvtap::sim {
namespace {

// The words of every good reply of `station` to `function` at `start`, parsed back.
std::vector<WordList> replies_of(const BusTimeline& t, std::uint8_t station) {
  std::vector<WordList> out;
  for (const BusEvent& e : t.events) {
    if (e.kind != BusEvent::Kind::Frame || e.station != station || e.role != Role::Response ||
        !e.check_ok)
      continue;
    const auto parsed = parse_frame(e.bytes, Dialect::Modbus, Role::Response);
    if (parsed) out.push_back(parsed->words);
  }
  return out;
}

// Each configuration built anew: copying one trips g++ 14's -Warray-bounds on its one-element
// vector of dialects, a false positive that -Werror turns into a failed build.
SimConfig meter_bus(bool low_first) {
  SimConfig c;
  c.inverters = 0;
  c.meter_station = 11;
  c.duration_s = 10;
  c.meter_low_first = low_first;
  return c;
}

TEST(Devices, MeterWordOrderSwapsTheWordsOfEveryFloat) {
  const SimConfig high = meter_bus(false);
  const SimConfig low = meter_bus(true);
  const std::vector<WordList> a = replies_of(BusMaster(high).run(), 11);
  const std::vector<WordList> b = replies_of(BusMaster(low).run(), 11);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  std::size_t floats = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].size(), b[i].size());
    for (std::size_t w = 0; w + 1 < a[i].size(); w += 2, ++floats) {
      EXPECT_EQ(a[i][w], b[i][w + 1]);
      EXPECT_EQ(a[i][w + 1], b[i][w]);
    }
  }
  EXPECT_GT(floats, 10u);
  const auto layout = BusMaster(low).run().devices.at(0).layout;
  ASSERT_FALSE(layout.empty());
  EXPECT_TRUE(std::all_of(layout.begin(), layout.end(), [](auto& l) { return l.low_first; }));
}

// The battery's layout is what its words hold: signed values change sign, the counter only
// grows and wraps its low word, the fill words are fill, the text is printable.
TEST(Devices, BatteryWordsHoldWhatItsLayoutSays) {
  SimConfig c;
  c.inverters = 0;
  c.battery_station = 5;
  c.duration_s = 600;
  const BusTimeline t = BusMaster(c).run();
  ASSERT_EQ(t.devices.size(), 1u);
  EXPECT_EQ(t.devices[0].label.kind, "battery");
  std::vector<WordList> status;
  std::string text;
  for (const WordList& w : replies_of(t, 5)) {
    if (w.size() == Battery::kStatusCount) status.push_back(w);
    if (w.size() == Battery::kNameCount && text.empty())
      for (std::uint16_t x : w) text += {static_cast<char>(x >> 8), static_cast<char>(x & 0xFF)};
  }
  ASSERT_GT(status.size(), 50u);
  bool negative = false, positive = false;
  std::uint32_t last = 0;
  bool wrapped = false;
  for (const WordList& w : status) {
    const auto current = static_cast<std::int16_t>(w[1]);
    negative = negative || current < -50;
    positive = positive || current > 50;
    const std::uint32_t energy = std::uint32_t{w[4]} << 16 | w[5];
    EXPECT_GE(energy, last);
    wrapped = wrapped || (last != 0 && w[5] < (last & 0xFFFF));
    last = energy;
    EXPECT_EQ(w[10], 0xFFFF);
    EXPECT_EQ(w[13], 0x8000);
    // s32, low word first: the high word is the low word's sign.
    EXPECT_EQ(w[7], static_cast<std::int16_t>(w[6]) < 0 ? 0xFFFF : 0x0000);
  }
  EXPECT_TRUE(negative && positive);
  EXPECT_TRUE(wrapped);
  EXPECT_EQ(text.substr(0, 12), "PVTAP-BAT-5K");
  EXPECT_EQ(t.devices[0].layout.size(), 14u);
}

}  // namespace
}  // namespace pvtap::sim
