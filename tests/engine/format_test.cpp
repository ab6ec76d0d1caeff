// Tests for engine/format.hpp: numbers read as Lua's tostring writes them, and every NaN
// (whatever its sign bit: 0/0 on x86 has it set, and printf then writes "-nan") reads "nan".
#include "engine/format.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rigidlab {
namespace {

TEST(FormatNumber, WritesLikeLuaTostring) {
  EXPECT_EQ(format_number(2.0), "2");
  EXPECT_EQ(format_number(-1.5), "-1.5");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(1e200), "1e+200");
  EXPECT_EQ(format_number(1.0 / 3.0), "0.33333333333333");
  EXPECT_EQ(format_number(1.0 / 3.0, 3), "0.333");
}

TEST(FormatNumber, NonFiniteValuesReadNanAndInf) {
  volatile double zero = 0.0;  // computed at run time, as a script's 0/0 is
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(format_number(zero / zero), "nan");
  EXPECT_EQ(format_number(nan), "nan");
  EXPECT_EQ(format_number(-nan), "nan");
  EXPECT_EQ(format_number(1.0 / zero), "inf");
  EXPECT_EQ(format_number(-1.0 / zero), "-inf");
}

}  // namespace
}  // namespace rigidlab
