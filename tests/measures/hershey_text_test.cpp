#include "omninav/measures/hershey_text.hpp"

#include <gtest/gtest.h>

namespace omninav::measures {
namespace {

TEST(HersheyText, SpellsOutTheSymbolsOfLabels) {
  EXPECT_EQ(hershey_text("Atm 0.6055 cap 4\u00b0"), "Atm 0.6055 cap 4 deg");
  EXPECT_EQ(hershey_text("heading \u00b1 1\u03c3 (\u00b0)"), "heading +/- 1sigma (deg)");
  EXPECT_EQ(hershey_text("360\u00d745, 0.3 \u2264 d \u2192 1"), "360x45, 0.3 <= d -> 1");
  EXPECT_EQ(hershey_text("plain ASCII, kept"), "plain ASCII, kept");
}

TEST(HersheyText, EveryOtherCharacterIsOneQuestionMark) {
  EXPECT_EQ(hershey_text("caf\u00e9 \u4e16\u754c"), "caf? ??");
  EXPECT_EQ(hershey_text(std::string("bad \xff\xfe byte")), "bad ?? byte");
  // A sequence cut short at the end is still one mark.
  EXPECT_EQ(hershey_text(std::string("cut \xe2\x86")), "cut ?");
}

}  // namespace
}  // namespace omninav::measures
