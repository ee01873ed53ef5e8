#pragma once
// Typed exceptions thrown by the libraries and caught once, at main, where they become a
// one-line message and a non-zero exit status (docs/design.md, Conventions: Errors).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace omninav {

// Base of every error omninav reports to a user. what() is the whole one-line message.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A configuration file or value is wrong: unknown key, bad type, out-of-range value.
class ConfigError : public Error {
 public:
  using Error::Error;
};

// An input file or sequence is wrong: unreadable, corrupt, inconsistent, missing a column.
class InputError : public Error {
 public:
  using Error::Error;
};

// The caller asked for something that cannot be done with these arguments.
class UsageError : public Error {
 public:
  using Error::Error;
};

// Why `path` cannot be read as a `kind` (e.g. "video file"), for "<path>: <reason>" when a
// regular file was wanted: "no such video file", "cannot reach the video file (Permission
// denied)", "is a folder, not a video file", "is a FIFO, not a video file".
std::string unreadable_file_reason(const std::filesystem::path& path, const std::string& kind);

// A name read from inside a file (a bag's topic, a type), as a one-line message shows it: UTF-8
// kept as it is, control characters and bytes that are not UTF-8 written as \xNN, so that a
// damaged name cannot garble the terminal or break the line.
std::string printable_name(std::string_view bytes);

}  // namespace omninav
