// Every omninav command line that README.md and docs/*.md show in their code blocks is one the
// program accepts: parsed and checked (commands, options, values, ranges) as the program would,
// without running it (check_command_line). A renamed flag or a removed command breaks this test,
// not the newcomer who copies the line.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "command_line_test.hpp"

namespace omninav::cli {
namespace {

std::filesystem::path config_dir() {
  return omninav::testing::config_dir();
}
const std::filesystem::path kSource = config_dir().parent_path();

struct Example {
  std::string where;  // file:line
  std::string line;   // the command line as written
};

// The lines of fenced code blocks that run omninav (continuations joined).
std::vector<Example> examples_in(const std::filesystem::path& file) {
  std::vector<Example> examples;
  std::ifstream in(file);
  std::string line, pending;
  bool in_code = false;
  int number = 0, start = 0;
  const std::regex program(R"(^\s*(\./)?(build/bin/)?omninav\s)");
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("```", 0) == 0) {
      in_code = !in_code;
      continue;
    }
    if (!in_code) continue;
    if (pending.empty() && !std::regex_search(line, program)) continue;
    if (pending.empty()) start = number;
    const bool continues = !line.empty() && line.back() == '\\';
    pending += continues ? line.substr(0, line.size() - 1) + " " : line;
    if (continues) continue;
    examples.push_back({file.filename().string() + ":" + std::to_string(start), pending});
    pending.clear();
  }
  return examples;
}

// The words of a shell command line up to a comment, pipe, redirection or `&&`, quotes removed.
std::vector<std::string> shell_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool has_word = false;
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote) {
        quote = 0;
      } else {
        word += c;
      }
      continue;
    }
    if (c == '\'' || c == '"') {
      quote = c;
      has_word = true;
    } else if (c == ' ' || c == '\t') {
      if (has_word) words.push_back(word);
      word.clear();
      has_word = false;
    } else if (!has_word && (c == '#' || c == '|' || c == '>' || c == ';' || c == '&')) {
      break;  // a comment, pipe, redirection or `&&` where a word would start: the command ends
    } else {
      word += c;
      has_word = true;
    }
  }
  if (has_word) words.push_back(word);
  return words;
}

TEST(DocsExamples, EveryCommandLineOfTheDocsIsAccepted) {
  std::vector<std::filesystem::path> files{kSource / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "docs")) {
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  }
  int checked = 0;
  for (const std::filesystem::path& file : files) {
    for (const Example& example : examples_in(file)) {
      std::vector<std::string> words = shell_words(example.line);
      ASSERT_FALSE(words.empty()) << example.where;
      words.erase(words.begin());  // the program
      // A configuration folder of the reader's own (`--config-dir DIR`): the shipped one here.
      for (std::size_t i = 0; i + 1 < words.size(); ++i) {
        if (words[i] == "--config-dir") words[i + 1] = config_dir().string();
      }
      ::testing::internal::CaptureStdout();
      ::testing::internal::CaptureStderr();
      const int status = check_command_line(words);
      ::testing::internal::GetCapturedStdout();
      const std::string errors = ::testing::internal::GetCapturedStderr();
      EXPECT_EQ(status, 0) << example.where << ": " << example.line << "\n" << errors;
      ++checked;
    }
  }
  EXPECT_GE(checked, 40) << "the docs' examples were not found";
}

TEST(DocsExamples, ALineThatTheProgramRefusesIsCaught) {
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(check_command_line({"localise", "--map", "m.vmem", "--queries", "q/"}), 2);
  EXPECT_EQ(check_command_line({"compass", "--input", "x", "--format", "xml"}), 2);
  EXPECT_EQ(check_command_line({"render", "--no-such-flag"}), 2);
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(check_command_line({"compass", "--input", "x", "--format", "jsonl", "--out", "-"}), 0);
}

}  // namespace
}  // namespace omninav::cli
