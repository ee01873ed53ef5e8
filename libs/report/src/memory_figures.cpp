#include "omninav/report/memory_figures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/measures/hershey_text.hpp"
#include "omninav/measures/plot.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::report {
namespace {

using memory::PlaceIndex;
using memory::VisualMemory;

cv::Scalar viridis(double similarity) {
  cv::Mat level(1, 1, CV_8UC1, cv::Scalar(std::clamp(similarity / 1000.0 * 255.0, 0.0, 255.0)));
  cv::Mat colour;
  cv::applyColorMap(level, colour, cv::COLORMAP_VIRIDIS);
  const cv::Vec3b c = colour.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

void put_text(cv::Mat& image, const std::string& text, cv::Point origin, double scale = 0.5,
              cv::Scalar colour = cv::Scalar(30, 30, 30)) {
  cv::putText(image, measures::hershey_text(text), origin, cv::FONT_HERSHEY_SIMPLEX, scale, colour,
              1, cv::LINE_AA);
}

// The layout of a localisation figure: the places' bounds with a margin of one spacing, drawn
// at one scale in panels of the same size, one per level.
struct LocalisationLayout {
  static constexpr int kPanel = 380, kHeader = 34, kFooter = 56, kGap = 10, kTop = 30;
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  double scale = 1.0;
  int panel_w = 0, panel_h = 0;
  int radius = 0;  // of a place's disc
  int shade = 0;   // of a candidate's shading

  LocalisationLayout(const std::vector<Eigen::Vector2d>& points,
                     const std::optional<Eigen::Vector2d>& query_position, double spacing) {
    const auto extend = [&](const Eigen::Vector2d& p) {
      min_x = std::min(min_x, p.x());
      max_x = std::max(max_x, p.x());
      min_y = std::min(min_y, p.y());
      max_y = std::max(max_y, p.y());
    };
    for (const Eigen::Vector2d& p : points) extend(p);
    if (query_position) extend(*query_position);
    min_x -= spacing;
    min_y -= spacing;
    max_x += spacing;
    max_y += spacing;
    scale = std::min(kPanel / (max_x - min_x), kPanel / (max_y - min_y));
    panel_w = static_cast<int>(std::ceil((max_x - min_x) * scale));
    panel_h = static_cast<int>(std::ceil((max_y - min_y) * scale));
    radius = std::max(3, static_cast<int>(std::lround(0.28 * spacing * scale)));
    shade = std::max(radius + 2, static_cast<int>(std::lround(0.62 * spacing * scale)));
  }

  int panel_x(int level) const { return kGap + level * (panel_w + kGap); }

  // y grows upwards in the world, downwards in the image.
  cv::Point pixel(int level, const Eigen::Vector2d& p) const {
    return cv::Point(panel_x(level) + static_cast<int>(std::lround((p.x() - min_x) * scale)),
                     kTop + kHeader + static_cast<int>(std::lround((max_y - p.y()) * scale)));
  }
};

// What one level of the search drew from the places.
void draw_level(cv::Mat& figure, const LocalisationLayout& layout, int l,
                const memory::Localiser& localiser, const signature::Signature& query,
                const signature::LevelResult& level, const std::vector<Eigen::Vector2d>& points) {
  cv::rectangle(figure,
                cv::Rect(layout.panel_x(l), LocalisationLayout::kTop + LocalisationLayout::kHeader,
                         layout.panel_w, layout.panel_h),
                cv::Scalar(245, 245, 245), cv::FILLED);
  const Eigen::VectorXf dis = localiser.index().dissimilarities(query, static_cast<std::size_t>(l));
  std::vector<double> values(dis.data(), dis.data() + dis.size());
  const std::vector<double> similarity = signature::rescale_similarities(values);
  for (const signature::Candidate& c : level.candidates) {
    cv::circle(figure, layout.pixel(l, points[c.place]), layout.shade, cv::Scalar(190, 190, 190),
               cv::FILLED, cv::LINE_AA);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cv::Point at = layout.pixel(l, points[i]);
    cv::circle(figure, at, layout.radius, viridis(similarity[i]), cv::FILLED, cv::LINE_AA);
    cv::circle(figure, at, layout.radius, cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
  }
  if (!level.candidates.empty()) {
    cv::circle(figure, layout.pixel(l, points[level.candidates.front().place]), layout.radius + 3,
               cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
  }
}

void draw_cross(cv::Mat& figure, cv::Point c) {
  cv::line(figure, c + cv::Point(-8, -8), c + cv::Point(8, 8), cv::Scalar(0, 0, 220), 2,
           cv::LINE_AA);
  cv::line(figure, c + cv::Point(-8, 8), c + cv::Point(8, -8), cv::Scalar(0, 0, 220), 2,
           cv::LINE_AA);
}

void draw_diamond(cv::Mat& figure, cv::Point c) {
  const std::vector<cv::Point> diamond{c + cv::Point(0, -9), c + cv::Point(9, 0),
                                       c + cv::Point(0, 9), c + cv::Point(-9, 0)};
  cv::fillConvexPoly(figure, diamond, cv::Scalar(255, 255, 255), cv::LINE_AA);
  cv::polylines(figure, diamond, true, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
}

// The colour bar and the legend under the panels.
void draw_legend(cv::Mat& figure, const LocalisationLayout& layout, bool query_position,
                 memory::PositionFrame frame) {
  constexpr int gap = LocalisationLayout::kGap;
  const int bar_y = LocalisationLayout::kTop + LocalisationLayout::kHeader + layout.panel_h + 12;
  const int bar_w = std::min(300, figure.cols - 2 * gap);
  for (int x = 0; x < bar_w; ++x) {
    cv::line(figure, cv::Point(gap + x, bar_y), cv::Point(gap + x, bar_y + 10),
             viridis(1000.0 * x / (bar_w - 1)));
  }
  put_text(figure, "0", cv::Point(gap, bar_y + 26), 0.4);
  put_text(figure, "similarity (Eq. 3)   1000", cv::Point(gap + bar_w - 190, bar_y + 26), 0.4);
  put_text(figure,
           std::string("grey: candidate set; ring: best place; diamond: estimate") +
               (query_position ? "; red x: truth" : "") + "; positions: " + to_string(frame),
           cv::Point(gap + bar_w + 16, bar_y + 10), 0.4);
}

}  // namespace

cv::Mat localisation_figure(const memory::Localiser& localiser, const signature::Signature& query,
                            const memory::Localisation& result,
                            std::optional<Eigen::Vector2d> query_position,
                            const std::string& title) {
  const auto positions = memory::place_positions(localiser.memory());
  if (!positions) {
    throw UsageError("the map's places have no positions (no lattice, no ground truth) to draw");
  }
  const std::vector<Eigen::Vector2d>& points = positions->second;
  const std::vector<int>& levels = localiser.index().levels();
  const LocalisationLayout layout(points, query_position, memory::typical_spacing(points));
  const int count = static_cast<int>(levels.size());
  constexpr int gap = LocalisationLayout::kGap;
  cv::Mat figure(LocalisationLayout::kTop + LocalisationLayout::kHeader + layout.panel_h +
                     LocalisationLayout::kFooter,
                 gap + count * (layout.panel_w + gap), CV_8UC3, cv::Scalar(255, 255, 255));
  put_text(figure, title, cv::Point(gap, 20), 0.55);
  for (int l = 0; l < count; ++l) {
    const signature::LevelResult& level = result.search.levels[static_cast<std::size_t>(l)];
    draw_level(figure, layout, l, localiser, query, level, points);
    if (query_position) draw_cross(figure, layout.pixel(l, *query_position));
    if (l + 1 == count && result.position) {
      draw_diamond(figure, layout.pixel(l, result.position->interpolated_position));
    }
    put_text(figure,
             "m = " + std::to_string(levels[static_cast<std::size_t>(l)]) + ": " +
                 std::to_string(level.candidates.size()) + " candidate" +
                 (level.candidates.size() == 1 ? "" : "s") + " of " + std::to_string(points.size()),
             cv::Point(layout.panel_x(l) + 4, LocalisationLayout::kTop + 22));
  }
  draw_legend(figure, layout, query_position.has_value(), positions->first);
  return figure;
}

namespace {

struct Spectra {
  int lines = 0;
  int half = 0;                 // W/2 + 1 components
  std::vector<cv::Mat> places;  // lines × half magnitudes per place
};

Spectra read_spectra(const VisualMemory& memory, signature::ColourMode mode) {
  Spectra spectra;
  signature::SignatureExtractor extractor({1, mode});
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    const std::string& source = memory.place(i).source;
    const cv::Mat image = io::read_image(source);
    spectra.places.push_back(extractor.full_spectrum(image, source));
  }
  spectra.lines = spectra.places.front().rows;
  spectra.half = spectra.places.front().cols;
  for (const cv::Mat& s : spectra.places) {
    if (s.rows != spectra.lines || s.cols != spectra.half) {
      throw UsageError("the map's source images differ in size; figures need one size");
    }
  }
  return spectra;
}

// terms[k] = Σ_lines |a_k − b_k|; Dis at m is the sum of the first m.
std::vector<double> component_terms(const cv::Mat& a, const cv::Mat& b) {
  std::vector<double> terms(static_cast<std::size_t>(a.cols), 0.0);
  for (int line = 0; line < a.rows; ++line) {
    const float* pa = a.ptr<float>(line);
    const float* pb = b.ptr<float>(line);
    for (int k = 0; k < a.cols; ++k) terms[static_cast<std::size_t>(k)] += std::fabs(pa[k] - pb[k]);
  }
  return terms;
}

double prefix(const std::vector<double>& terms, int m) {
  return std::accumulate(terms.begin(), terms.begin() + std::min<std::size_t>(m, terms.size()),
                         0.0);
}

// One point per distance of `distance` (ascending): the mean of `value` over the places at that
// distance (within 1 µm). Each step takes at least one place, whatever the numbers.
std::pair<std::vector<double>, std::vector<double>> mean_per_distance(
    const std::vector<double>& distance, const std::vector<double>& value) {
  std::vector<double> x, y;
  for (std::size_t a = 0; a < distance.size();) {
    std::size_t b = a + 1;
    double sum = value[a];
    while (b < distance.size() && distance[b] - distance[a] < 1e-6) sum += value[b++];
    x.push_back(distance[a]);
    y.push_back(sum / static_cast<double>(b - a));
    a = b;
  }
  return {x, y};
}

// The places' true positions; InputError for one that is not finite or absurdly far, before
// any distance overflows or a loop over distances spins.
std::vector<Eigen::Vector2d> true_positions(const VisualMemory& memory) {
  std::vector<Eigen::Vector2d> positions;
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    const CameraPose& truth = *memory.place(i).truth;
    if (!plausible_position(truth)) {
      throw InputError("place " + std::to_string(i) + " has a true position of (" +
                       general(truth.x_m) + ", " + general(truth.y_m) +
                       ") m: not finite or farther than " + general(kMaxCoordinateM / 1000) +
                       " km from the origin");
    }
    positions.push_back(truth.floor_position());
  }
  return positions;
}

// The place nearest the places' centroid.
std::size_t middle_place(const std::vector<Eigen::Vector2d>& positions) {
  Eigen::Vector2d centre(0, 0);
  for (const Eigen::Vector2d& p : positions) centre += p;
  centre *= 1.0 / static_cast<double>(positions.size());
  std::size_t middle = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if ((positions[i] - centre).norm() < (positions[middle] - centre).norm()) middle = i;
  }
  return middle;
}

// Every pair's per-component terms (component_terms), computed once for Figs. 6 and 7.
class PairTerms {
 public:
  explicit PairTerms(const Spectra& spectra)
      : n_(spectra.places.size()), terms_(spectra.places.size() * spectra.places.size()) {
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t j = i + 1; j < n_; ++j) {
        terms_[i * n_ + j] = component_terms(spectra.places[i], spectra.places[j]);
      }
    }
  }
  // Dis between places i and j over the first m components.
  double dissimilarity(std::size_t i, std::size_t j, int m) const {
    return prefix(i < j ? terms_[i * n_ + j] : terms_[j * n_ + i], m);
  }

 private:
  std::size_t n_;
  std::vector<std::vector<double>> terms_;
};

// What every figure reads: the map's places, where they truly are, and their spectra.
struct FigureInputs {
  const VisualMemory& memory;
  std::vector<Eigen::Vector2d> positions;  // truth
  double spacing = 0.0;
  std::size_t middle = 0;  // the place nearest the centre
  Spectra luminance, colour;
  PairTerms luminance_terms, colour_terms;

  std::size_t count() const { return positions.size(); }
  double distance(std::size_t i, std::size_t j) const {
    return (positions[i] - positions[j]).norm();
  }
};

// Where the figures go, and what was written.
class FigureFolder {
 public:
  FigureFolder(std::filesystem::path folder, SignatureFigures& out)
      : folder_(std::move(folder)), out_(out) {}
  void csv(const std::string& name, const std::string& text) {
    write_output_file(folder_ / name, text);
    out_.files.push_back(folder_ / name);
  }
  template <typename Plot>
  void plot(const Plot& plot, const std::string& name) {
    plot.save(folder_ / name);
    out_.files.push_back(folder_ / name);
  }

 private:
  std::filesystem::path folder_;
  SignatureFigures& out_;
};

// Fig. 5: the spectrum of a row of the middle place, and its mean over rows.
void spectrum_figure(const FigureInputs& in, FigureFolder& folder, std::ostream& summary) {
  const cv::Mat& s = in.luminance.places[in.middle];
  const int half = in.luminance.half;
  const int row = s.rows / 2;
  std::vector<double> k, middle_row, mean_rows;
  std::ostringstream csv;
  write_csv_line(csv, {"k", "magnitude_row_" + std::to_string(row), "magnitude_mean_over_rows"});
  for (int c = 0; c < std::min(30, half); ++c) {
    double mean = 0.0;
    for (int y = 0; y < s.rows; ++y) mean += s.at<float>(y, c) / s.rows;
    k.push_back(c);
    middle_row.push_back(s.at<float>(row, c));
    mean_rows.push_back(mean);
    write_csv_line(csv, {std::to_string(c), general(s.at<float>(row, c)), general(mean)});
  }
  double low = 0.0, all = 0.0;
  for (int y = 0; y < s.rows; ++y) {
    for (int c = 1; c < half; ++c) {
      const double power = double(s.at<float>(y, c)) * s.at<float>(y, c);
      all += power;
      if (c < 15) low += power;
    }
  }
  folder.csv("fig5_spectrum.csv", csv.str());
  measures::LinePlot plot("Fig. 5: Fourier magnitudes of place " + std::to_string(in.middle) +
                              " (k = 0 is the mean grey level)",
                          "component k", "|F(k)|, grey levels");
  plot.add_series("row " + std::to_string(row), k, middle_row,
                  measures::SeriesStyle::kLineAndPoints);
  plot.add_series("mean over rows", k, mean_rows, measures::SeriesStyle::kLineAndPoints);
  folder.plot(plot, "fig5_spectrum.png");
  summary << "Fig. 5: components 1..14 hold " << fixed(100.0 * low / all, 1)
          << "% of the power of components 1.." << half - 1 << " (place " << in.middle << ")\n";
}

// Fig. 6: similarity of the middle place to its neighbours, for m = 2, 5, 15, 50, all.
void components_figure(const FigureInputs& in, FigureFolder& folder) {
  const std::size_t middle = in.middle;
  const int half = in.luminance.half;
  std::vector<std::size_t> near;
  for (std::size_t j = 0; j < in.count(); ++j) {
    if (j != middle && in.distance(j, middle) <= 3.5 * in.spacing) near.push_back(j);
  }
  std::sort(near.begin(), near.end(), [&](std::size_t a, std::size_t b) {
    return in.distance(a, middle) < in.distance(b, middle);
  });
  measures::LinePlot plot(
      "Fig. 6: similarity of place " + std::to_string(middle) + " to its neighbours, by m",
      "distance to the input place, m", "similarity (Eq. 3 over these places), mean");
  std::ostringstream csv;
  const std::vector<int> ms{2, 5, 15, 50, half};
  std::vector<std::string> header{"place", "distance_m"};
  for (int m : ms) header.push_back("similarity_m" + std::to_string(m));
  write_csv_line(csv, header);
  std::vector<std::vector<double>> sims;
  std::vector<double> distance;
  for (std::size_t j : near) distance.push_back(in.distance(j, middle));
  for (int m : ms) {
    std::vector<double> dis;
    for (std::size_t j : near) dis.push_back(in.luminance_terms.dissimilarity(middle, j, m));
    sims.push_back(signature::rescale_similarities(dis));
    // One point per distance: the mean over the neighbours at that distance.
    const auto [x, y] = mean_per_distance(distance, sims.back());
    plot.add_series(m == half ? "m = " + std::to_string(m) + " (all)" : "m = " + std::to_string(m),
                    x, y, measures::SeriesStyle::kLineAndPoints);
  }
  for (std::size_t r = 0; r < near.size(); ++r) {
    std::vector<std::string> fields{std::to_string(near[r]), general(distance[r])};
    for (const auto& s : sims) fields.push_back(general(s[r]));
    write_csv_line(csv, fields);
  }
  folder.csv("fig6_components.csv", csv.str());
  folder.plot(plot, "fig6_components.png");
}

// Fig. 6, measured: leave-one-out localisation against m. Each place in turn is the query; it
// is localised when the most similar other place is a grid neighbour (within 1.05 spacings).
void localisation_rate_figure(const FigureInputs& in, FigureFolder& folder, std::ostream& summary) {
  const int half = in.luminance.half;
  const std::size_t n = in.count();
  std::vector<int> ms{1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 75, 100, 150};
  ms.erase(std::remove_if(ms.begin(), ms.end(), [&](int m) { return m >= half; }), ms.end());
  ms.push_back(half);
  std::vector<double> x, rate_lum, rate_col;
  std::ostringstream csv;
  write_csv_line(csv, {"m", "leave_one_out_rate_luminance", "leave_one_out_rate_per_channel"});
  for (int m : ms) {
    int ok_lum = 0, ok_col = 0;
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t best_lum = i, best_col = i;
      double lum = 1e300, col = 1e300;
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const double dl = in.luminance_terms.dissimilarity(i, j, m);
        const double dc = in.colour_terms.dissimilarity(i, j, m);
        if (dl < lum) lum = dl, best_lum = j;
        if (dc < col) col = dc, best_col = j;
      }
      ok_lum += in.distance(best_lum, i) <= 1.05 * in.spacing;
      ok_col += in.distance(best_col, i) <= 1.05 * in.spacing;
    }
    x.push_back(m);
    rate_lum.push_back(100.0 * ok_lum / n);
    rate_col.push_back(100.0 * ok_col / n);
    write_csv_line(csv, {std::to_string(m), general(rate_lum.back()), general(rate_col.back())});
  }
  folder.csv("fig6_localisation_rate.csv", csv.str());
  measures::LinePlot plot("Fig. 6 measured: leave-one-out localisation by number of components",
                          "components compared, m", "% of places whose best match is a neighbour");
  plot.add_series("luminance", x, rate_lum, measures::SeriesStyle::kLineAndPoints);
  plot.add_series("per channel (B, G, R)", x, rate_col, measures::SeriesStyle::kLineAndPoints);
  folder.plot(plot, "fig6_localisation_rate.png");
  summary << "Fig. 6: leave-one-out rate, luminance / per channel:";
  for (std::size_t i = 0; i < ms.size(); ++i) {
    summary << " m=" << ms[i] << ": " << fixed(rate_lum[i], 0) << "/" << fixed(rate_col[i], 0)
            << "%";
  }
  summary << '\n';
}

// The middle place and up to four more, each the farthest from those before it.
std::vector<std::size_t> reference_places(const FigureInputs& in) {
  std::vector<std::size_t> references{in.middle};
  while (references.size() < std::min<std::size_t>(5, in.count())) {
    std::size_t far = 0;
    double far_d = -1.0;
    for (std::size_t i = 0; i < in.count(); ++i) {
      double d = 1e300;
      for (std::size_t r : references) d = std::min(d, in.distance(i, r));
      if (d > far_d) far_d = d, far = i;
    }
    references.push_back(far);
  }
  return references;
}

// Fig. 7: dissimilarity (m = 15) against distance from five reference places, and the median
// over all pairs in bins of half a spacing.
void dissimilarity_distance_figure(const FigureInputs& in, FigureFolder& folder,
                                   std::ostream& summary) {
  const int m = std::min(15, in.luminance.half);
  const std::size_t n = in.count();
  measures::LinePlot plot("Fig. 7: dissimilarity (Eq. 2, m = 15, luminance) against distance",
                          "distance between the two places, m", "Dis / (rows x m), grey levels");
  const double norm = static_cast<double>(in.luminance.lines) * m;
  std::ostringstream csv;
  write_csv_line(csv, {"reference_place", "other_place", "distance_m", "dissimilarity_per_value"});
  for (std::size_t r : reference_places(in)) {
    std::vector<std::pair<double, double>> curve;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == r) continue;
      const double d = in.distance(j, r);
      const double dis = in.luminance_terms.dissimilarity(r, j, m) / norm;
      curve.emplace_back(d, dis);
      write_csv_line(csv, {std::to_string(r), std::to_string(j), general(d), general(dis)});
    }
    std::sort(curve.begin(), curve.end());
    std::vector<double> distances, values;
    for (const auto& [d, value] : curve) {
      distances.push_back(d);
      values.push_back(value);
    }
    // One point per distance (the mean of places at the same distance), as a line.
    const auto [x, y] = mean_per_distance(distances, values);
    plot.add_series("from place " + std::to_string(r), x, y, measures::SeriesStyle::kLine);
  }
  // The median over all pairs, in bins.
  std::map<int, std::vector<double>> bins;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      bins[static_cast<int>(std::lround(in.distance(j, i) / (0.5 * in.spacing)))].push_back(
          in.luminance_terms.dissimilarity(i, j, m) / norm);
    }
  }
  // A place against itself: Dis = 0 at distance 0.
  std::vector<double> bx{0.0}, by{0.0};
  for (auto& [bin, values] : bins) {
    if (values.size() < 3) continue;
    bx.push_back(bin * 0.5 * in.spacing);
    by.push_back(median(values));
  }
  plot.add_series("median of all pairs", bx, by, measures::SeriesStyle::kLineAndPoints);
  folder.csv("fig7_dissimilarity_distance.csv", csv.str());
  folder.plot(plot, "fig7_dissimilarity_distance.png");
  summary << "Fig. 7: median Dis per value at distance (m):";
  for (std::size_t i = 1; i < bx.size(); i += 2) {
    summary << ' ' << fixed(bx[i], 2) << ": " << fixed(by[i], 2);
  }
  summary << '\n';
}

}  // namespace

SignatureFigures write_signature_figures(const VisualMemory& memory,
                                         const std::filesystem::path& folder) {
  if (!memory.all_have_truth()) {
    throw UsageError(
        "figures need a map whose places all have ground-truth poses (explore a "
        "rendered grid, e.g. omninav render --trajectory grid:...)");
  }
  if (memory.place_count() < 8) throw UsageError("figures need a map of at least 8 places");
  std::vector<Eigen::Vector2d> positions = true_positions(memory);
  std::filesystem::create_directories(folder);
  const double spacing = memory::typical_spacing(positions);
  const std::size_t middle = middle_place(positions);
  Spectra luminance = read_spectra(memory, signature::ColourMode::kLuminance);
  Spectra colour = read_spectra(memory, signature::ColourMode::kPerChannel);
  PairTerms luminance_terms(luminance), colour_terms(colour);
  const FigureInputs in{memory,
                        std::move(positions),
                        spacing,
                        middle,
                        std::move(luminance),
                        std::move(colour),
                        std::move(luminance_terms),
                        std::move(colour_terms)};

  SignatureFigures out;
  FigureFolder files(folder, out);
  std::ostringstream summary;
  summary << memory.place_count() << " places, spacing " << fixed(spacing, 3) << " m, panoramas "
          << 2 * (in.luminance.half - 1) << " columns x " << in.luminance.lines << " rows\n";
  spectrum_figure(in, files, summary);
  components_figure(in, files);
  localisation_rate_figure(in, files, summary);
  dissimilarity_distance_figure(in, files, summary);
  out.summary = summary.str();
  return out;
}

}  // namespace omninav::report
