#include "omninav/io/folder_sequence.hpp"

#include <algorithm>

#include "omninav/core/errors.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/io/natural_sort.hpp"

namespace omninav::io {
namespace {

// Hidden files such as macOS's "._img1.png" resource forks carry an image extension but are
// not images.
bool is_hidden(const std::filesystem::path& file) {
  return file.filename().string().starts_with('.');
}

}  // namespace

std::vector<std::filesystem::path> list_images(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  std::filesystem::directory_iterator entries(folder, error);
  if (error) throw InputError(folder.string() + ": cannot list folder (" + error.message() + ")");
  for (const std::filesystem::directory_entry& entry : entries) {
    if (entry.is_regular_file(error) && is_image_file_name(entry.path()) &&
        !is_hidden(entry.path())) {
      files.push_back(entry.path());
    }
  }
  if (files.empty()) {
    throw InputError(folder.string() +
                     ": no images in folder (looked for png, jpg, jpeg, bmp, tif, tiff, ppm, pgm)");
  }
  natural_sort(files);
  return files;
}

FolderSequence::FolderSequence(const std::filesystem::path& folder)
    : folder_(folder), files_(list_images(folder)) {}

std::optional<Frame> FolderSequence::next() {
  if (next_index_ == files_.size()) return std::nullopt;
  const std::filesystem::path& file = files_[next_index_];
  Frame frame;
  frame.index = static_cast<int>(next_index_);
  frame.image = read_image(file);
  frame.source = file.string();
  size_check_.check(frame.image, frame.source);
  ++next_index_;
  return frame;
}

std::string FolderSequence::describe() const {
  return "folder " + folder_.string() + " (" + std::to_string(files_.size()) + " images, no poses)";
}

}  // namespace omninav::io
