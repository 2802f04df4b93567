// DialectSet::then: a list of dialects read in its order, where the first named of GSL and
// plain Modbus takes the codes they share.
#include <gtest/gtest.h>

#include "pvtap/codec/dialect.h"

namespace pvtap {
namespace {

TEST(DialectSet, ModbusNamedBeforeGslIsPreferred) {
  const DialectSet modbus_first = DialectSet::none().then(Dialect::Modbus).then(Dialect::Gsl);
  EXPECT_TRUE(modbus_first.prefers_modbus());
  EXPECT_TRUE(modbus_first.contains(Dialect::Modbus));
  EXPECT_TRUE(modbus_first.contains(Dialect::Gsl));
  EXPECT_FALSE(modbus_first.contains(Dialect::Hybrid));

  const DialectSet gsl_first = DialectSet::none().then(Dialect::Gsl).then(Dialect::Modbus);
  EXPECT_FALSE(gsl_first.prefers_modbus());
  EXPECT_EQ(gsl_first.contains(Dialect::Modbus), modbus_first.contains(Dialect::Modbus));
}

TEST(DialectSet, OtherDialectsLeaveThePreferenceAlone) {
  EXPECT_FALSE(DialectSet::none().then(Dialect::Hybrid).then(Dialect::Ascii).prefers_modbus());
  EXPECT_TRUE(DialectSet::none().then(Dialect::Hybrid).then(Dialect::Modbus).prefers_modbus());
  EXPECT_EQ(DialectSet::none().then(Dialect::Ascii), DialectSet::only(Dialect::Ascii));
}

}  // namespace
}  // namespace pvtap
