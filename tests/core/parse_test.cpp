#include "omninav/core/parse.hpp"

#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

TEST(Parse, NumbersWithBlanks) {
  EXPECT_DOUBLE_EQ(parse_double(" 12.5 ", "f:1"), 12.5);
  EXPECT_DOUBLE_EQ(parse_double("-3e2", "f:1"), -300.0);
  EXPECT_EQ(parse_int(" 42\r", "f:1"), 42);
}

TEST(Parse, GarbageNamesWhere) {
  try {
    parse_double("12abc", "entries.csv:7");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "entries.csv:7: '12abc' is not a number");
  }
  EXPECT_THROW(parse_double("", "x"), InputError);
  EXPECT_THROW(parse_double("nan", "x"), InputError);
  EXPECT_THROW(parse_int("4.5", "x"), InputError);
}

TEST(Split, KeepsEmptyFieldsAndTrims) {
  const std::vector<std::string> fields = split(" a, b ,,c ", ',');
  ASSERT_EQ(fields.size(), 4u);
  EXPECT_EQ(fields[0], "a");
  EXPECT_EQ(fields[1], "b");
  EXPECT_EQ(fields[2], "");
  EXPECT_EQ(fields[3], "c");
}

}  // namespace
}  // namespace omninav
