#include "omninav/core/format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "omninav/core/json.hpp"

namespace omninav {
namespace {

TEST(Format, FixedRoundsToTheDigitsAsked) {
  EXPECT_EQ(fixed(2.0, 0), "2");
  EXPECT_EQ(fixed(2.25, 3), "2.250");
  EXPECT_EQ(fixed(-1.0 / 3.0, 4), "-0.3333");
  EXPECT_EQ(fixed(0.125, 2), "0.12") << "0.125 is exact: rounded half to even, as printf";
  EXPECT_EQ(fixed(1234567.891, 1), "1234567.9");
  EXPECT_EQ(fixed_or_empty(std::nullopt, 2), "");
  EXPECT_EQ(fixed_or_empty(1.5, 2), "1.50");
}

TEST(Format, SignedFixedAlwaysHasASign) {
  EXPECT_EQ(signed_fixed(2.34, 1), "+2.3");
  EXPECT_EQ(signed_fixed(-0.5, 1), "-0.5");
  EXPECT_EQ(signed_fixed(0.0, 1), "+0.0");
}

TEST(Format, TrimmedDropsTrailingZeros) {
  EXPECT_EQ(trimmed(1.2, 3), "1.2");
  EXPECT_EQ(trimmed(2.0, 3), "2");
  EXPECT_EQ(trimmed(100.0, 2), "100");
  EXPECT_EQ(trimmed(-0.0001, 3), "0");
  EXPECT_EQ(trimmed(0.30000000000000004, 3), "0.3");
}

TEST(Format, GeneralAndShortest) {
  EXPECT_EQ(general(0.5), "0.5");
  EXPECT_EQ(general(1e-7), "1e-07");
  EXPECT_EQ(general(123456789.0), "1.23457e+08");
  EXPECT_EQ(general(2.0 / 3.0, 3), "0.667");
  EXPECT_EQ(shortest(0.1), "0.1");
  EXPECT_EQ(shortest(-1500.0), "-1500");
  for (const double value : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, -2.5e-9}) {
    EXPECT_EQ(std::stod(shortest(value)), value) << shortest(value);
  }
}

TEST(Format, RoundedIsTheDoubleOfTheFixedText) {
  EXPECT_EQ(rounded(1.23456, 3), 1.235);
  EXPECT_EQ(rounded(-0.00004, 4), -0.0);
  EXPECT_EQ(rounded(2.0, 1), 2.0);
  EXPECT_TRUE(std::isnan(rounded(std::numeric_limits<double>::quiet_NaN(), 2)));
}

TEST(Json, NumbersAreRoundedAndMissingOnesNull) {
  Json object;
  object["b"] = json_number(0.123456, 4);
  object["a"] = json_number(std::nullopt, 2);
  object["c"] = json_number(std::numeric_limits<double>::infinity(), 2);
  object["d"] = json_number(12.0, 1);
  EXPECT_EQ(object.dump(), R"({"b":0.1235,"a":null,"c":null,"d":12.0})")
      << "keys in the order written";
  EXPECT_EQ(json_text(Json{{"name", "a\xff"}}), "{\n  \"name\": \"a\xEF\xBF\xBD\"\n}")
      << "a byte that is not UTF-8 becomes U+FFFD";
}

}  // namespace
}  // namespace omninav
