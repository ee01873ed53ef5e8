#include "omninav/measures/png.hpp"

#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "omninav/core/errors.hpp"
#include "omninav/core/output_file.hpp"

namespace omninav::measures {

void save_png(const cv::Mat& image, const std::filesystem::path& path) {
  if (image.empty()) throw UsageError("cannot write " + path.string() + ": the image is empty");
  const int depth = image.depth();
  const int channels = image.channels();
  if ((depth != CV_8U && depth != CV_16U) || (channels != 1 && channels != 3 && channels != 4)) {
    throw UsageError("cannot write " + path.string() +
                     " as PNG: needs an 8- or 16-bit image with 1, 3 or 4 channels");
  }
  // Encode in memory, then write the bytes: the format does not depend on the extension, and
  // a failure to open or write the file gets the system's reason rather than imwrite's bare
  // `false`.
  std::vector<uchar> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(".png", image, bytes);
  } catch (const cv::Exception& e) {
    throw InputError("cannot encode " + path.string() + " as PNG: " + e.what());
  }
  if (!encoded) throw InputError("cannot encode " + path.string() + " as PNG");

  write_output_file(path,
                    std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace omninav::measures
