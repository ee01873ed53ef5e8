#pragma once
// Every file omninav writes is written whole or not at all (docs/design.md, Conventions: Errors).
//
//   OutputFile csv(path);            // a unique temporary beside `path`
//   csv.stream() << text;            // or hand csv.temporary() to a writer that wants a path
//   csv.commit();                    // flushed, synced, renamed over `path`
//
// An OutputFile destroyed without commit() removes its temporary. A `path` that is a symbolic
// link is written through to its target (the link stays a link); a device, FIFO or other
// special file is written directly, never replaced by a regular file. Every failure is an
// InputError naming `path` with the system's reason, and leaves no temporary behind.

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace omninav {

class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();

  // The file the user named.
  const std::filesystem::path& path() const { return path_; }
  // Where to write: the temporary (or the special file itself). It exists, empty.
  const std::filesystem::path& temporary() const { return temporary_; }
  // True for a special file, written directly: temporary() is then the file itself.
  bool in_place() const { return direct_; }
  // A binary stream onto temporary(), opened on first use.
  std::ostream& stream();
  // Closes the stream (if used), checks it, syncs and renames the temporary over path().
  void commit();
  // For a writer of temporary() that failed: removes the temporary, throws InputError
  // "<path>: cannot write (<reason>)".
  [[noreturn]] void fail(const std::string& reason);

 private:
  void remove_temporary() noexcept;

  std::filesystem::path path_;
  std::filesystem::path temporary_;
  std::filesystem::path target_;  // path_, or the target of the link path_ is
  bool direct_ = false;           // a special file: written in place
  bool done_ = false;
  std::unique_ptr<std::ofstream> stream_;
};

// Removes the temporaries of `path` a killed writer left beside it. Only for a caller that
// knows no other process is writing `path` (the map's writer, under its lock).
void remove_stale_temporaries(const std::filesystem::path& path);

// `bytes` written to `path` through an OutputFile.
void write_output_file(const std::filesystem::path& path, std::string_view bytes);

// Checks, before the work that produces it, that `path` can be written: not a folder, its
// folder exists and may be written in (InputError naming `path` otherwise), and not one of the
// command's `inputs` (check_not_an_input).
void check_output_path(const std::filesystem::path& path,
                       const std::vector<std::filesystem::path>& inputs = {});

// Whether `a` and `b` name the same existing file or folder (std::filesystem::equivalent: `./M`
// and `M`, a link and its target, two hard links). False when either does not exist.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// The one guard that no output of a command replaces one of its inputs (a map read and written
// over, a CSV sequence replaced by its own headings): UsageError "<output>: is also the input
// <input>; write it elsewhere" when `output` is the same file as one of `inputs` (empty paths
// are skipped).
void check_not_an_input(const std::filesystem::path& output,
                        const std::vector<std::filesystem::path>& inputs);

// Flushes standard output; InputError "standard output: ..." when anything written to it was
// lost (a full disk, a closed pipe). Each command's last step.
void flush_standard_output();

// Writes `text` to standard output and flushes it at once, so that a failure keeps its reason
// (errno is gone by the command's last flush): InputError "standard output: ..." as above. For
// text longer than standard output's buffer.
void write_standard_output(std::string_view text);

}  // namespace omninav
