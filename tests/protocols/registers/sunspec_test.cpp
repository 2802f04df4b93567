// SunSpec devices: the chain learned from a master's reads, the map it makes, scale factors and
// "no value" marks, and the chain written into a map file.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_format.h"
#include "pvtap/registers/sunspec.h"

namespace pvtap {
namespace {

constexpr std::uint8_t kStation = 7;

Frame read_request(std::uint16_t start, std::uint16_t count) {
  Frame f;
  f.dialect = Dialect::Modbus;
  f.role = Role::Request;
  f.station = kStation;
  f.function = fc::kGslReadHolding;
  f.start = start;
  f.count = count;
  return f;
}

Frame read_reply(const std::vector<std::uint16_t>& words) {
  Frame f;
  f.dialect = Dialect::Modbus;
  f.role = Role::Response;
  f.station = kStation;
  f.function = fc::kGslReadHolding;
  for (const std::uint16_t w : words) f.words.push_back(w);
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  return f;
}

// Decodes a read of `words` at `start`, as a session does with a request and its reply.
std::vector<DecodedValue> read(const RegisterDecoder& decoder, std::uint16_t start,
                               const std::vector<std::uint16_t>& words) {
  const Frame request = read_request(start, static_cast<std::uint16_t>(words.size()));
  std::vector<DecodedValue> out;
  decoder.decode(read_reply(words), &request, out);
  return out;
}

const DecodedValue* find(const std::vector<DecodedValue>& values, std::string_view key) {
  for (const DecodedValue& v : values) {
    if (v.key() == key) return &v;
  }
  return nullptr;
}

// Model 103's 50 registers, with a current of 12.34 A (A_SF -2), phase A at 230.1 V (V_SF -1),
// 5000 W (W_SF 0), 50.01 Hz (Hz_SF -2) and a sink temperature that is not implemented.
std::vector<std::uint16_t> inverter_block() {
  std::vector<std::uint16_t> w(50, 0);
  w[0] = 1234;
  w[4] = 0xFFFE;  // A_SF -2
  w[8] = 2301;
  w[11] = 0xFFFF;  // V_SF -1
  w[12] = 5000;
  w[13] = 0;
  w[14] = 5001;
  w[15] = 0xFFFE;
  w[32] = 0x8000;  // TmpSnk: not implemented
  w[36] = 4;       // St: MPPT
  return w;
}

TEST(SunSpecLearner, FollowsTheScanHeaderByHeader) {
  SunSpecLearner learner;
  const std::vector<std::uint16_t> other{0x5375, 0x6E53};
  EXPECT_FALSE(learner.learn(40010, other)) << "the marker counts only at a base a client scans";
  EXPECT_TRUE(learner.learn(40000, std::vector<std::uint16_t>{0x5375, 0x6E53}));
  EXPECT_TRUE(learner.found());
  EXPECT_TRUE(learner.learn(40002, std::vector<std::uint16_t>{1, 66}));
  EXPECT_FALSE(learner.learn(40004, std::vector<std::uint16_t>(66, 0))) << "a body holds no header";
  EXPECT_TRUE(learner.learn(40070, std::vector<std::uint16_t>{103, 50}));
  EXPECT_TRUE(learner.learn(40122, std::vector<std::uint16_t>{0xFFFF, 0}));
  const SunSpecChain& chain = learner.chain();
  EXPECT_EQ(chain.base, 40000);
  ASSERT_EQ(chain.models.size(), 2u);
  EXPECT_EQ(chain.models[1].id, 103);
  EXPECT_EQ(chain.models[1].address, 40070);
  EXPECT_TRUE(chain.ended);
  EXPECT_FALSE(learner.learn(40122, std::vector<std::uint16_t>{160, 48})) << "the chain ended";
}

TEST(SunSpecLearner, ReadsSeveralHeadersInOneLongRead) {
  std::vector<std::uint16_t> words{0x5375, 0x6E53, 1, 4, 0, 0, 0, 0, 64110, 2, 9, 9, 0xFFFF, 0};
  SunSpecLearner learner;
  EXPECT_TRUE(learner.learn(0, words));
  ASSERT_EQ(learner.chain().models.size(), 2u);
  EXPECT_EQ(learner.chain().models[1].id, 64110);
  EXPECT_TRUE(learner.chain().ended);
}

TEST(SunSpecMap, NamesEveryPointOfTheKnownModels) {
  SunSpecChain chain;
  chain.base = 40000;
  ASSERT_TRUE(chain.append(1, 66));
  ASSERT_TRUE(chain.append(103, 50));
  ASSERT_TRUE(chain.append(160, 48));   // two MPPT modules
  ASSERT_TRUE(chain.append(64110, 4));  // a vendor's model pvtap does not know
  RegisterMapResult result = sunspec_register_map(chain, "test");
  ASSERT_TRUE(result) << result.error_text();
  const RegisterMap& map = result.value();
  EXPECT_EQ(map.dialect(), Dialect::Modbus);
  const RegisterDef* w = map.find_key("m103_w");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->address, 40072 + 12);
  EXPECT_EQ(w->name, "inverter (three phase): AC power");
  EXPECT_EQ(w->scale_factor, "m103_w_sf");
  EXPECT_EQ(w->scale_factor_address, 40072 + 13);
  EXPECT_TRUE(map.find_key("m103_w_sf")->is_scale_factor);
  EXPECT_EQ(map.find_key("m1_mn")->kind, RegisterKind::Text);
  const RegisterDef* module2 = map.find_key("m160_2_dcv");
  ASSERT_NE(module2, nullptr);
  EXPECT_EQ(module2->address, 40122 + 2 + 8 + 20 + 10);
  EXPECT_EQ(module2->scale_factor, "m160_dcv_sf");
  EXPECT_NE(map.find_key("m64110_id"), nullptr) << "an unknown model's header is still named";
  EXPECT_EQ(map.locate(40174 + 2), std::nullopt) << "its body is left to inference";
  EXPECT_EQ(sunspec_model_name(160), "multiple MPPT inverter extension");
}

TEST(SunSpecDecoding, LearnsTheChainFromTheScanThenScalesByTheFactors) {
  RegisterDecoder decoder;
  EXPECT_EQ(decoder.station_map(kStation), nullptr);
  read(decoder, 40000, {0x5375, 0x6E53});
  read(decoder, 40002, {1, 66});
  read(decoder, 40070, {103, 50});
  ASSERT_NE(decoder.station_map(kStation), nullptr);
  ASSERT_NE(decoder.sunspec_chain(kStation), nullptr);
  const std::vector<DecodedValue> v = read(decoder, 40072, inverter_block());
  const DecodedValue* amps = find(v, "m103_a");
  ASSERT_NE(amps, nullptr);
  EXPECT_DOUBLE_EQ(amps->value, 12.34);
  EXPECT_EQ(format_value(*amps), "12.34 A");  // two digits, as A_SF -2 gives
  EXPECT_DOUBLE_EQ(find(v, "m103_phvpha")->value, 230.1);
  EXPECT_DOUBLE_EQ(find(v, "m103_w")->value, 5000.0);
  EXPECT_DOUBLE_EQ(find(v, "m103_hz")->value, 50.01);
  const DecodedValue* sink = find(v, "m103_tmpsnk");
  ASSERT_NE(sink, nullptr);
  EXPECT_TRUE(sink->has(ValueWarning::NoValue));
  EXPECT_EQ(format_value(*sink), "no value (0x8000)");
  EXPECT_EQ(format_value(*find(v, "m103_st")), "mppt");
}

TEST(SunSpecDecoding, RemembersScaleFactorsReadBefore) {
  RegisterDecoder decoder;
  read(decoder, 40000, {0x5375, 0x6E53, 103, 50});
  // A read of the current alone, before any scale factor: shown unscaled, flagged.
  std::vector<DecodedValue> v = read(decoder, 40004, {1234});
  ASSERT_NE(find(v, "m103_a"), nullptr);
  EXPECT_TRUE(find(v, "m103_a")->has(ValueWarning::NoScaleFactor));
  read(decoder, 40004, inverter_block());
  v = read(decoder, 40004, {1500});
  EXPECT_FALSE(find(v, "m103_a")->has(ValueWarning::NoScaleFactor));
  EXPECT_DOUBLE_EQ(find(v, "m103_a")->value, 15.0);
}

TEST(SunSpecDecoding, AGivenMapOrTheOptionTurnsLearningOff) {
  RegisterDecoder off(DecoderOptions{GslIdReading::Decimal, PairRule::Binary, false});
  read(off, 40000, {0x5375, 0x6E53, 103, 50});
  EXPECT_EQ(off.station_map(kStation), nullptr);
  RegisterDecoder given;
  RegisterMapResult meter = load_register_map(
      "dialect = \"modbus\"\n[[register]]\naddress = 0\nkey = \"x\"\nname = \"x\"\n", "m.toml");
  ASSERT_TRUE(meter);
  given.use_station_map(kStation, meter.value());
  read(given, 40000, {0x5375, 0x6E53, 103, 50});
  EXPECT_EQ(given.sunspec_chain(kStation), nullptr);
  EXPECT_EQ(given.station_map(kStation)->find_key("m103_w"), nullptr);
}

TEST(SunSpecDecoding, ForgetsWhatItLearnedWhenAsked) {
  RegisterDecoder decoder;
  read(decoder, 40000, {0x5375, 0x6E53, 103, 50});
  ASSERT_NE(decoder.station_map(kStation), nullptr);
  decoder.forget_learned();
  EXPECT_EQ(decoder.station_map(kStation), nullptr);
}

TEST(SunSpecMapFile, TheChainInAMapFileDecodesWithoutTheScan) {
  constexpr std::string_view kDraft = R"toml(dialect = "modbus"
[sunspec]
base = 40000
models = [[1, 66], [103, 50]]
ended = true

[[register]]
address = 40084
key = "ac_power"
name = "AC power, renamed"
unit = "W"
signed = true
scale_factor = "m103_w_sf"
)toml";
  RegisterMapResult result = load_register_map(kDraft, "station-7.toml");
  ASSERT_TRUE(result) << result.error_text();
  RegisterDecoder decoder;
  decoder.use_station_map(kStation, result.value());
  const std::vector<DecodedValue> v = read(decoder, 40072, inverter_block());
  ASSERT_NE(find(v, "ac_power"), nullptr) << "the file's entry wins over the model's";
  EXPECT_EQ(find(v, "m103_w"), nullptr);
  EXPECT_DOUBLE_EQ(find(v, "ac_power")->value, 5000.0);
  EXPECT_DOUBLE_EQ(find(v, "m103_phvpha")->value, 230.1);
  EXPECT_NE(result.value().find_key("sunspec_end_id"), nullptr);
}

TEST(SunSpecMapFile, RejectsWhatIsNoChain) {
  for (const std::string_view bad : {
           std::string_view("dialect = \"gsl\"\n[sunspec]\nbase = 40000\nmodels = []\n"),
           std::string_view("dialect = \"modbus\"\n[sunspec]\nmodels = [[1, 66]]\n"),
           std::string_view("dialect = \"modbus\"\n[sunspec]\nbase = 40000\nmodels = [[1]]\n"),
           std::string_view("dialect = \"modbus\"\n[sunspec]\nbase = 65000\n"
                            "models = [[1, 66], [103, 60000]]\n"),
           // Numbers that are not integers: a float beyond int64 was converted unchecked.
           std::string_view(
               "dialect = \"modbus\"\n[sunspec]\nbase = 40000\nmodels = [[1, 1e33]]\n"),
           std::string_view(
               "dialect = \"modbus\"\n[sunspec]\nbase = 40000.0\nmodels = [[1, 66]]\n"),
       }) {
    const RegisterMapResult result = load_register_map(bad, "bad.toml");
    EXPECT_FALSE(result) << bad;
    if (!result) {
      EXPECT_NE(result.error_text().find("[sunspec]"), std::string::npos);
    }
  }
}

TEST(ScaleFactorEntries, MustNameAOneWordSignedNumber) {
  const RegisterMapResult result = load_register_map(
      "dialect = \"modbus\"\n[[register]]\naddress = 0\nkey = \"w\"\nname = \"w\"\n"
      "scale_factor = \"w_sf\"\n[[register]]\naddress = 1\nkey = \"w_sf\"\nname = \"sf\"\n"
      "no_value = 0x10000\n",
      "sf.toml");
  ASSERT_FALSE(result);
  EXPECT_NE(result.error_text().find("one-word signed number"), std::string::npos);
  EXPECT_NE(result.error_text().find("no_value"), std::string::npos);
}

}  // namespace
}  // namespace pvtap
