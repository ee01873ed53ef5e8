// What the command line does with bad numbers, failing writes and outputs it must not damage:
// each test sets up the fault and checks the exit status, the message and the files left
// behind.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "command_line_test.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << stream.rdbuf();
  return bytes.str();
}

// `map` again with place `index`'s true x replaced: a truth no explorer would write, as a
// damaged or hand-edited file holds it.
memory::VisualMemory with_true_x(const memory::VisualMemory& map, memory::PlaceIndex index,
                                 double x_m) {
  memory::VisualMemory copy(map.parameters());
  if (map.exploration_spacing_m()) copy.set_exploration_spacing_m(*map.exploration_spacing_m());
  for (const memory::Run& run : map.runs()) copy.add_run(run);
  for (memory::PlaceIndex i = 0; i < map.place_count(); ++i) {
    memory::Place place = map.place(i);
    if (i == index) place.truth->x_m = x_m;
    copy.add_place(std::move(place));
  }
  for (const memory::VisualMemory::EdgeRef& edge : map.edges()) {
    copy.add_edge(edge.from, edge.to, *edge.edge);
  }
  return copy;
}

class Reliability : public CommandLineTest {
 protected:
  void make_map() {
    render_and_explore_grid();
    image_ = io::read_all(*io::open_sequence(grid_)).at(3).source;
  }

  // Runs omninav with its standard output on /dev/full (a full disk); keeps standard error.
  int run_onto_full_disk(std::vector<std::string> args) {
    args.insert(args.begin(), {"--config-dir", config_dir_.string()});
    std::fflush(stdout);
    const int saved = ::dup(1);
    const int full = ::open("/dev/full", O_WRONLY);
    ::dup2(full, 1);
    ::testing::internal::CaptureStderr();
    const int status = run(args);
    errors_ = ::testing::internal::GetCapturedStderr();
    std::cout.clear();
    std::clearerr(stdout);
    ::dup2(saved, 1);
    ::close(saved);
    ::close(full);
    return status;
  }

  std::string image_;
};

TEST_F(Reliability, NonFiniteNumbersAreRefusedByEveryNumberOption) {
  const fs::path existing = folder_ / "some.vmem";
  std::ofstream(existing) << "x";
  const std::string in = folder_.string(), out = (folder_ / "out").string();
  const std::vector<std::vector<std::string>> commands = {
      {"unwrap", "-i", in, "-o", out, "--centre-x", "nan"},
      {"unwrap", "-i", in, "-o", out, "--outer", "inf"},
      {"unwrap", "-i", in, "-o", out, "--front-offset", "nan"},
      {"render", "--trajectory", "rotate:turns=0.1", "--out", out, "--noise", "nan"},
      {"render", "--trajectory", "rotate:turns=0.1", "--out", out, "--exposure", "nan"},
      {"compass", "-i", in, "--threshold", "nan"},
      {"explore", "--input", in, "--out", out, "--dissimilarity", "nan"},
      {"explore", "--input", in, "--out", out, "--every-m", "-inf"},
      {"organise", existing.string(), "--step-m", "nan"},
  };
  for (const std::vector<std::string>& command : commands) {
    const std::string option = command[command.size() - 2];
    EXPECT_EQ(run_omninav(command), 2) << option;
    EXPECT_NE(errors_.find(option + ": '" + command.back() + "' is not a finite number"),
              std::string::npos)
        << errors_;
  }
  // A range without an upper bound is said so (CLI11 printed DBL_MAX in 309 digits).
  EXPECT_EQ(run_omninav({"unwrap", "-i", in, "-o", out, "--centre-x", "-1"}), 2);
  EXPECT_NE(errors_.find("--centre-x: '-1' is not >= 0\n"), std::string::npos) << errors_;
  EXPECT_LT(errors_.size(), 100u) << errors_;
  // Numbers inside a value are arguments too: exit status 2, as for an option's own.
  EXPECT_EQ(run_omninav({"compass", "-i", in, "--method", "fx:nan"}), 2) << errors_;
  EXPECT_EQ(run_omninav({"render", "--trajectory", "grid:nx=nan", "--out", out}), 2) << errors_;
  EXPECT_NE(errors_.find("key nx: 'nan' is not a whole number"), std::string::npos) << errors_;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Reliability, LostStandardOutputIsAFailure) {
  make_map();
  EXPECT_EQ(run_onto_full_disk({"compass", "--input", grid_.string(), "--out", "-"}), 1);
  EXPECT_NE(errors_.find("standard output: cannot write (No space left on device)"),
            std::string::npos)
      << errors_;
  EXPECT_EQ(run_onto_full_disk({"localise", map_.string(), image_}), 1);
  EXPECT_NE(errors_.find("standard output: cannot write"), std::string::npos) << errors_;
}

TEST_F(Reliability, AFailedWriteNamesTheFileAndLeavesNothing) {
  make_map();
  // A device is written, never replaced (as root, renaming onto /dev/full replaced it).
  EXPECT_EQ(run_omninav({"compass", "--input", grid_.string(), "--out", "/dev/full"}), 1);
  EXPECT_NE(errors_.find("/dev/full: cannot write (No space left on device)"), std::string::npos)
      << errors_;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  const fs::path outputs = folder_ / "outputs";
  fs::create_directories(outputs);
  EXPECT_EQ(run_omninav({"compass", "--input", grid_.string(), "--out",
                         (outputs / "no" / "h.csv").string()}),
            1);
  EXPECT_NE(errors_.find("h.csv: cannot write"), std::string::npos) << errors_;
  EXPECT_TRUE(fs::is_empty(outputs)) << "no temporary left behind";
}

TEST_F(Reliability, AFeaturelessQueryMatchesNoPlace) {
  make_map();
  const fs::path black = folder_ / "black.png";
  cv::imwrite(black.string(), cv::Mat(24, 180, CV_8UC3, cv::Scalar::all(0)));
  EXPECT_EQ(run_omninav({"localise", map_.string(), black.string()}), 1);
  EXPECT_NE(errors_.find("black.png: matches no place of the map"), std::string::npos) << errors_;
  EXPECT_EQ(std::count(errors_.begin(), errors_.end(), '\n'), 1) << errors_;
  EXPECT_EQ(output_.find("place"), std::string::npos) << output_;
  // Among other queries: reported as such, the others answered.
  EXPECT_EQ(run_omninav({"localise", map_.string(), black.string(), image_}), 0) << errors_;
  EXPECT_NE(output_.find("black.png: matches no place of the map"), std::string::npos) << output_;
  EXPECT_NE(output_.find(image_ + ": place 3 "), std::string::npos) << output_;
}

TEST_F(Reliability, ASingleQuerysPlotLeavesAnEarlierRunsFiguresAlone) {
  make_map();
  const fs::path plot = folder_ / "p.png";
  const fs::path earlier = folder_ / "p_0000.png";
  std::ofstream(earlier) << "an earlier run's figure";
  ASSERT_EQ(run_omninav({"localise", map_.string(), image_, "--plot", plot.string()}), 0)
      << errors_;
  EXPECT_EQ(read_bytes(earlier), "an earlier run's figure");
  EXPECT_FALSE(cv::imread(plot.string()).empty());
  ASSERT_EQ(run_omninav({"localise", map_.string(), image_, image_, "--plot", plot.string()}), 0)
      << errors_;
  EXPECT_FALSE(cv::imread(earlier.string()).empty());
  EXPECT_FALSE(cv::imread((folder_ / "p_0001.png").string()).empty());
}

TEST_F(Reliability, OrganiseChecksItsOutputsBeforeChangingTheMap) {
  make_map();
  const std::string before = read_bytes(map_);
  EXPECT_EQ(run_omninav({"organise", map_.string(), "--step-m", "0.3", "--plot",
                         (folder_ / "no" / "such" / "x.png").string()}),
            1);
  EXPECT_NE(errors_.find("x.png: cannot write"), std::string::npos) << errors_;
  EXPECT_EQ(read_bytes(map_), before);
  EXPECT_FALSE(memory::load_map(map_).all_have_lattice());

  ASSERT_EQ(run_omninav({"organise", map_.string(), "--step-m", "0.3"}), 0) << errors_;
  EXPECT_NE(output_.find("vs truth: RMSE"), std::string::npos) << output_;
  EXPECT_EQ(output_.find("nan"), std::string::npos) << output_;  // "no interior places"

  // A truth of 1e12 mm (OpenCV's triangulation threw on it, after the map had been changed) is
  // refused where the map is read, so organise fails before it changes anything.
  memory::MapStore(map_).save(with_true_x(memory::load_map(map_), 2, 1e9),
                              {.overwrite = true, .after_place = {}});
  const std::string absurd = read_bytes(map_);
  EXPECT_EQ(run_omninav({"organise", map_.string(), "--step-m", "0.3"}), 1) << errors_;
  EXPECT_NE(errors_.find("place_truth of place 2: x_m: 1e+09 m is not a position"),
            std::string::npos)
      << errors_;
  EXPECT_EQ(read_bytes(map_), absurd);
}

TEST_F(Reliability, EveryCommandChecksItsOutputPathsBeforeTheWork) {
  make_map();
  const std::string nowhere = (folder_ / "no" / "out.png").string();
  const std::vector<std::vector<std::string>> commands = {
      {"compass", "-i", grid_.string(), "--plot", nowhere},
      {"compass", "-i", grid_.string(), "--out", nowhere},
      {"route", map_.string(), "--from", image_, "--to", image_, "--plot", nowhere},
      {"localise", map_.string(), image_, "--plot", nowhere},
      {"export", map_.string(), "--out", nowhere},
  };
  for (const std::vector<std::string>& command : commands) {
    EXPECT_EQ(run_omninav(command), 1) << command[0];
    // Before the work: nothing printed but the one error line (route: before the lattice check).
    EXPECT_EQ(errors_, "error: " + nowhere + ": cannot write (no folder " +
                           (folder_ / "no").string() + ")\n");
  }
}

TEST_F(Reliability, NoOutputMayReplaceAnInputOfItsCommand) {
  make_map();
  const std::string map = map_.string();
  // The map by other names: ./relative, through a link.
  const fs::path link = folder_ / "link.vmem";
  fs::create_symlink(map_, link);
  const std::string dotted = (map_.parent_path() / "." / map_.filename()).string();
  // A CSV sequence (file, x_m, y_m, heading_deg) of one of the grid's images.
  const fs::path sequence = folder_ / "seq.csv";
  std::ofstream(sequence) << "file,x_m,y_m,heading_deg\n" << image_ << ",1,1,0\n";
  // navigate writes steps.csv into --out: here a copy of the map bears that name.
  const fs::path steps = folder_ / "steps.csv";
  fs::copy_file(map_, steps);
  const std::vector<std::vector<std::string>> commands = {
      {"export", map, "--out", dotted},
      {"export", map, "--out", link.string()},
      {"localise", map, image_, "--plot", map},
      {"localise", map, image_, "--plot", image_},
      {"route", map, "--from", image_, "--to", image_, "--plot", link.string()},
      {"organise", map, "--step-m", "0.3", "--plot", dotted},
      {"compass", "--input", grid_.string(), "--map", map, "--out", map},
      {"compass", "--input", sequence.string(), "--out", sequence.string()},
      {"compass", "--input", sequence.string(), "--plot", sequence.string()},
      {"explore", "--input", sequence.string(), "--out", sequence.string()},
      {"navigate", steps.string(), "--start", "1.5,1.3,0", "--goal", image_, "--out",
       folder_.string()},
  };
  const std::string map_bytes = read_bytes(map_), sequence_bytes = read_bytes(sequence),
                    image_bytes = read_bytes(image_), steps_bytes = read_bytes(steps);
  for (const std::vector<std::string>& command : commands) {
    SCOPED_TRACE(command[0] + " " + command.back());
    EXPECT_EQ(run_omninav(command), 2) << errors_;
    EXPECT_NE(errors_.find("is also the input"), std::string::npos) << errors_;
    EXPECT_EQ(read_bytes(map_), map_bytes);
    EXPECT_EQ(read_bytes(sequence), sequence_bytes);
    EXPECT_EQ(read_bytes(image_), image_bytes);
    EXPECT_EQ(read_bytes(steps), steps_bytes);
  }
}

TEST_F(Reliability, FiguresRefuseAnAbsurdTruthInsteadOfSpinning) {
  make_map();
  memory::MapStore(map_).save(with_true_x(memory::load_map(map_), 2, 1e160),
                              {.overwrite = true, .after_place = {}});
  EXPECT_EQ(run_omninav({"export", map_.string(), "--what", "figures", "--out",
                         (folder_ / "figures").string()}),
            1);
  EXPECT_NE(errors_.find("place_truth of place 2: x_m: 1e+160 m is not a position"),
            std::string::npos)
      << errors_;
  EXPECT_FALSE(fs::exists(folder_ / "figures"));
}

TEST_F(Reliability, OutputsThatAreNotOursAreNotReplaced) {
  make_map();
  // --force replaces a map, not a picture; checked before the work.
  const fs::path picture = folder_ / "picture.png";
  cv::imwrite(picture.string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(7)));
  const std::string bytes = read_bytes(picture);
  EXPECT_EQ(
      run_omninav({"explore", "--input", grid_.string(), "--out", picture.string(), "--force"}), 2);
  EXPECT_NE(errors_.find("picture.png: is not an omninav map; not replacing it"), std::string::npos)
      << errors_;
  EXPECT_EQ(read_bytes(picture), bytes);
  // render, like unwrap, writes into an empty folder unless --force.
  const fs::path images = folder_ / "images";
  fs::create_directories(images);
  fs::copy_file(picture, images / "mine.png");
  EXPECT_EQ(run_omninav({"render", "--trajectory", "rotate:turns=0.1", "--out", images.string(),
                         "--width", "90", "--height", "12"}),
            2);
  EXPECT_NE(errors_.find("is not empty; choose an empty folder or add --force"), std::string::npos)
      << errors_;
  EXPECT_EQ(std::distance(fs::directory_iterator(images), fs::directory_iterator()), 1);
}

TEST_F(Reliability, QuestionableRequestsAreQuestioned) {
  make_map();
  EXPECT_EQ(run_omninav({"localise", map_.string(), image_, "--levels", ""}), 2);
  EXPECT_NE(errors_.find("--levels is empty"), std::string::npos) << errors_;
  // --every-m on images without poses would do nothing.
  const fs::path plain = folder_ / "plain";
  fs::create_directories(plain);
  for (const io::Frame& frame : io::read_all(*io::open_sequence(grid_))) {
    fs::copy_file(frame.source, plain / fs::path(frame.source).filename());
  }
  EXPECT_EQ(run_omninav({"explore", "--input", plain.string(), "--out",
                         (folder_ / "plain.vmem").string(), "--every-m", "0.3"}),
            2);
  EXPECT_NE(errors_.find("no pose"), std::string::npos) << errors_;
  EXPECT_FALSE(fs::exists(folder_ / "plain.vmem"));
  // -q: no summary lines.
  EXPECT_EQ(run_omninav({"-q", "explore", "--input", grid_.string(), "--out",
                         (folder_ / "quiet.vmem").string()}),
            0);
  EXPECT_EQ(output_, "");
}

TEST_F(Reliability, EachBadInputIsOneLineNamingIt) {
  const auto expect_one_line = [&](const std::vector<std::string>& args, int status,
                                   const std::string& message) {
    EXPECT_EQ(run_omninav(args), status) << errors_;
    EXPECT_EQ(errors_, "error: " + message + "\n");
  };
  // (A bad video: tests/io/video_sequence_test.cpp, where OpenCV's own leaks are tolerated.)
  const fs::path fifo = folder_ / "pipe.avi";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_one_line({"compass", "-i", fifo.string()}, 1,
                  fifo.string() + ": is a FIFO, not a video file");
  expect_one_line({"frobnicate"}, 2,
                  "unknown command 'frobnicate' (commands: render, unwrap, compass, explore, "
                  "localise, export, organise, route, navigate, demo, evaluate, completion)");
}

TEST_F(Reliability, ACutPngIsOneLineWithoutLibpngsOwn) {
  make_map();
  const fs::path png = folder_ / "cut.png";
  cv::imwrite(png.string(), cv::Mat(24, 180, CV_8UC3, cv::Scalar(1, 2, 3)));
  fs::resize_file(png, 60);
  EXPECT_EQ(run_omninav({"localise", map_.string(), png.string()}), 1);
  EXPECT_EQ(errors_, "error: " + png.string() +
                         ": cannot read image (unreadable, corrupt or not an image)\n");
}

}  // namespace
}  // namespace omninav::cli
