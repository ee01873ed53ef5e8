#pragma once
// A folder of image files read in natural order (docs/design.md, Data formats: Input sequences).
// Such a folder knows neither capture times nor poses.

#include <filesystem>
#include <vector>

#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

// The image files directly in `folder` (extensions png, jpg, jpeg, bmp, tif, tiff, ppm, pgm in
// any case; hidden files skipped), in natural order. Throws InputError naming the folder when
// it holds none.
std::vector<std::filesystem::path> list_images(const std::filesystem::path& folder);

class FolderSequence : public SequenceReader {
 public:
  explicit FolderSequence(const std::filesystem::path& folder);

  std::optional<Frame> next() override;
  std::size_t size() const override { return files_.size(); }
  std::string describe() const override;

 private:
  std::filesystem::path folder_;
  std::vector<std::filesystem::path> files_;
  std::size_t next_index_ = 0;
  ImageSizeCheck size_check_;
};

}  // namespace omninav::io
