#include "omninav/core/csv.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

namespace fs = std::filesystem;

class CsvTest : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = fs::temp_directory_path() /
            ("omninav_csv_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv");
  }
  void TearDown() override { fs::remove(file_); }

  CsvTable read(const std::string& text) {
    std::ofstream(file_, std::ios::binary) << text;
    return CsvTable::read(file_);
  }

  // The message of the InputError reading `text` throws, or "" when it throws none.
  std::string error_of(const std::string& text) {
    try {
      read(text);
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }

  fs::path file_;
};

TEST(CsvField, QuotesOnlyFieldsThatNeedIt) {
  EXPECT_EQ(csv_field("plain text"), "plain text");
  EXPECT_EQ(csv_field("1.25"), "1.25");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("carriage\rreturn"), "\"carriage\rreturn\"");
}

TEST(CsvField, LineJoinsFieldsWithCommas) {
  EXPECT_EQ(csv_line({"a", "b,c", "", "3"}), "a,\"b,c\",,3\n");
  EXPECT_EQ(csv_line({}), "\n");
}

TEST_F(CsvTest, ReadsColumnsByNameTrimmedAndSkipsBlankLines) {
  const CsvTable table = read("\xEF\xBB\xBFx, y ,name\n\n 1 ,2, a \n  \n3,4,b\n");
  EXPECT_EQ(table.columns(), (std::vector<std::string>{"x", "y", "name"}));
  ASSERT_EQ(table.rows().size(), 2u);
  EXPECT_EQ(table.rows()[0].fields, (std::vector<std::string>{"1", "2", "a"}));
  EXPECT_EQ(table.rows()[0].line, 3);
  EXPECT_EQ(table.rows()[1].line, 5);
  EXPECT_EQ(table.require_column("name"), 2u);
  EXPECT_FALSE(table.find_column("z"));
  EXPECT_EQ(table.where(table.rows()[1]), file_.string() + ":5");
}

TEST_F(CsvTest, ReadsBackWhatTheWriterQuotes) {
  const std::vector<std::string> awkward{"a,b", "say \"hi\"", "two\nlines", "  kept  ", "x"};
  const CsvTable table = read(csv_line({"c1", "c2", "c3", "c4", "c5"}) + csv_line(awkward) +
                              csv_line({"1", "2", "3", "4", "5"}));
  ASSERT_EQ(table.rows().size(), 2u);
  // Unquoted fields are trimmed, so a field with outer blanks comes back trimmed.
  EXPECT_EQ(table.rows()[0].fields,
            (std::vector<std::string>{"a,b", "say \"hi\"", "two\nlines", "kept", "x"}));
  EXPECT_EQ(table.rows()[0].line, 2);
  EXPECT_EQ(table.rows()[1].line, 4) << "the quoted line break counts as a line";
  EXPECT_EQ(table.rows()[1].fields[4], "5");
}

TEST_F(CsvTest, QuotedFieldsKeepTheirBlanksAndCarriageReturnsEndLines) {
  const CsvTable table = read("a,b\r\n\" x \" , \"\"\r\n");
  ASSERT_EQ(table.rows().size(), 1u);
  EXPECT_EQ(table.rows()[0].fields, (std::vector<std::string>{" x ", ""}));
}

TEST_F(CsvTest, AQuoteInsideAnUnquotedFieldIsText) {
  const CsvTable table = read("a,b\n5'3\",x\"y\n");
  EXPECT_EQ(table.rows()[0].fields, (std::vector<std::string>{"5'3\"", "x\"y"}));
}

TEST_F(CsvTest, ErrorsNameTheFileAndLine) {
  EXPECT_NE(error_of("").find("no header row"), std::string::npos);
  EXPECT_NE(error_of("a,a\n").find("appears twice"), std::string::npos);
  EXPECT_NE(error_of("a,b\n1\n").find(file_.string() + ":2: 1 fields, but the header has 2"),
            std::string::npos);
  EXPECT_NE(
      error_of("a,b\n1,\"open\n\nmore\n").find(file_.string() + ":2: a quoted field is not closed"),
      std::string::npos);
  EXPECT_NE(error_of("a,b\n\"x\"y,1\n").find(file_.string() + ":2: text after the closing quote"),
            std::string::npos);
  EXPECT_THROW(CsvTable::read(file_.string() + ".missing"), InputError);
}

}  // namespace
}  // namespace omninav
