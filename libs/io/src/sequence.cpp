#include "omninav/io/sequence.hpp"

#include <algorithm>
#include <cctype>

#include "omninav/core/errors.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/csv_sequence.hpp"
#include "omninav/io/folder_sequence.hpp"
#include "omninav/io/video_sequence.hpp"

namespace omninav::io {
namespace {

bool has_csv_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".csv";
}

}  // namespace

std::unique_ptr<SequenceReader> open_sequence(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(path.string() + ": no such file or folder");
  }
  if (is_bag(path)) return open_bag(path, {});
  if (std::filesystem::is_directory(path, error)) {
    if (std::filesystem::exists(path / kBobEntriesFile, error)) {
      return std::make_unique<BobDatabaseReader>(path);
    }
    // Read as a plain folder, a database missing its entries would lose every pose.
    if (std::filesystem::exists(path / kBobMetadataFile, error)) {
      throw InputError(path.string() + ": has " + kBobMetadataFile + " but no " + kBobEntriesFile +
                       ": a BoB database missing its entries (the poses of its images)");
    }
    return std::make_unique<FolderSequence>(path);
  }
  if (has_csv_extension(path)) return std::make_unique<CsvSequence>(path);
  return std::make_unique<VideoSequence>(path);
}

std::vector<Frame> read_all(SequenceReader& reader) {
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = reader.next()) frames.push_back(std::move(*frame));
  return frames;
}

}  // namespace omninav::io
