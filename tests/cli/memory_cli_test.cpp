// omninav explore, localise and export end to end, in-process: exit status, messages, and
// output checked against the rendered images' ground truth (not against the commands' own
// scoring), on a small grid of the built-in room.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "command_line_test.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/json.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

constexpr double kSpacing_m = 0.3;

class ExploreLocaliseExport : public CommandLineTest {
 protected:
  // A 6 × 5 grid at 30 cm explored into a map, and queries rendered along a line between its
  // points at a heading that is not the grid's (the line's direction, 33.7°).
  void make_map_and_queries() {
    render_and_explore_grid();
    queries_ = folder_ / "queries";
    ASSERT_EQ(run_omninav({"render", "--trajectory",
                           "line:x0=1.35,y0=1.15,x1=2.25,y1=1.75,speed_m_s=0.2,fps=1", "--out",
                           queries_.string(), "--width", "180", "--height", "24"}),
              0)
        << errors_;
    query_frames_ = io::read_all(*io::open_sequence(queries_));
  }

  std::filesystem::path queries_;
  std::vector<io::Frame> query_frames_;
};

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto found = std::find(header.begin(), header.end(), name);
  if (found == header.end()) throw std::runtime_error("no column " + name);
  return static_cast<std::size_t>(found - header.begin());
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

// --home-vector: min-warping of each query against its best place's stored panorama. Checked
// against the truth of both poses: the direction from the query to the place, in the world.
TEST_F(ExploreLocaliseExport, LocaliseHomeVectorPointsFromTheQueryToItsBestPlace) {
  make_map_and_queries();
  const memory::VisualMemory map = memory::load_map(map_);
  ASSERT_EQ(run_omninav(
                {"localise", map_.string(), queries_.string(), "--format", "csv", "--home-vector"}),
            0)
      << errors_;
  const std::vector<std::vector<std::string>> rows = csv_rows(output_);
  ASSERT_EQ(rows.size(), query_frames_.size() + 1) << output_;
  const std::size_t best_column = column(rows[0], "best_place");
  const std::size_t home_column = column(rows[0], "home_deg");
  const std::size_t featureless_column = column(rows[0], "home_featureless");
  std::vector<double> errors_deg;
  for (std::size_t q = 0; q < query_frames_.size(); ++q) {
    const CameraPose& truth = *query_frames_[q].truth;
    const CameraPose& place = *map.place(std::stoul(rows[q + 1][best_column])).truth;
    EXPECT_EQ(rows[q + 1][featureless_column], "0") << "query " << q;
    // A query within 5 cm of its place has no direction to speak of.
    if (std::hypot(place.x_m - truth.x_m, place.y_m - truth.y_m) < 0.05) continue;
    const double truth_deg =
        rad_to_deg(std::atan2(place.y_m - truth.y_m, place.x_m - truth.x_m) - truth.heading_rad);
    errors_deg.push_back(
        std::fabs(signed_difference_deg(std::stod(rows[q + 1][home_column]), truth_deg)));
  }
  ASSERT_GE(errors_deg.size(), 2u);
  std::sort(errors_deg.begin(), errors_deg.end());
  // The targets of docs/compass.md for the median (10°); a sign or frame error would be ~180°.
  EXPECT_LT(errors_deg[errors_deg.size() / 2], 10.0) << output_;

  ASSERT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--home-vector"}), 0)
      << errors_;
  EXPECT_EQ(count(output_, "home vector to place"), query_frames_.size()) << output_;
}

TEST_F(ExploreLocaliseExport, LocaliseFindsEachQuerysPlaceAndHeadingInEveryFormat) {
  make_map_and_queries();
  const memory::VisualMemory map = memory::load_map(map_);
  ASSERT_GT(map.place_count(), 10u);

  ASSERT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--format", "csv"}), 0)
      << errors_;
  const std::vector<std::vector<std::string>> rows = csv_rows(output_);
  ASSERT_EQ(rows.size(), query_frames_.size() + 1) << output_;
  const std::vector<std::string>& header = rows[0];
  const std::size_t best_column = column(header, "best_place");
  const std::size_t heading_column = column(header, "heading_deg");
  std::vector<std::string> best_places;
  for (std::size_t q = 0; q < query_frames_.size(); ++q) {
    const CameraPose& truth = *query_frames_[q].truth;
    const std::size_t best = std::stoul(rows[q + 1][best_column]);
    best_places.push_back(rows[q + 1][best_column]);
    ASSERT_LT(best, map.place_count());
    const CameraPose& place = *map.place(best).truth;
    // The truth's nearest place, and the best place's distance from the query.
    double nearest_m = 1e9;
    for (std::size_t p = 0; p < map.place_count(); ++p) {
      nearest_m = std::min(nearest_m, std::hypot(map.place(p).truth->x_m - truth.x_m,
                                                 map.place(p).truth->y_m - truth.y_m));
    }
    const double best_m = std::hypot(place.x_m - truth.x_m, place.y_m - truth.y_m);
    // Within one spacing of the query whenever the query lies among the places.
    if (nearest_m < kSpacing_m) {
      EXPECT_LT(best_m, kSpacing_m + 1e-9) << "query " << q;
    }
    // The query's heading: the place's heading and the phases' relative heading.
    EXPECT_LT(std::fabs(signed_difference_deg(std::stod(rows[q + 1][heading_column]),
                                              rad_to_deg(truth.heading_rad))),
              5.0)
        << "query " << q;
  }

  ASSERT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--format", "json"}), 0)
      << errors_;
  const Json json = Json::parse(output_);
  EXPECT_EQ(json["map"], map_.string());
  ASSERT_EQ(json["queries"].size(), query_frames_.size()) << output_;
  std::vector<std::string> json_best;
  for (const Json& query : json["queries"]) {
    ASSERT_FALSE(query["best"].empty()) << output_;
    json_best.push_back(std::to_string(query["best"][0]["place"].get<int>()));
    EXPECT_TRUE(query["truth"].is_object()) << "the queries have ground truth";
  }
  EXPECT_TRUE(json["summary"].is_object()) << output_;
  EXPECT_EQ(json_best, best_places) << "json and csv name the same best places";

  const std::filesystem::path plot = folder_ / "query.png";
  ASSERT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--plot", plot.string()}), 0)
      << errors_;
  // Text: a line per query (each with ground truth), then the summary.
  EXPECT_EQ(count(output_, "\n  truth "), query_frames_.size()) << output_;
  EXPECT_NE(output_.find("localised "), std::string::npos) << output_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "query_0000.png"));
}

TEST_F(ExploreLocaliseExport, LocaliseErrorsNameTheFile) {
  make_map_and_queries();
  const std::filesystem::path junk = folder_ / "junk.vmem";
  std::ofstream(junk) << "not a map";
  EXPECT_EQ(run_omninav({"localise", junk.string(), queries_.string()}), 1);
  EXPECT_NE(errors_.find("junk.vmem"), std::string::npos) << errors_;
  EXPECT_NE(errors_.find("not an omninav map"), std::string::npos) << errors_;

  EXPECT_EQ(run_omninav({"localise", map_.string(), (folder_ / "nothere.png").string()}), 1);
  EXPECT_NE(errors_.find("nothere.png"), std::string::npos) << errors_;

  EXPECT_EQ(run_omninav({"localise", (folder_ / "missing.vmem").string(), queries_.string()}), 1);
  EXPECT_NE(errors_.find("missing.vmem"), std::string::npos) << errors_;

  EXPECT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--format", "yaml"}), 2);
  EXPECT_NE(errors_.find("--format: yaml not in {text,csv,json}"), std::string::npos) << errors_;
  EXPECT_EQ(run_omninav({"localise", map_.string(), queries_.string(), "--levels", "15,5"}), 2)
      << "levels must increase";
  EXPECT_NE(errors_.find("levels"), std::string::npos) << errors_;
}

TEST_F(ExploreLocaliseExport, ExportWritesEveryPlaceAndEdgeAsCsvAndGraphml) {
  make_map_and_queries();
  const memory::VisualMemory map = memory::load_map(map_);

  const std::filesystem::path places = folder_ / "places.csv";
  ASSERT_EQ(run_omninav({"export", map_.string(), "--out", places.string()}), 0) << errors_;
  const std::vector<std::vector<std::string>> rows = csv_rows(read_text(places));
  ASSERT_EQ(rows.size(), map.place_count() + 1);
  const std::size_t x_column = column(rows[0], "truth_x_m");
  const std::size_t source_column = column(rows[0], "heading_source");
  for (std::size_t p = 0; p < map.place_count(); ++p) {
    EXPECT_NEAR(std::stod(rows[p + 1][x_column]), map.place(p).truth->x_m, 1e-6);
    EXPECT_EQ(rows[p + 1][source_column], "truth") << "a grid database's own headings";
  }

  ASSERT_EQ(run_omninav({"export", map_.string(), "--what", "edges"}), 0) << errors_;
  EXPECT_EQ(csv_rows(output_).size(), map.edge_count() + 1);

  ASSERT_EQ(run_omninav({"export", map_.string(), "--format", "graphml"}), 0) << errors_;
  EXPECT_EQ(output_.rfind("<?xml", 0), 0u);
  EXPECT_EQ(count(output_, "<node "), map.place_count());
  EXPECT_EQ(count(output_, "<edge "), map.edge_count());
  EXPECT_NE(output_.find("</graphml>"), std::string::npos);

  const std::filesystem::path figures = folder_ / "figures";
  ASSERT_EQ(run_omninav({"export", map_.string(), "--what", "figures", "--out", figures.string()}),
            0)
      << errors_;
  for (const char* name : {"fig5_spectrum.png", "fig6_components.png",
                           "fig7_dissimilarity_distance.png", "fig7_dissimilarity_distance.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(figures / name)) << name;
  }

  EXPECT_EQ(run_omninav({"export", (folder_ / "missing.vmem").string()}), 1);
  EXPECT_NE(errors_.find("missing.vmem"), std::string::npos) << errors_;
}

TEST_F(ExploreLocaliseExport, ExploringAStreamTakesHeadingsFromTheCompassAndExtendsTheMap) {
  // A rendered walk (a stream): headings from the visual compass, started at the first
  // frame's true heading, within three columns of the truth at every place (a column of these
  // 180-column panoramas is 2 degrees; measured: 4.7 degrees at most).
  const std::filesystem::path walk = folder_ / "walk";
  ASSERT_EQ(
      run_omninav({"render", "--trajectory", "line:x0=1.2,y0=1.3,x1=3.0,y1=1.6,speed_m_s=0.2,fps=4",
                   "--out", walk.string(), "--width", "180", "--height", "24"}),
      0)
      << errors_;
  map_ = folder_ / "walk.vmem";
  // A fixed threshold, so that a second run over the same frames makes the same places (auto's
  // second run starts from the map's plateau instead of the first frames').
  ASSERT_EQ(run_omninav({"explore", "--input", walk.string(), "--out", map_.string(),
                         "--dissimilarity", "1.5"}),
            0)
      << errors_;
  EXPECT_NE(output_.find("headings: compass"), std::string::npos) << output_;
  const memory::VisualMemory first = memory::load_map(map_);
  ASSERT_GT(first.place_count(), 2u);
  for (std::size_t p = 0; p < first.place_count(); ++p) {
    const memory::Place& place = first.place(p);
    EXPECT_EQ(place.heading_source, memory::HeadingSource::kCompass);
    EXPECT_LT(
        std::fabs(rad_to_deg(signed_difference(*place.heading_rad, place.truth->heading_rad))), 6.0)
        << "place " << p;
  }
  // Exploring again extends the map with a second run.
  ASSERT_EQ(run_omninav({"explore", "--input", walk.string(), "--out", map_.string(),
                         "--dissimilarity", "1.5"}),
            0)
      << errors_;
  const memory::VisualMemory extended = memory::load_map(map_);
  EXPECT_EQ(extended.runs().size(), 2u);
  EXPECT_EQ(extended.place_count(), 2 * first.place_count());
}

TEST_F(ExploreLocaliseExport, ExploringByOdometrySpacesPlacesByWhatTheWheelsMeasured) {
  // A straight drive rendered with noisy wheel odometry beside the truth (30 % relative, so
  // that it differs from the truth by more than a frame's step): --every-m with --odometry
  // makes a place every 0.3 m of odometry, without it every 0.3 m of the true poses.
  const std::filesystem::path drive = folder_ / "drive";
  ASSERT_EQ(run_omninav({"render", "--trajectory",
                         "line:x0=1,y0=1.5,x1=4.5,y1=1.5,speed_m_s=0.2,fps=5,odometry_noise=0.3,"
                         "odometry_seed=2",
                         "--out", drive.string(), "--width", "96", "--height", "14"}),
            0)
      << errors_;
  const std::vector<io::Frame> frames = io::read_all(*io::open_sequence(drive));
  double odometry_m = 0.0, true_m = 0.0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    ASSERT_TRUE(frames[i].odometry) << "frame " << i;
    odometry_m += std::hypot(frames[i].odometry->x_m - frames[i - 1].odometry->x_m,
                             frames[i].odometry->y_m - frames[i - 1].odometry->y_m);
    true_m += std::hypot(frames[i].truth->x_m - frames[i - 1].truth->x_m,
                         frames[i].truth->y_m - frames[i - 1].truth->y_m);
  }
  ASSERT_GT(std::abs(odometry_m - true_m), 0.3) << "the seed's odometry is too close to the truth";
  const auto places = [&](const std::vector<std::string>& extra) {
    const std::filesystem::path map = folder_ / "drive.vmem";
    std::vector<std::string> args = {"explore",         "--input", drive.string(), "--out",
                                     map.string(),      "--force", "--every-m",    "0.3",
                                     "--dissimilarity", "0"};
    args.insert(args.end(), extra.begin(), extra.end());
    EXPECT_EQ(run_omninav(args), 0) << errors_;
    return static_cast<double>(memory::load_map(map).place_count());
  };
  // The first frame, then one every 0.3 m travelled (a frame's 4 cm of slack either way).
  EXPECT_NEAR(places({"--odometry"}), std::floor(odometry_m / 0.3) + 1, 1.0);
  EXPECT_NEAR(places({}), std::floor(true_m / 0.3) + 1, 1.0);

  // A database without odometry cannot be explored by it.
  const std::filesystem::path plain = folder_ / "plain";
  ASSERT_EQ(run_omninav({"render", "--trajectory", "line:x0=1,y0=1.5,x1=2,y1=1.5,fps=5", "--out",
                         plain.string(), "--width", "96", "--height", "14"}),
            0)
      << errors_;
  EXPECT_EQ(run_omninav({"explore", "--input", plain.string(), "--out",
                         (folder_ / "plain.vmem").string(), "--every-m", "0.3", "--odometry"}),
            2);
  EXPECT_NE(errors_.find("no odometry"), std::string::npos) << errors_;
}

}  // namespace
}  // namespace omninav::cli
