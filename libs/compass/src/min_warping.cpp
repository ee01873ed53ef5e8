// Min-warping, the fast implementation (min_warping.hpp). Per pair: one matrix product per
// scale plane gives every column distance of that plane (Eigen), then for each α the minima over
// the candidate partners are taken for all ψ at once (contiguous rows of a doubled table, so
// the inner loop is a vector minimum).
#include "omninav/compass/min_warping.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <set>
#include <utility>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::compass {

namespace {

constexpr double kPi = 3.14159265358979323846;

using ColumnMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic>;  // rows × columns

int positive_mod(int value, int modulus) {
  const int m = value % modulus;
  return m < 0 ? m + modulus : m;
}

// The parabola through (−1, minus), (0, centre), (1, plus): the abscissa of its vertex, within
// half a step (a flat or inverted triple stays at 0).
double parabola_vertex(double minus, double centre, double plus) {
  const double curvature = minus - 2.0 * centre + plus;
  if (!(curvature > 0.0)) return 0.0;
  return std::clamp(0.5 * (minus - plus) / curvature, -0.5, 0.5);
}

}  // namespace

void MinWarpingParams::check() const {
  check_range("min_warping.search_width_px", search_width_px, 8, 4096);
  check_range("min_warping.search_height_px", search_height_px, 1, 4096);
  check_range("min_warping.max_relative_distance", max_relative_distance, 0.05, 0.99);
  check_range("min_warping.max_scale", max_scale, 1.0, 4.0);
  check_range("min_warping.scale_planes", scale_planes, 1, 33);
  if (scale_planes % 2 == 0) {
    throw UsageError("key 'min_warping.scale_planes' = " + std::to_string(scale_planes) +
                     " must be odd (1 is a plane)");
  }
  check_range("min_warping.distance_samples", distance_samples, 16, 4096);
  check_range("min_warping.featureless_below_grey", featureless_below_grey, 0.0, 255.0);
}

// A reduced panorama and its magnified copies: magnified[m] holds the zero-mean columns of the
// image magnified by the m-th scale ≥ 1 (m = 0: unmagnified) and norms[m] their squared norms.
struct MinWarpingView::Data {
  std::string name;
  int width_px = 0, height_px = 0;  // of the original panorama
  bool featureless = false;
  std::vector<ColumnMatrix> magnified;
  std::vector<Eigen::RowVectorXf> norms;
};

double MinWarpingResult::travel_world_rad(double first_heading_rad) const {
  return wrap_angle(first_heading_rad + travel_rad);
}

MinWarpingView::MinWarpingView() : data_(std::make_unique<Data>()) {}
MinWarpingView::~MinWarpingView() = default;
MinWarpingView::MinWarpingView(MinWarpingView&&) noexcept = default;
MinWarpingView& MinWarpingView::operator=(MinWarpingView&&) noexcept = default;
const std::string& MinWarpingView::name() const {
  return data_->name;
}
cv::Size MinWarpingView::size() const {
  return {data_->width_px, data_->height_px};
}
bool MinWarpingView::featureless() const {
  return data_->featureless;
}

struct MinWarping::Impl {
  int width = 0;   // search columns
  int height = 0;  // search rows
  // The scale of each plane, ascending; plane (P−1)/2 is σ = 1.
  std::vector<double> scales;
  // Row maps of the magnifications ≥ 1: for magnification m and output row r, the source row
  // (fractional) in the reduced image.
  std::vector<std::vector<double>> source_rows;
  // The candidate partners of a snapshot column i' columns from the direction of travel:
  // (column offset δ, scale plane), the current column being i + ψ + δ.
  std::vector<std::vector<std::pair<int, int>>> candidates;
  PanoramaGeometry geometry;  // elevations of the reduced rows
};

MinWarping::MinWarping(const MinWarpingParams& params, const PanoramaGeometry& geometry)
    : params_(params), impl_(std::make_unique<Impl>()) {
  params_.check();
  Impl& impl = *impl_;
  impl.width = params_.search_width_px;
  impl.height = params_.search_height_px;
  impl.geometry = geometry;
  impl.geometry.width_px = impl.width;
  impl.geometry.height_px = impl.height;

  const int planes = params_.scale_planes;
  const int unit = planes / 2;
  const double log_step = planes > 1 ? std::log(params_.max_scale) / unit : 1.0;
  for (int k = 0; k < planes; ++k) impl.scales.push_back(std::exp((k - unit) * log_step));

  // Magnification about the horizon (min_warping.hpp, "Scale planes"): the row at elevation e'
  // takes the source at atan(tan e' / σ), clamped to the image.
  for (int k = unit; k < planes; ++k) {
    std::vector<double> rows(impl.height);
    for (int r = 0; r < impl.height; ++r) {
      const double elevation = impl.geometry.elevation_of_row(r);
      const double source = std::atan(std::tan(elevation) / impl.scales[k]);
      rows[r] = std::clamp(impl.geometry.row_of_elevation(source), 0.0, impl.height - 1.0);
    }
    impl.source_rows.push_back(std::move(rows));
  }

  // Candidates: ν sampled evenly in [0, ν_max]; each gives the partner's column offset (rounded
  // to a search column) and its scale plane (nearest in log σ, end planes beyond the stack).
  impl.candidates.resize(impl.width);
  for (int i = 0; i < impl.width; ++i) {
    const double u = wrap_angle(-2.0 * kPi * i / impl.width);
    std::set<std::pair<int, int>> found;
    for (int n = 0; n < params_.distance_samples; ++n) {
      const double nu = params_.max_relative_distance * n / (params_.distance_samples - 1);
      const double v = std::atan2(std::sin(u), std::cos(u) - nu);
      const double scale = 1.0 / std::sqrt(1.0 - 2.0 * nu * std::cos(u) + nu * nu);
      double offset = -v * impl.width / (2.0 * kPi) - i;
      offset -= impl.width * std::round(offset / impl.width);
      const int delta = static_cast<int>(std::lround(offset));
      int plane =
          planes > 1 ? static_cast<int>(std::lround(std::log(scale) / log_step)) + unit : unit;
      plane = std::clamp(plane, 0, planes - 1);
      found.emplace(delta, plane);
    }
    impl.candidates[i].assign(found.begin(), found.end());
  }
}

MinWarping::~MinWarping() = default;

MinWarpingView MinWarping::prepare(const cv::Mat& panorama, const std::string& name) const {
  const Impl& impl = *impl_;
  if (panorama.empty()) throw InputError(name + ": empty panorama");
  const int depth = panorama.depth();
  if ((depth != CV_8U && depth != CV_32F) ||
      (panorama.channels() != 1 && panorama.channels() != 3)) {
    throw InputError(name +
                     ": min-warping needs an 8-bit or 32-bit float panorama with 1 or 3 "
                     "channels");
  }
  if (panorama.cols < impl.width) {
    throw InputError(name + ": a panorama " + std::to_string(panorama.cols) +
                     " columns wide is narrower than the search's " + std::to_string(impl.width) +
                     " (min_warping.search_width_px)");
  }
  cv::Mat grey;
  panorama.convertTo(grey, CV_32F);
  if (grey.channels() == 3) {
    cv::transform(grey, grey, cv::Matx13f(1.f / 3.f, 1.f / 3.f, 1.f / 3.f));
  }
  if (!cv::checkRange(grey)) throw InputError(name + ": the panorama has NaN or infinite pixels");
  cv::Mat reduced;
  // Area averaging (whole blocks when the sizes are multiples); rows linear in elevation stay
  // so, whatever their number.
  cv::resize(grey, reduced, cv::Size(impl.width, impl.height), 0, 0,
             panorama.rows >= impl.height ? cv::INTER_AREA : cv::INTER_LINEAR);

  MinWarpingView view;
  MinWarpingView::Data& data = *view.data_;
  data.name = name;
  data.width_px = panorama.cols;
  data.height_px = panorama.rows;
  for (const std::vector<double>& rows : impl.source_rows) {
    ColumnMatrix columns(impl.height, impl.width);
    for (int r = 0; r < impl.height; ++r) {
      const int r0 = static_cast<int>(std::floor(rows[r]));
      const int r1 = std::min(r0 + 1, impl.height - 1);
      const float t = static_cast<float>(rows[r] - r0);
      const float* above = reduced.ptr<float>(r0);
      const float* below = reduced.ptr<float>(r1);
      for (int c = 0; c < impl.width; ++c) {
        columns(r, c) = (1.f - t) * above[c] + t * below[c];
      }
    }
    columns.rowwise() -= columns.colwise().mean();
    data.norms.push_back(columns.colwise().squaredNorm());
    data.magnified.push_back(std::move(columns));
  }
  // Featureless: the zero-mean columns against those a quarter turn away.
  const ColumnMatrix& plain = data.magnified.front();
  double sum = 0.0;
  for (int c = 0; c < impl.width; ++c) {
    sum += (plain.col(c) - plain.col((c + impl.width / 4) % impl.width)).squaredNorm();
  }
  const double rms = std::sqrt(sum / (static_cast<double>(impl.width) * impl.height));
  data.featureless = rms < params_.featureless_below_grey;
  return view;
}

namespace {

// ψ is processed in blocks of this many lanes, the running minima held in registers.
constexpr int kBlock = 16;

int padded(int width) {
  return (width + kBlock - 1) / kBlock * kBlock;
}

// The column distances of one plane, row i holding d(i, j mod W) for j in [0, 2W + kBlock) so
// that the padded W consecutive current columns from any start are contiguous.
void plane_distances(const ColumnMatrix& first, const Eigen::RowVectorXf& first_norms,
                     const ColumnMatrix& second, const Eigen::RowVectorXf& second_norms,
                     std::vector<float>& out) {
  const int width = static_cast<int>(first.cols());
  const int stride = 2 * width + kBlock;
  const ColumnMatrix products = first.transpose() * second;  // (i, j) = x_i · y_j
  out.resize(static_cast<std::size_t>(width) * stride);
  for (int i = 0; i < width; ++i) {
    float* row = out.data() + static_cast<std::ptrdiff_t>(i) * stride;
    for (int j = 0; j < width; ++j) {
      const float total = first_norms(i) + second_norms(j);
      row[j] = total > 1e-6f ? 1.f - 2.f * products(i, j) / total : 1.f;
    }
    for (int j = width; j < stride; ++j) row[j] = row[j % width];
  }
}

void require_same_size(const MinWarpingView::Data& a, const MinWarpingView::Data& b) {
  if (a.width_px != b.width_px || a.height_px != b.height_px) {
    throw InputError(b.name + ": a " + std::to_string(b.width_px) + "x" +
                     std::to_string(b.height_px) + " panorama cannot be compared with " + a.name +
                     " (" + std::to_string(a.width_px) + "x" + std::to_string(a.height_px) +
                     "); both must have the same size");
  }
}

}  // namespace

cv::Mat MinWarping::cost_surface(const MinWarpingView& first, const MinWarpingView& second) const {
  const Impl& impl = *impl_;
  const MinWarpingView::Data& a = first.data();
  const MinWarpingView::Data& b = second.data();
  require_same_size(a, b);
  const int width = impl.width;
  const int planes = static_cast<int>(impl.scales.size());
  const int unit = planes / 2;
  const int stride = 2 * width + kBlock;
  std::vector<std::vector<float>> tables(planes);
  for (int k = 0; k < planes; ++k) {
    // σ ≥ 1: the snapshot magnified by σ against the current view; σ < 1: the snapshot against
    // the current view magnified by 1/σ.
    const int m = std::abs(k - unit);
    if (k >= unit) {
      plane_distances(a.magnified[m], a.norms[m], b.magnified[0], b.norms[0], tables[k]);
    } else {
      plane_distances(a.magnified[0], a.norms[0], b.magnified[m], b.norms[m], tables[k]);
    }
  }
  // For each snapshot column i and travel direction α: ψ = p takes the current column
  // i + p + δ of each candidate, so the candidate's distances for all ψ are W consecutive
  // entries of row i of its plane. Snapshot column outermost: the rows it reads (one per plane)
  // stay in the first-level cache; blocks of kBlock ψ keep their minima in registers.
  const int columns = padded(width);
  std::vector<float> sums(static_cast<std::size_t>(width) * columns, 0.f);
  std::vector<const float*> rows;
  for (int i = 0; i < width; ++i) {
    for (int alpha = 0; alpha < width; ++alpha) {
      rows.clear();
      for (const auto& [delta, plane] : impl.candidates[positive_mod(i - alpha, width)]) {
        rows.push_back(tables[plane].data() + static_cast<std::ptrdiff_t>(i) * stride +
                       positive_mod(i + delta, width));
      }
      float* sum = sums.data() + static_cast<std::ptrdiff_t>(alpha) * columns;
      for (int p0 = 0; p0 < columns; p0 += kBlock) {
        // Eigen's fixed-size arrays: packet minima (std::min's scalar form is not vectorised).
        using Block = Eigen::Array<float, kBlock, 1>;
        Block minimum = Block::Constant(std::numeric_limits<float>::infinity());
        for (const float* row : rows) minimum = minimum.min(Eigen::Map<const Block>(row + p0));
        Eigen::Map<Block>(sum + p0) += minimum;
      }
    }
  }
  cv::Mat surface(width, width, CV_64F);
  for (int alpha = 0; alpha < width; ++alpha) {
    for (int p = 0; p < width; ++p) {
      surface.at<double>(alpha, p) = sums[static_cast<std::size_t>(alpha) * columns + p] / width;
    }
  }
  return surface;
}

MinWarping::RotationOnly MinWarping::rotation_only(const MinWarpingView& first,
                                                   const MinWarpingView& second) const {
  const MinWarpingView::Data& a = first.data();
  const MinWarpingView::Data& b = second.data();
  require_same_size(a, b);
  RotationOnly best;
  if (a.featureless || b.featureless) return best;
  // Every column at its rotated position on the plane σ = 1 (ν = 0).
  const int width = impl_->width;
  const ColumnMatrix products = a.magnified[0].transpose() * b.magnified[0];
  double least = std::numeric_limits<double>::infinity();
  int least_p = 0;
  for (int p = 0; p < width; ++p) {
    double sum = 0.0;
    for (int i = 0; i < width; ++i) {
      const int j = (i + p) % width;
      const float total = a.norms[0](i) + b.norms[0](j);
      sum += total > 1e-6f ? 1.0 - 2.0 * products(i, j) / total : 1.0;
    }
    if (sum / width < least) {
      least = sum / width;
      least_p = p;
    }
  }
  best.cost = least;
  best.rotation_rad = wrap_angle(2.0 * kPi * least_p / width);
  return best;
}

MinWarpingResult MinWarping::estimate(const MinWarpingView& first,
                                      const MinWarpingView& second) const {
  const Impl& impl = *impl_;
  require_same_size(first.data(), second.data());
  MinWarpingResult result;
  if (first.featureless() || second.featureless()) {
    result.featureless = true;  // no evidence: no turn, no direction
    return result;
  }
  const cv::Mat surface = cost_surface(first, second);
  const int width = impl.width;
  cv::Point best;
  double best_cost = 0.0;
  cv::minMaxLoc(surface, &best_cost, nullptr, &best, nullptr);
  const int alpha = best.y, psi = best.x;
  const auto at = [&](int a, int p) {
    return surface.at<double>(positive_mod(a, width), positive_mod(p, width));
  };
  const double psi_fine = psi + parabola_vertex(at(alpha, psi - 1), best_cost, at(alpha, psi + 1));
  const double alpha_fine =
      alpha + parabola_vertex(at(alpha - 1, psi), best_cost, at(alpha + 1, psi));

  const RotationOnly rotation = rotation_only(first, second);
  // Search column a looks along the azimuth of its block's centre in the full panorama.
  const double factor = static_cast<double>(first.data().width_px) / width;
  result.travel_index = alpha;
  result.rotation_index = psi;
  result.cost = best_cost;
  result.rotation_only_cost = rotation.cost;
  result.rotation_only_rad = rotation.rotation_rad;
  result.rotation_rad = wrap_angle(2.0 * kPi * psi_fine / width);
  result.travel_rad =
      azimuth_of_column(alpha_fine * factor + (factor - 1.0) / 2.0, first.data().width_px);
  result.home_rad = wrap_angle(result.travel_rad + kPi - result.rotation_rad);
  return result;
}

MinWarpingResult MinWarping::estimate(const cv::Mat& first, const cv::Mat& second) const {
  const MinWarpingView a = prepare(first, "first panorama");
  const MinWarpingView b = prepare(second, "second panorama");
  return estimate(a, b);
}

MinWarpingResult MinWarping::estimate_resized(const MinWarpingView& first, const cv::Mat& second,
                                              const std::string& name) const {
  if (second.empty() || second.size() == first.size())
    return estimate(first, prepare(second, name));
  cv::Mat resized;
  cv::resize(second, resized, first.size(), 0, 0, cv::INTER_AREA);
  return estimate(first, prepare(resized, name));
}

}  // namespace omninav::compass
