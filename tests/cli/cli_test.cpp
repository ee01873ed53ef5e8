// The command line end to end, run in-process: exit status, messages and files written.
#include "cli.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "command_line_test.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/omni/unwrap.hpp"

namespace omninav::cli {
namespace {

using CommandLine = CommandLineTest;

TEST_F(CommandLine, RenderWritesADatabaseWithExactGroundTruth) {
  const std::filesystem::path out = folder_ / "run";
  ASSERT_EQ(
      run_omninav({"render", "--trajectory", "rotate:x=1.0,y=1.0,turns=0.25,rate_deg_s=45,fps=4",
                   "--out", out.string(), "--width", "180", "--height", "20"}),
      0)
      << errors_;
  EXPECT_TRUE(std::filesystem::exists(out / "contact_sheet.png"));
  const std::unique_ptr<io::SequenceReader> reader = io::open_sequence(out);
  const std::vector<io::Frame> frames = io::read_all(*reader);
  // A quarter turn at 45°/s lasts 2 s: 8 intervals of 0.25 s, 9 frames.
  ASSERT_EQ(frames.size(), 9u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_TRUE(frames[i].truth.has_value());
    EXPECT_NEAR(frames[i].truth->x_m, 1.0, 1e-9);
    EXPECT_NEAR(frames[i].truth->z_m, 1.0, 1e-9);
    EXPECT_NEAR(frames[i].truth->heading_rad, deg_to_rad(11.25 * i), 1e-9);
    ASSERT_TRUE(frames[i].time_s.has_value());
    EXPECT_NEAR(*frames[i].time_s, 0.25 * i, 1e-9);
    EXPECT_EQ(frames[i].image.cols, 180);
    EXPECT_EQ(frames[i].image.rows, 20);
  }
  // Refuses to replace the database unless told to.
  EXPECT_EQ(run_omninav({"render", "--trajectory", "rotate:turns=0.1", "--out", out.string()}), 2);
  EXPECT_EQ(
      run_omninav({"render", "--trajectory", "rotate:turns=0.1", "--out", out.string(), "--force"}),
      0)
      << errors_;
}

TEST_F(CommandLine, BadTrajectoryIsAUsageErrorOnOneLineNamingTheProblem) {
  EXPECT_EQ(
      run_omninav({"render", "--trajectory", "spiral:turns=2", "--out", (folder_ / "x").string()}),
      2);
  EXPECT_NE(errors_.find("spiral"), std::string::npos) << errors_;
  EXPECT_EQ(std::count(errors_.begin(), errors_.end(), '\n'), 1) << errors_;
  EXPECT_FALSE(std::filesystem::exists(folder_ / "x" / "database_entries.csv"));
}

TEST_F(CommandLine, MissingWorldFileIsAnError) {
  EXPECT_EQ(run_omninav({"render", "--world", (folder_ / "nowhere.obj").string(), "--trajectory",
                         "rotate", "--out", (folder_ / "x").string()}),
            1);
  EXPECT_NE(errors_.find("nowhere.obj"), std::string::npos) << errors_;
}

TEST_F(CommandLine, ConfigWithAnUnknownKeyNamesFileAndKey) {
  const std::filesystem::path config = folder_ / "config";
  std::filesystem::create_directories(config);
  std::filesystem::copy(config_dir_, config, std::filesystem::copy_options::recursive);
  std::ofstream(config / "worlds.yaml", std::ios::app) << "\nrender_quality: high\n";
  config_dir_ = config;
  EXPECT_EQ(run_omninav({"render", "--trajectory", "rotate", "--out", (folder_ / "x").string()}),
            1);
  EXPECT_NE(errors_.find("worlds.yaml"), std::string::npos) << errors_;
  EXPECT_NE(errors_.find("render_quality"), std::string::npos) << errors_;
}

TEST_F(CommandLine, ShippedConfigIsValid) {
  // `render` runs with the shipped camera.yaml and worlds.yaml as the binary finds them
  // (--config-dir). Each shipped file is loaded strictly, key by key, by
  // tests/evaluation/shipped_config_test.cpp.
  EXPECT_EQ(run_omninav({"render", "--trajectory", "rotate:turns=0.05", "--out",
                         (folder_ / "ok").string(), "--width", "36", "--height", "4"}),
            0)
      << errors_;
}

TEST_F(CommandLine, HelpAndUsageErrors) {
  EXPECT_EQ(run_omninav({"--help"}), 0);
  EXPECT_EQ(run_omninav({"render", "--help"}), 0);
  EXPECT_EQ(run_omninav({"render"}), 2);  // --trajectory and --out are required
  EXPECT_EQ(run_omninav({"no-such-command"}), 2);
}

// One name per idea: --force replaces, --plot draws, --out is where outputs go. The old
// spellings still work, with a warning that names the new one, and are hidden from --help.
TEST_F(CommandLine, RenamedFlagsKeepTheirOldSpellingWithAWarning) {
  render_and_explore_grid();
  ASSERT_EQ(
      run_omninav({"explore", "--input", grid_.string(), "--out", map_.string(), "--overwrite"}), 0)
      << errors_;
  EXPECT_NE(errors_.find("--overwrite is now --force"), std::string::npos) << errors_;
  const std::filesystem::path picture = folder_ / "old.png";
  ASSERT_EQ(run_omninav({"organise", map_.string(), "--picture", picture.string()}), 0) << errors_;
  EXPECT_NE(errors_.find("--picture is now --plot"), std::string::npos) << errors_;
  EXPECT_TRUE(std::filesystem::exists(picture));
  for (const char* command : {"explore", "organise", "demo"}) {
    ASSERT_EQ(run_omninav({command, "--help"}), 0);
    for (const char* old_name : {"--overwrite", "--picture", "--report"}) {
      EXPECT_EQ(output_.find(old_name), std::string::npos) << command << " --help: " << old_name;
    }
  }
}

TEST_F(CommandLine, DemoWritesItsReport) {
  const std::filesystem::path report = folder_ / "report";
  const std::filesystem::path map = folder_ / "demo.vmem";
  ASSERT_EQ(run_omninav({"demo", "--out", report.string(), "--map", map.string(), "--queries", "4",
                         "--trials", "2"}),
            0)
      << errors_;
  // Every stage leaves its output: the exploration, the organised map, the localisation, the
  // route and the drives.
  EXPECT_EQ(io::open_sequence(report / "exploration")->size(), 57u);  // the grid minus furniture
  const memory::VisualMemory memory = memory::load_map(map);
  EXPECT_EQ(memory.place_count(), 57u);
  EXPECT_TRUE(memory.all_have_lattice());
  for (const char* file :
       {"exploration/contact_sheet.png", "lattice.png", "localisation.csv", "localisation_0000.png",
        "route.png", "navigation/steps.csv", "navigation/path.png", "trials/trials.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(report / file)) << file;
  }
}

TEST_F(CommandLine, UnwrapRecoversRenderedPanoramasFromSyntheticMirrorImages) {
  // Ground truth: rendered panoramas, wrapped into raw mirror images by omni::wrap_panorama.
  const std::filesystem::path render_out = folder_ / "rendered";
  ASSERT_EQ(
      run_omninav({"render", "--trajectory", "rotate:x=2.4,y=1.2,turns=0.1,rate_deg_s=20,fps=2",
                   "--out", render_out.string()}),
      0)
      << errors_;
  const std::vector<io::Frame> panoramas = io::read_all(*io::open_sequence(render_out));
  omni::UnwrapParams params;  // fractions of the raw width, front at the top, no flip
  params.centre_x = 0.5;
  params.centre_y = 0.5;
  params.inner_radius = 0.1;
  params.outer_radius = 0.48;
  const std::filesystem::path raw = folder_ / "raw";
  std::filesystem::create_directories(raw);
  for (const io::Frame& frame : panoramas) {
    cv::imwrite((raw / ("raw_" + std::to_string(frame.index) + ".png")).string(),
                omni::wrap_panorama(frame.image, params, {800, 800}));
  }
  const std::filesystem::path out = folder_ / "unwrapped";
  ASSERT_EQ(
      run_omninav({"unwrap", "--input", raw.string(), "--out", out.string(), "--units", "fraction",
                   "--centre-x", "0.5", "--centre-y", "0.5", "--inner", "0.1", "--outer", "0.48"}),
      0)
      << errors_;
  for (const io::Frame& frame : panoramas) {
    const cv::Mat unwrapped =
        cv::imread((out / ("raw_" + std::to_string(frame.index) + ".png")).string());
    ASSERT_EQ(unwrapped.size(), frame.image.size());
    cv::Mat difference;
    cv::absdiff(unwrapped, frame.image, difference);
    // Two resamplings of a textured image (wrap, then unwrap) blur edges: a few grey levels on
    // average; a column or row off, or a mirrored panorama, costs tens.
    EXPECT_LT(cv::mean(difference)[1], 6.0) << frame.index;
  }
  // A folder that is not empty is refused unless --force.
  EXPECT_EQ(
      run_omninav({"unwrap", "--input", raw.string(), "--out", out.string(), "--units", "fraction",
                   "--centre-x", "0.5", "--centre-y", "0.5", "--inner", "0.1", "--outer", "0.48"}),
      2);
}

TEST_F(CommandLine, OrganiseThenNavigateNeedTheirPrerequisites) {
  const std::filesystem::path grid = folder_ / "grid";
  ASSERT_EQ(run_omninav({"render", "--trajectory", "grid:x0=1.2,y0=1.0,nx=5,ny=4,spacing_m=0.3",
                         "--out", grid.string(), "--width", "180", "--height", "24"}),
            0)
      << errors_;
  const std::filesystem::path map = folder_ / "grid.vmem";
  ASSERT_EQ(run_omninav({"explore", "--input", grid.string(), "--out", map.string()}), 0)
      << errors_;
  const std::string goal = io::read_all(*io::open_sequence(grid)).back().source;
  // Navigating a map that has no lattice yet: a usage error saying what to do.
  EXPECT_EQ(run_omninav({"navigate", map.string(), "--start", "1.5,1.6,0", "--goal", goal, "--out",
                         (folder_ / "nav").string()}),
            2);
  EXPECT_NE(errors_.find("organise"), std::string::npos) << errors_;
  // The rendered grid database states its spacing (BoB's grid.separationMM): no step needed.
  ASSERT_EQ(run_omninav({"organise", map.string()}), 0) << errors_;
  EXPECT_NE(output_.find("0.300 m between consecutive places (map: the grid database's "
                         "grid.separationMM)"),
            std::string::npos)
      << output_;
  EXPECT_NE(output_.find("quality:"), std::string::npos) << output_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "grid.lattice.png"));
  {
    // A grid database whose metadata does not state it: the scale must be given.
    const std::filesystem::path bare = folder_ / "bare";
    std::filesystem::copy(grid, bare);
    std::ofstream(bare / "database_metadata.yaml") << "metadata:\n  type: grid\n";
    const std::filesystem::path bare_map = folder_ / "bare.vmem";
    ASSERT_EQ(run_omninav({"explore", "--input", bare.string(), "--out", bare_map.string()}), 0)
        << errors_;
    EXPECT_EQ(run_omninav({"organise", bare_map.string()}), 2);
    EXPECT_NE(errors_.find("--step-m"), std::string::npos) << errors_;
    ASSERT_EQ(run_omninav({"organise", bare_map.string(), "--step-m", "0.3"}), 0) << errors_;
  }
  EXPECT_EQ(run_omninav({"navigate", map.string(), "--start", "1.5,1.6,0", "--goal", goal, "--out",
                         (folder_ / "nav").string(), "--max-steps", "5"}),
            0)
      << errors_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "nav" / "steps.csv"));
}

TEST_F(CommandLine, CompassFollowsARenderedTurnAndWritesItsCsv) {
  const std::filesystem::path run = folder_ / "rotate";
  ASSERT_EQ(
      run_omninav({"render", "--trajectory", "rotate:x=2.4,y=1.2,turns=0.25,rate_deg_s=-30,fps=5",
                   "--out", run.string()}),
      0)
      << errors_;
  const std::filesystem::path csv = folder_ / "compass.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", run.string(), "--truth", "--out", csv.string()}), 0)
      << errors_;
  std::ifstream file(csv);
  std::string header, line, last;
  std::getline(file, header);
  int rows = 0;
  while (std::getline(file, line)) {
    last = line;
    ++rows;
  }
  EXPECT_EQ(rows, 16);  // a quarter turn at 30°/s is 3 s: 15 intervals at 5 Hz, 16 frames
  EXPECT_NE(header.find("heading_deg"), std::string::npos) << header;
  // The paper's Algorithm 1 as written follows the same turn: its last error (the CSV's
  // error_deg, next to last) is small.
  const std::filesystem::path paper_csv = folder_ / "compass_paper.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", run.string(), "--truth", "--method", "alg1-paper",
                         "--out", paper_csv.string()}),
            0)
      << errors_;
  std::ifstream paper_file(paper_csv);
  std::string paper_last;
  while (std::getline(paper_file, line)) paper_last = line;
  const std::string without_distance = paper_last.substr(0, paper_last.rfind(','));
  const double paper_error_deg =
      std::stod(without_distance.substr(without_distance.rfind(',') + 1));
  EXPECT_LT(std::abs(paper_error_deg), 1.0) << paper_last;
  // A missing input is an input error (1), through an option as through a positional argument.
  EXPECT_EQ(run_omninav({"compass", "--input", (folder_ / "nowhere").string()}), 1);
  EXPECT_EQ(errors_, "error: " + (folder_ / "nowhere").string() + ": no such file or folder\n");
  EXPECT_EQ(run_omninav({"localise", (folder_ / "nowhere.vmem").string(), "q.png"}), 1);
  EXPECT_EQ(run_omninav({"organise", (folder_ / "nowhere.vmem").string()}), 1);
}

TEST_F(CommandLine, UnwrapOfAFolderWithACorruptImageNamesIt) {
  const std::filesystem::path raw = folder_ / "raw";
  std::filesystem::create_directories(raw);
  std::ofstream(raw / "broken.png") << "not a png";
  EXPECT_EQ(run_omninav({"unwrap", "--input", raw.string(), "--out", (folder_ / "out").string()}),
            1);
  EXPECT_NE(errors_.find("broken.png"), std::string::npos) << errors_;
}

}  // namespace
}  // namespace omninav::cli
