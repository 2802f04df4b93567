// ValueJsonCache: a value object copied from what the cache rendered before is the object
// write_value_json renders afresh, whatever repeats or changes between values.
#include "writers/value_json_cache.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "pvtap/registers/register_decoder.h"
#include "report/value_json.h"

namespace pvtap::analyzer {
namespace {

std::string fresh(const DecodedValue& v, Dialect d) {
  std::string out;
  JsonWriter w(out);
  write_value_json(w, v, d);
  return out;
}

std::string cached(ValueJsonCache& cache, const DecodedValue& v, Dialect d, std::uint8_t station) {
  std::string out;
  JsonWriter w(out);
  cache.write(w, v, d, station);
  return out;
}

struct Read {
  Dialect dialect;
  std::uint16_t start;
  std::size_t count;
};

// The built-in maps' blocks (GSL's text model name, numbers, enums and bits; Hybrid's device
// number and BCD), cut short at times, with words drawn from a few choices so that readings
// repeat, change, and come back, from two stations.
TEST(ValueJsonCache, KeptReadingsAreTheFreshRendering) {
  const RegisterDecoder decoder;
  const std::vector<Read> reads = {{Dialect::Gsl, 1000, 10},
                                   {Dialect::Gsl, 1030, 4},
                                   {Dialect::Gsl, 1050, 23},
                                   {Dialect::Hybrid, 0x1000, 38},
                                   {Dialect::Hybrid, 0x1060, 2}};
  std::mt19937 random(39);
  const std::uint16_t choices[] = {0, 1, 0x2080, 0x4142, 0xFFFF, 0x8000, 0x1234};
  ValueJsonCache cache;
  std::size_t values = 0;
  for (int round = 0; round < 2000; ++round) {
    const Read& read = reads[random() % reads.size()];
    std::vector<std::uint16_t> words(read.count - (random() % 8 == 0 ? 1 : 0));
    for (std::uint16_t& word : words) word = choices[random() % (round % 3 == 0 ? 7 : 2)];
    const auto station = static_cast<std::uint8_t>(1 + random() % 2);
    std::vector<DecodedValue> decoded;
    decoder.decode_block(read.dialect, read.start, words, ValueOrigin::ReadReply, decoded);
    for (const DecodedValue& v : decoded) {
      ASSERT_EQ(cached(cache, v, read.dialect, station), fresh(v, read.dialect))
          << "round " << round << ", register " << v.address;
      ++values;
    }
  }
  EXPECT_GT(values, 10000u);
}

// Two values of one register that differ only in a warning (a reading without its scale
// factor, say) are two renderings.
TEST(ValueJsonCache, AWarningChangesTheRendering) {
  const RegisterDecoder decoder;
  std::vector<DecodedValue> decoded;
  const std::uint16_t word = 2301;
  decoder.decode_block(Dialect::Gsl, 1050, std::span(&word, 1), ValueOrigin::ReadReply, decoded);
  ASSERT_EQ(decoded.size(), 1u);
  ValueJsonCache cache;
  DecodedValue v = decoded[0];
  const std::string plain = cached(cache, v, Dialect::Gsl, 1);
  EXPECT_EQ(cached(cache, v, Dialect::Gsl, 1), plain);
  v.add(ValueWarning::NoScaleFactor);
  EXPECT_EQ(cached(cache, v, Dialect::Gsl, 1), fresh(v, Dialect::Gsl));
  EXPECT_NE(cached(cache, v, Dialect::Gsl, 1), plain);
}

}  // namespace
}  // namespace pvtap::analyzer
