// Unit tests of the simulator's parts: register images read back through the core's decoder,
// fault plans, determinism, and frames that the core parses as sent.
#include <gtest/gtest.h>

#include <algorithm>

#include "bus_master.h"
#include "fault_plan.h"
#include "frame_shapes.h"
#include "pvtap/frame_codec.h"
#include "pvtap/register_decoder.h"
#include "register_image.h"

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
    const ParseOutcome parsed = parse_frame(e.bytes, e.dialect, e.role);
    ASSERT_TRUE(parsed) << parsed.error;
    EXPECT_EQ(parsed.frame->station, e.station);
    EXPECT_EQ(parsed.frame->function, e.function);
  }
}

}  // namespace
}  // namespace pvtap::sim
