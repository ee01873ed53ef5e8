#include "omninav/io/natural_sort.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace omninav::io {
namespace {

TEST(NaturalSort, DigitRunsCompareByValue) {
  EXPECT_TRUE(natural_less("img2", "img10"));
  EXPECT_FALSE(natural_less("img10", "img2"));
  EXPECT_TRUE(natural_less("img1", "img2"));
  EXPECT_TRUE(natural_less("snapshot_2.png", "snapshot_10.png"));
  // Numbers longer than any integer type still compare by value.
  EXPECT_TRUE(natural_less("x99999999999999999999", "x100000000000000000000"));
}

TEST(NaturalSort, LaterRunsDecideWhenEarlierOnesTie) {
  EXPECT_TRUE(natural_less("run2_frame9", "run2_frame10"));
  EXPECT_TRUE(natural_less("run2_frame10", "run10_frame1"));
}

TEST(NaturalSort, PrefixSortsFirst) {
  EXPECT_TRUE(natural_less("img", "img1"));
  EXPECT_FALSE(natural_less("img1", "img"));
}

TEST(NaturalSort, CaseAndLeadingZerosOnlyBreakTies) {
  EXPECT_TRUE(natural_less("IMG2", "img10"));  // case ignored for the order
  EXPECT_TRUE(natural_less("img002", "img10"));
  // Equal in natural order: plain byte order decides, so the order is total.
  EXPECT_NE(natural_less("img01", "img1"), natural_less("img1", "img01"));
  EXPECT_NE(natural_less("IMG1", "img1"), natural_less("img1", "IMG1"));
}

TEST(NaturalSort, IsIrreflexive) {
  for (const char* name : {"", "a", "img10", "007"}) EXPECT_FALSE(natural_less(name, name));
}

TEST(NaturalSort, SortsShuffledFileNamesByName) {
  const std::vector<std::string> expected = {"img1.png",  "img2.png",  "img3.png",  "img9.png",
                                             "img10.png", "img11.png", "img20.png", "img100.png"};
  std::vector<std::filesystem::path> files;
  for (const std::string& name : expected)
    files.push_back(std::filesystem::path("/data/run") / name);
  std::mt19937 random(42);
  std::shuffle(files.begin(), files.end(), random);

  natural_sort(files);

  ASSERT_EQ(files.size(), expected.size());
  for (std::size_t i = 0; i < files.size(); ++i) EXPECT_EQ(files[i].filename(), expected[i]);
}

TEST(NaturalSort, OrdersByFileNameNotFolder) {
  std::vector<std::filesystem::path> files = {"b/img2.png", "a/img10.png"};
  natural_sort(files);
  EXPECT_EQ(files[0], "b/img2.png");
}

}  // namespace
}  // namespace omninav::io
