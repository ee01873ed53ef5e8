#include "omninav/core/output_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

namespace fs = std::filesystem;

class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("omninav_output_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string read(const fs::path& file) {
    std::ifstream stream(file, std::ios::binary);
    std::ostringstream text;
    text << stream.rdbuf();
    return text.str();
  }
  // The message of the InputError `write` throws, "" when it throws none.
  template <typename Write>
  static std::string error_of(Write&& write) {
    try {
      write();
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(OutputFileTest, ReplacesTheFileWholeAndLeavesNothingElse) {
  const fs::path file = dir_ / "table.csv";
  std::ofstream(file) << "old";
  {
    OutputFile out(file);
    EXPECT_EQ(out.temporary().parent_path(), dir_);
    EXPECT_NE(out.temporary(), file);
    out.stream() << "new,rows\n";
    EXPECT_EQ(read(file), "old") << "the old file stays until the commit";
    out.commit();
  }
  EXPECT_EQ(read(file), "new,rows\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"table.csv"});
}

TEST_F(OutputFileTest, AnAbandonedFileLeavesTheOldOneAndNoTemporary) {
  const fs::path file = dir_ / "picture.png";
  std::ofstream(file) << "old";
  {
    OutputFile out(file);
    out.stream() << "half a picture";
  }
  EXPECT_EQ(read(file), "old");
  EXPECT_EQ(entries(), std::vector<std::string>{"picture.png"});
}

TEST_F(OutputFileTest, TwoWritersOfOneFileHaveTheirOwnTemporaries) {
  OutputFile first(dir_ / "map.vmem"), second(dir_ / "map.vmem");
  EXPECT_NE(first.temporary(), second.temporary());
  EXPECT_EQ(first.temporary().extension(), ".vmem");
}

TEST_F(OutputFileTest, FailuresNameTheFileAndLeaveNothing) {
  const std::string missing_folder =
      error_of([&] { write_output_file(dir_ / "no" / "such.csv", "x"); });
  EXPECT_NE(missing_folder.find("such.csv: cannot write"), std::string::npos) << missing_folder;
  const std::string full = error_of([&] { write_output_file("/dev/full", "x"); });
  EXPECT_EQ(full, "/dev/full: cannot write (No space left on device)");
  const std::string full_stream = error_of([&] {
    OutputFile out("/dev/full");
    out.stream() << std::string(100000, 'x');
    out.commit();
  });
  EXPECT_NE(full_stream.find("/dev/full: cannot write"), std::string::npos) << full_stream;
  // A device is written, never replaced by a regular file (as root a rename would replace it).
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  const std::string folder = error_of([&] { write_output_file(dir_, "x"); });
  EXPECT_NE(folder.find("it is a folder"), std::string::npos) << folder;
  EXPECT_TRUE(entries().empty());
}

TEST_F(OutputFileTest, ALinkIsWrittenThroughAndStaysALink) {
  fs::create_directories(dir_ / "real");
  fs::create_symlink("real/target.csv", dir_ / "link.csv");  // dangling until written
  write_output_file(dir_ / "link.csv", "first");
  write_output_file(dir_ / "link.csv", "second");
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.csv"));
  EXPECT_EQ(read(dir_ / "real" / "target.csv"), "second");
  EXPECT_EQ(entries(), (std::vector<std::string>{"link.csv", "real"}));
}

TEST_F(OutputFileTest, OutputPathsAreCheckedBeforeTheWork) {
  EXPECT_NO_THROW(check_output_path(dir_ / "new.png"));
  EXPECT_NE(error_of([&] { check_output_path(dir_ / "no" / "x.png"); }).find("x.png"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_output_path(dir_); }).find("it is a folder"), std::string::npos);
}

TEST_F(OutputFileTest, StaleTemporariesOfAKilledWriterAreRemoved) {
  const fs::path file = dir_ / "map.vmem";
  std::ofstream(dir_ / ".map.a1B2c3.vmem") << "killed";
  std::ofstream(dir_ / ".other.a1B2c3.vmem") << "someone else's";
  std::ofstream(file) << "map";
  remove_stale_temporaries(file);
  EXPECT_EQ(entries(), (std::vector<std::string>{".other.a1B2c3.vmem", "map.vmem"}));
}

TEST_F(OutputFileTest, LostStandardOutputIsAnError) {
  std::fflush(stdout);
  const int saved = ::dup(1);
  const int full = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(full, 0);
  ::dup2(full, 1);
  std::cout << "a result line\n";
  const std::string error = error_of([] { flush_standard_output(); });
  ::dup2(saved, 1);
  ::close(saved);
  ::close(full);
  EXPECT_NE(error.find("standard output: cannot write"), std::string::npos) << error;
  EXPECT_NO_THROW(flush_standard_output()) << "the error is not sticky";
}

TEST_F(OutputFileTest, AnOutputThatIsAnInputIsRefusedWhateverItsSpelling) {
  const fs::path map = dir_ / "room.vmem";
  std::ofstream(map) << "map";
  fs::create_symlink(map, dir_ / "link.vmem");
  fs::create_hard_link(map, dir_ / "hard.vmem");
  const fs::path dotted = dir_ / "." / "room.vmem";
  for (const fs::path& output : {map, dotted, dir_ / "link.vmem", dir_ / "hard.vmem"}) {
    SCOPED_TRACE(output.string());
    EXPECT_THROW(check_output_path(output, {map}), UsageError);
    EXPECT_THROW(check_not_an_input(map, {output}), UsageError);
  }
  EXPECT_NO_THROW(check_output_path(dir_ / "room.png", {map}));
  EXPECT_NO_THROW(check_output_path(map, {dir_ / "missing.vmem", {}}));
  EXPECT_EQ(read(map), "map");
}

}  // namespace
}  // namespace omninav
