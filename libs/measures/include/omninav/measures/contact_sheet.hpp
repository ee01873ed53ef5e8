#pragma once
// Contact sheets: a grid of images with a caption under each, to look at panoramas (e.g. the
// rendered views along a route, or a query and its best places) in one PNG. Write one with
// save_png (png.hpp).

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace omninav::measures {

struct ContactSheetParams {
  // Each image is enlarged by the smallest whole factor that makes it at least this wide
  // (a 360×45 panorama becomes 720×90); images already this wide keep their size. Never shrunk.
  int min_width_px = 720;
  int interpolation = cv::INTER_NEAREST;  // keeps pixels crisp; cv::INTER_LINEAR smooths them
  int margin_px = 10;                     // around the sheet and between cells
  int caption_height_px = 30;             // the text band under each image
  double font_scale = 0.6;                // cv::FONT_HERSHEY_SIMPLEX; shrunk to fit the cell
  cv::Scalar background = cv::Scalar(200, 200, 200);  // neutral light grey, BGR
};

// A BGR (CV_8UC3) sheet of `images` in `columns` columns, row by row. Layout, in pixels:
//   factor_i  = max(1, ceil(min_width_px / width_i)); image i is drawn at factor_i × its size
//   cell_w    = the largest enlarged width,  image_h = the largest enlarged height
//   cell_h    = image_h + caption_height_px
//   c         = min(columns, images.size()) columns,  r = ceil(images.size() / c) rows
//   sheet     = (margin + c·(cell_w + margin)) wide, (margin + r·(cell_h + margin)) high
//   image i   in column i % c and row i / c, its top-left corner at
//               (margin + col·(cell_w + margin) + (cell_w − enlarged width_i) / 2,
//                margin + row·(cell_h + margin))   (centred across, top-aligned)
//   caption i centred under the image band, in the caption_height_px below image_h;
//               too long, it is shrunk and then cut with "...".
// Images must be 8-bit with 1 (grey, converted to BGR), 3 (BGR) or 4 channels (alpha
// dropped). `captions` is empty (no captions) or holds one per image. Throws UsageError on an
// empty list, an empty or unsupported image (naming its index), a wrong caption count,
// columns < 1 or non-positive sizes.
cv::Mat contact_sheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& captions,
                      int columns, const ContactSheetParams& params = {});

}  // namespace omninav::measures
