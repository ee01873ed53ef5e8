#include "omninav/measures/contact_sheet.hpp"

#include <algorithm>
#include <string>

#include "omninav/core/errors.hpp"
#include "omninav/measures/hershey_text.hpp"

namespace omninav::measures {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kMinFontScale = 0.35;

cv::Mat as_bgr(const cv::Mat& image, std::size_t index) {
  if (image.empty())
    throw UsageError("contact sheet: image " + std::to_string(index) + " is empty");
  if (image.depth() != CV_8U) {
    throw UsageError("contact sheet: image " + std::to_string(index) + " is not 8-bit");
  }
  cv::Mat bgr;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case 3:
      return image;
    case 4:
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    default:
      throw UsageError("contact sheet: image " + std::to_string(index) + " has " +
                       std::to_string(image.channels()) + " channels (1, 3 or 4 expected)");
  }
}

// Draws `caption` centred in `band`, shrinking the font and then cutting the text to fit.
void draw_caption(cv::Mat& sheet, const std::string& text, const cv::Rect& band,
                  double font_scale) {
  if (text.empty()) return;
  std::string caption = hershey_text(text);
  const int room = band.width - 4;
  int baseline = 0;
  double scale = font_scale;
  cv::Size size = cv::getTextSize(caption, kFont, scale, 1, &baseline);
  if (size.width > room) {
    scale = std::max(kMinFontScale, scale * room / size.width);
    size = cv::getTextSize(caption, kFont, scale, 1, &baseline);
  }
  while (size.width > room && caption.size() > 3) {
    caption.erase(caption.size() - (caption.ends_with("...") ? 4 : 3));
    caption += "...";
    size = cv::getTextSize(caption, kFont, scale, 1, &baseline);
  }
  const cv::Point origin(band.x + (band.width - size.width) / 2,
                         band.y + (band.height + size.height) / 2);
  cv::putText(sheet, caption, origin, kFont, scale, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat contact_sheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& captions,
                      int columns, const ContactSheetParams& params) {
  if (images.empty()) throw UsageError("contact sheet: no images given");
  if (!captions.empty() && captions.size() != images.size()) {
    throw UsageError("contact sheet: " + std::to_string(captions.size()) + " captions for " +
                     std::to_string(images.size()) + " images");
  }
  if (columns < 1) throw UsageError("contact sheet: needs at least one column");
  if (params.min_width_px < 1 || params.margin_px < 0 || params.caption_height_px < 0 ||
      !(params.font_scale > 0.0)) {
    throw UsageError("contact sheet: sizes must be positive");
  }

  std::vector<cv::Mat> enlarged;
  enlarged.reserve(images.size());
  int cell_width = 0;
  int image_height = 0;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const cv::Mat bgr = as_bgr(images[i], i);
    const int factor = std::max(1, (params.min_width_px + bgr.cols - 1) / bgr.cols);
    cv::Mat big;
    if (factor == 1) {
      big = bgr;
    } else {
      cv::resize(bgr, big, cv::Size(bgr.cols * factor, bgr.rows * factor), 0, 0,
                 params.interpolation);
    }
    cell_width = std::max(cell_width, big.cols);
    image_height = std::max(image_height, big.rows);
    enlarged.push_back(big);
  }

  const int count = static_cast<int>(images.size());
  const int used_columns = std::min(columns, count);
  const int rows = (count + used_columns - 1) / used_columns;
  const int margin = params.margin_px;
  const int cell_height = image_height + params.caption_height_px;
  cv::Mat sheet(margin + rows * (cell_height + margin),
                margin + used_columns * (cell_width + margin), CV_8UC3, params.background);

  for (int i = 0; i < count; ++i) {
    const int cell_x = margin + (i % used_columns) * (cell_width + margin);
    const int cell_y = margin + (i / used_columns) * (cell_height + margin);
    const cv::Mat& image = enlarged[static_cast<std::size_t>(i)];
    image.copyTo(
        sheet(cv::Rect(cell_x + (cell_width - image.cols) / 2, cell_y, image.cols, image.rows)));
    if (!captions.empty() && params.caption_height_px > 0) {
      draw_caption(sheet, captions[static_cast<std::size_t>(i)],
                   cv::Rect(cell_x, cell_y + image_height, cell_width, params.caption_height_px),
                   params.font_scale);
    }
  }
  return sheet;
}

}  // namespace omninav::measures
