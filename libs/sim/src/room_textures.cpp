#include "room_textures.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace omninav::sim::textures {
namespace {

int px(double metres, double px_per_m) {
  return std::max(1, static_cast<int>(std::lround(metres * px_per_m)));
}

}  // namespace

cv::Scalar random_colour(cv::RNG& rng, int low, int high) {
  return cv::Scalar(rng.uniform(low, high), rng.uniform(low, high), rng.uniform(low, high));
}

// Smooth brightness variation (stains, uneven paint, light falloff) at a scale of `cell_m`.
void add_smooth_noise(cv::Mat& image, double cell_m, double px_per_m, double amplitude,
                      cv::RNG& rng) {
  const int cells_x = std::max(2, image.cols / px(cell_m, px_per_m) + 2);
  const int cells_y = std::max(2, image.rows / px(cell_m, px_per_m) + 2);
  cv::Mat coarse(cells_y, cells_x, CV_32F);
  rng.fill(coarse, cv::RNG::NORMAL, 0.0, amplitude);
  cv::Mat smooth;
  cv::resize(coarse, smooth, image.size(), 0, 0, cv::INTER_CUBIC);
  cv::Mat smooth3;
  cv::merge(std::vector<cv::Mat>{smooth, smooth, smooth}, smooth3);
  cv::Mat image_f;
  image.convertTo(image_f, CV_32FC3);
  image_f += smooth3;
  image_f.convertTo(image, CV_8UC3);
}

// A framed picture: blocks, discs and bands of random colours, different on every call.
void draw_picture(cv::Mat& image, cv::Rect frame, cv::RNG& rng) {
  cv::rectangle(image, frame, random_colour(rng, 20, 90), cv::FILLED);
  const int border = std::max(2, std::min(frame.width, frame.height) / 12);
  const cv::Rect canvas(frame.x + border, frame.y + border, frame.width - 2 * border,
                        frame.height - 2 * border);
  if (canvas.width <= 2 || canvas.height <= 2) return;
  cv::rectangle(image, canvas, random_colour(rng, 120, 250), cv::FILLED);
  const int shapes = rng.uniform(3, 9);
  for (int i = 0; i < shapes; ++i) {
    const cv::Point centre(canvas.x + rng.uniform(0, canvas.width),
                           canvas.y + rng.uniform(0, canvas.height));
    const int size = rng.uniform(std::max(2, canvas.height / 8), std::max(3, canvas.height / 2));
    const cv::Scalar colour = random_colour(rng, 0, 255);
    switch (rng.uniform(0, 3)) {
      case 0:
        cv::circle(image, centre, size / 2, colour, cv::FILLED, cv::LINE_AA);
        break;
      case 1:
        cv::rectangle(
            image, cv::Rect(centre.x - size / 2, centre.y - size / 3, size, 2 * size / 3) & canvas,
            colour, cv::FILLED);
        break;
      default:
        cv::line(image, centre, centre + cv::Point(size, rng.uniform(-size, size)), colour,
                 std::max(1, size / 6), cv::LINE_AA);
    }
  }
}

namespace {

void draw_door(cv::Mat& image, int x, double px_per_m, cv::RNG& rng) {
  const cv::Rect door(x, image.rows - px(2.05, px_per_m), px(0.9, px_per_m), px(2.05, px_per_m));
  const cv::Scalar wood = random_colour(rng, 30, 110);
  cv::rectangle(image, door, wood, cv::FILLED);
  cv::rectangle(image, door, wood * 0.5, std::max(2, px(0.04, px_per_m)));
  for (int panel = 0; panel < 2; ++panel) {  // two recessed panels
    const cv::Rect recess(door.x + door.width / 6,
                          door.y + door.height / 12 + panel * door.height / 2, 2 * door.width / 3,
                          door.height / 3);
    cv::rectangle(image, recess, wood * 0.75, std::max(1, px(0.02, px_per_m)));
  }
  cv::circle(image, {door.x + door.width - px(0.1, px_per_m), door.y + door.height / 2},
             std::max(2, px(0.03, px_per_m)), cv::Scalar(40, 200, 220), cv::FILLED, cv::LINE_AA);
}

void draw_window(cv::Mat& image, int x, double px_per_m, cv::RNG& rng) {
  const int width = px(rng.uniform(0.9, 1.6), px_per_m);
  const int height = px(rng.uniform(0.9, 1.3), px_per_m);
  const int sill = px(0.9, px_per_m);
  const cv::Rect window(x, image.rows - sill - height, width, height);
  // Sky above a horizon of distant trees: bright, as a window is.
  cv::rectangle(image, window, cv::Scalar(250, 225, 200), cv::FILLED);
  cv::rectangle(image, cv::Rect(window.x, window.y + 2 * height / 3, width, height / 3),
                cv::Scalar(60, 140, 70), cv::FILLED);
  const int frame = std::max(2, px(0.05, px_per_m));
  cv::rectangle(image, window, cv::Scalar(245, 245, 245), frame);
  cv::line(image, {window.x + width / 2, window.y}, {window.x + width / 2, window.y + height},
           cv::Scalar(245, 245, 245), frame);
  cv::line(image, {window.x, window.y + height / 2}, {window.x + width, window.y + height / 2},
           cv::Scalar(245, 245, 245), frame);
}

}  // namespace

cv::Mat wall(double width_m, double height_m, double px_per_m, cv::RNG& rng) {
  const cv::Scalar paint = random_colour(rng, 140, 235);
  return painted_wall(width_m, height_m, px_per_m, paint, true, rng);
}

cv::Mat painted_wall(double width_m, double height_m, double px_per_m, const cv::Scalar& paint,
                     bool decorated, cv::RNG& rng) {
  cv::Mat image(px(height_m, px_per_m), px(width_m, px_per_m), CV_8UC3, paint);
  // Wallpaper: vertical stripes of a random period, or none.
  if (decorated && rng.uniform(0, 2) == 1) {
    const int period = px(rng.uniform(0.06, 0.3), px_per_m);
    const cv::Scalar stripe = cv::Scalar(image.at<cv::Vec3b>(0, 0)) * rng.uniform(0.75, 0.92);
    for (int x = 0; x < image.cols; x += period) {
      cv::rectangle(image, cv::Rect(x, 0, std::max(1, period / 3), image.rows), stripe, cv::FILLED);
    }
  }
  add_smooth_noise(image, 0.4, px_per_m, 10.0, rng);
  // Openings and pictures, placed left to right without overlap.
  int x = decorated ? px(rng.uniform(0.2, 0.8), px_per_m) : image.cols;
  while (x < image.cols - px(0.6, px_per_m)) {
    const double kind = rng.uniform(0.0, 1.0);
    const int remaining = image.cols - x;
    if (kind < 0.15 && remaining > px(1.0, px_per_m)) {
      draw_door(image, x, px_per_m, rng);
      x += px(0.9, px_per_m);
    } else if (kind < 0.3 && remaining > px(1.7, px_per_m)) {
      draw_window(image, x, px_per_m, rng);
      x += px(1.6, px_per_m);
    } else {
      const int width = std::min(remaining - 1, px(rng.uniform(0.25, 1.1), px_per_m));
      const int height = px(rng.uniform(0.25, 0.8), px_per_m);
      const int top = image.rows - px(rng.uniform(1.1, 2.1), px_per_m) - height / 2;
      draw_picture(image, cv::Rect(x, std::max(0, top), width, height), rng);
      x += width;
    }
    x += px(rng.uniform(0.15, 0.9), px_per_m);
  }
  // Skirting board along the floor.
  cv::rectangle(image, cv::Rect(0, image.rows - px(0.1, px_per_m), image.cols, px(0.1, px_per_m)),
                random_colour(rng, 30, 120), cv::FILLED);
  return image;
}

cv::Mat floor(double width_m, double depth_m, double px_per_m, cv::RNG& rng) {
  const cv::Scalar tone = random_colour(rng, 70, 160);
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, tone);
  const int tile = px(rng.uniform(0.3, 0.6), px_per_m);
  for (int y = 0; y < image.rows; y += tile) {
    for (int x = 0; x < image.cols; x += tile) {
      cv::rectangle(image, cv::Rect(x, y, tile, tile), tone * rng.uniform(0.85, 1.15), cv::FILLED);
      cv::rectangle(image, cv::Rect(x, y, tile, tile), tone * 0.6, 1);
    }
  }
  add_smooth_noise(image, 0.3, px_per_m, 8.0, rng);
  const int rugs = rng.uniform(1, 4);
  for (int i = 0; i < rugs; ++i) {
    const int width = px(rng.uniform(0.8, 2.0), px_per_m);
    const int height = px(rng.uniform(0.6, 1.5), px_per_m);
    const cv::Rect rug(rng.uniform(0, std::max(1, image.cols - width)),
                       rng.uniform(0, std::max(1, image.rows - height)), width, height);
    cv::rectangle(image, rug, random_colour(rng, 40, 220), cv::FILLED);
    cv::rectangle(image, rug, random_colour(rng, 20, 250), std::max(2, px(0.06, px_per_m)));
    draw_picture(image, cv::Rect(rug.x + width / 4, rug.y + height / 4, width / 2, height / 2),
                 rng);
  }
  return image;
}

cv::Mat planks(double width_m, double depth_m, double px_per_m, cv::RNG& rng) {
  const cv::Scalar wood(rng.uniform(30, 110), rng.uniform(70, 150), rng.uniform(110, 200));
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, wood);
  const int plank_width = px(rng.uniform(0.12, 0.22), px_per_m);
  for (int y = 0; y < image.rows; y += plank_width) {
    int x = -rng.uniform(0, px(1.5, px_per_m));  // staggered joints
    while (x < image.cols) {
      const int length = px(rng.uniform(0.8, 2.0), px_per_m);
      const cv::Rect plank(x, y, length, plank_width);
      cv::rectangle(image, plank, wood * rng.uniform(0.8, 1.2), cv::FILLED);
      for (int grain = 0; grain < 3; ++grain) {  // a few streaks of grain
        const int gy = y + rng.uniform(1, std::max(2, plank_width - 1));
        cv::line(image, {x, gy}, {x + length, gy + rng.uniform(-2, 3)}, wood * 0.7, 1, cv::LINE_AA);
      }
      cv::rectangle(image, plank, wood * 0.45, 1);
      x += length;
    }
  }
  add_smooth_noise(image, 0.5, px_per_m, 6.0, rng);
  return image;
}

cv::Mat carpet(double width_m, double depth_m, double px_per_m, cv::RNG& rng) {
  const cv::Scalar pile = random_colour(rng, 40, 200);
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, pile);
  // A border a little in from the walls, and a pattern of motifs inside it.
  const int inset = px(rng.uniform(0.2, 0.5), px_per_m);
  const cv::Scalar border = random_colour(rng, 20, 230);
  cv::rectangle(image, cv::Rect(inset, inset, image.cols - 2 * inset, image.rows - 2 * inset),
                border, std::max(2, px(0.12, px_per_m)));
  const int motif = px(rng.uniform(0.3, 0.7), px_per_m);
  const cv::Scalar ink = random_colour(rng, 20, 230);
  for (int y = inset + motif; y < image.rows - inset - motif / 2; y += motif) {
    for (int x = inset + motif; x < image.cols - inset - motif / 2; x += motif) {
      cv::circle(image, {x, y}, std::max(1, motif / 5), ink, cv::FILLED, cv::LINE_AA);
    }
  }
  add_smooth_noise(image, 0.2, px_per_m, 10.0, rng);
  return image;
}

cv::Mat ceiling(double width_m, double depth_m, double px_per_m, cv::RNG& rng) {
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, cv::Scalar(225, 230, 232));
  add_smooth_noise(image, 0.8, px_per_m, 6.0, rng);
  const int lights = rng.uniform(2, 5);
  for (int i = 0; i < lights; ++i) {
    const int width = px(rng.uniform(0.3, 1.2), px_per_m);
    const int height = px(rng.uniform(0.2, 0.6), px_per_m);
    cv::rectangle(image,
                  cv::Rect(rng.uniform(0, std::max(1, image.cols - width)),
                           rng.uniform(0, std::max(1, image.rows - height)), width, height),
                  cv::Scalar(255, 255, 255), cv::FILLED);
  }
  return image;
}

cv::Mat furniture(double px_per_m, cv::RNG& rng) {
  const int size = px(1.0, px_per_m);
  const cv::Scalar base = random_colour(rng, 25, 230);
  cv::Mat image(size, size, CV_8UC3, base);
  switch (rng.uniform(0, 4)) {
    case 0: {  // wood grain: thin horizontal bands of varying tone
      for (int y = 0; y < size; y += rng.uniform(2, 8)) {
        cv::line(image, {0, y}, {size, y + rng.uniform(-3, 4)}, base * rng.uniform(0.7, 1.1), 1,
                 cv::LINE_AA);
      }
      break;
    }
    case 1: {  // drawers with handles
      const int drawer = size / rng.uniform(2, 5);
      for (int y = 0; y < size; y += drawer) {
        cv::rectangle(image, cv::Rect(2, y + 2, size - 4, drawer - 4), base * 0.6, 2);
        cv::rectangle(image, cv::Rect(size / 2 - size / 12, y + drawer / 2 - 2, size / 6, 4),
                      cv::Scalar(200, 200, 200), cv::FILLED);
      }
      break;
    }
    case 2: {  // checked fabric
      const int check = px(rng.uniform(0.05, 0.2), px_per_m);
      const cv::Scalar other = random_colour(rng, 25, 230);
      for (int y = 0; y < size; y += check) {
        for (int x = (y / check) % 2 * check; x < size; x += 2 * check) {
          cv::rectangle(image, cv::Rect(x, y, check, check), other, cv::FILLED);
        }
      }
      break;
    }
    default: {  // dots
      const int dots = rng.uniform(10, 40);
      for (int i = 0; i < dots; ++i) {
        cv::circle(image, {rng.uniform(0, size), rng.uniform(0, size)},
                   rng.uniform(2, std::max(3, size / 10)), random_colour(rng, 0, 255), cv::FILLED,
                   cv::LINE_AA);
      }
    }
  }
  add_smooth_noise(image, 0.25, px_per_m, 8.0, rng);
  return image;
}

}  // namespace omninav::sim::textures
