#include "omninav/core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

namespace fs = std::filesystem;

std::string system_reason(int error) {
  return error != 0 ? std::strerror(error) : "write failed";
}

fs::path folder_of(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

// Best effort: the rename is atomic without it, only not yet durable.
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

constexpr std::string_view kUnique = "XXXXXX";

// Hidden, so that no folder reader lists it; the extension kept for writers that go by it.
fs::path temporary_pattern(const fs::path& target) {
  std::string name = ".";
  name.append(target.stem().string()).append(".").append(kUnique);
  name.append(target.extension().string());
  return folder_of(target) / name;
}

}  // namespace

OutputFile::OutputFile(fs::path path) : path_(std::move(path)) {
  std::error_code error;
  fs::path target = path_;
  // A link is written through: its target is replaced, the link stays.
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(target, error)); ++hops) {
    const fs::path next = fs::read_symlink(target, error);
    target = next.is_absolute() ? next : folder_of(target) / next;
  }
  const fs::file_status status = fs::status(target, error);
  if (fs::is_directory(status)) {
    done_ = true;
    throw InputError(path_.string() + ": cannot write (it is a folder)");
  }
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    direct_ = true;  // a device or a FIFO: never replaced by a regular file
    temporary_ = target;
    return;
  }
  const std::string extension = target.extension().string();
  std::string name = temporary_pattern(target).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkstemps(buffer.data(), static_cast<int>(extension.size()));
  if (fd < 0) {
    const int reason = errno;
    done_ = true;
    throw InputError(path_.string() + ": cannot write (" + system_reason(reason) + ")");
  }
  // The permissions the file would have had written in place: the old file's, else the umask's.
  struct stat old {};
  mode_t mode = 0666;
  if (::stat(target.c_str(), &old) == 0) {
    mode = old.st_mode & 07777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode &= ~mask;
  }
  ::fchmod(fd, mode);
  ::close(fd);
  temporary_ = buffer.data();
  target_ = target;
}

OutputFile::~OutputFile() {
  if (!done_) remove_temporary();
}

std::ostream& OutputFile::stream() {
  if (!stream_) {
    errno = 0;
    stream_ = std::make_unique<std::ofstream>(temporary_, std::ios::binary | std::ios::trunc);
    if (!*stream_) fail(system_reason(errno));
  }
  return *stream_;
}

void OutputFile::commit() {
  if (done_) return;
  if (stream_) {
    errno = 0;
    stream_->flush();
    const int flush_error = errno;
    stream_->close();
    if (!*stream_) fail(system_reason(flush_error != 0 ? flush_error : errno));
  }
  if (direct_) {
    done_ = true;
    return;
  }
  const int fd = ::open(temporary_.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int reason = errno;
    if (fd >= 0) ::close(fd);
    fail(system_reason(reason));
  }
  ::close(fd);
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) fail(system_reason(errno));
  done_ = true;
  sync_folder(folder_of(target_));
}

void OutputFile::fail(const std::string& reason) {
  if (stream_) stream_.reset();
  remove_temporary();
  done_ = true;
  throw InputError(path_.string() + ": cannot write (" + reason + ")");
}

void OutputFile::remove_temporary() noexcept {
  if (direct_ || temporary_.empty()) return;
  stream_.reset();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void remove_stale_temporaries(const fs::path& path) {
  const std::string pattern = temporary_pattern(path).filename().string();
  const std::size_t unique = pattern.find(kUnique);
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_of(path), error)) {
    const std::string name = entry.path().filename().string();
    if (name.size() == pattern.size() && name.compare(0, unique, pattern, 0, unique) == 0 &&
        name.compare(unique + kUnique.size(), std::string::npos, pattern,
                     unique + kUnique.size()) == 0) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

void write_output_file(const fs::path& path, std::string_view bytes) {
  OutputFile file(path);
  // Written with write(2), not a stream, so that a failure keeps the system's reason.
  const int fd = ::open(file.temporary().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  int reason = fd < 0 ? errno : 0;
  for (std::size_t done = 0; reason == 0 && done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno != EINTR) reason = errno;
    if (n > 0) done += static_cast<std::size_t>(n);
  }
  if (fd >= 0 && ::close(fd) != 0 && reason == 0) reason = errno;
  if (reason != 0) file.fail(system_reason(reason));
  file.commit();
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  if (a.empty() || b.empty() || !fs::exists(a, error) || !fs::exists(b, error)) return false;
  return fs::equivalent(a, b, error);
}

void check_not_an_input(const fs::path& output, const std::vector<fs::path>& inputs) {
  for (const fs::path& input : inputs) {
    if (same_file(output, input)) {
      throw UsageError(output.string() + ": is also the input " + input.string() +
                       "; write it elsewhere");
    }
  }
}

void check_output_path(const fs::path& path, const std::vector<fs::path>& inputs) {
  check_not_an_input(path, inputs);
  std::error_code error;
  if (fs::is_directory(path, error)) {
    throw InputError(path.string() + ": cannot write (it is a folder)");
  }
  const fs::path folder = folder_of(path);
  if (!fs::exists(folder, error)) {
    throw InputError(path.string() + ": cannot write (no folder " + folder.string() + ")");
  }
  if (!fs::is_directory(folder, error)) {
    throw InputError(path.string() + ": cannot write (" + folder.string() + " is not a folder)");
  }
  const bool special = fs::exists(path, error) && !fs::is_regular_file(path, error);
  if (::access((special ? path : folder).c_str(), W_OK) != 0) {
    throw InputError(path.string() + ": cannot write (" + system_reason(errno) + ")");
  }
}

namespace {

// Flushes standard output; throws with the errno of the first failure since the caller cleared
// it.
void check_standard_output() {
  std::cout.flush();
  const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  const int reason = errno;
  if (!lost) return;
  std::cout.clear();
  std::clearerr(stdout);
  throw InputError("standard output: cannot write (" + system_reason(reason) + ")");
}

}  // namespace

void write_standard_output(std::string_view text) {
  errno = 0;
  std::cout << text;
  check_standard_output();
}

void flush_standard_output() {
  errno = 0;
  check_standard_output();
}

}  // namespace omninav
