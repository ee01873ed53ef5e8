// The commands on a camera (`--input camera:...`), with a video file standing in for the device:
// the same results as the video read directly, and Ctrl-C stopping `explore` with the map
// written up to the last frame it processed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "command_line_test.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/io/video_sequence.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/signature/signature.hpp"

extern char** environ;

namespace omninav::cli {
namespace {

// A robot turning on the spot while the scene slowly changes: frame i is a blend of two smooth
// textures, i/(frames-1) of the way from the first to the second, rolled by 2 i columns.
// MJPEG in AVI at `fps`; false when OpenCV cannot write it.
bool write_turning_video(const std::filesystem::path& file, int frames, double fps) {
  const cv::Size size{128, 32};
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, size);
  if (!writer.isOpened()) return false;
  std::vector<cv::Mat> textures;
  for (int seed : {5, 6}) {
    cv::Mat noise(size, CV_8UC3);
    cv::RNG rng(static_cast<std::uint64_t>(seed));
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 3.0);
    cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
    textures.push_back(noise);
  }
  for (int i = 0; i < frames; ++i) {
    const double along = frames > 1 ? static_cast<double>(i) / (frames - 1) : 0.0;
    cv::Mat blend;
    cv::addWeighted(textures[0], 1.0 - along, textures[1], along, 0.0, blend);
    writer.write(roll_columns(blend, 2 * i));
  }
  return true;
}

constexpr const char* kNoWriter = "cv::VideoWriter cannot write MJPG in AVI on this build";

// The program itself started with `args` (after its name and --config-dir), as a user starts
// it: the read end of a pipe from its file descriptor `piped` (1 or 2) is returned with its
// pid; its other output goes to /dev/null. {-1, -1} when it could not start.
std::pair<pid_t, int> spawn_omninav(const std::filesystem::path& config_dir,
                                    const std::vector<std::string>& args, int piped) {
  std::vector<std::string> words{OMNINAV_PROGRAM, "--config-dir", config_dir.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  int ends[2];
  if (::pipe(ends) != 0) return {-1, -1};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, ends[1], piped);
  posix_spawn_file_actions_addclose(&actions, ends[0]);
  posix_spawn_file_actions_addopen(&actions, piped == 1 ? 2 : 1, "/dev/null", O_WRONLY, 0);
  pid_t child = 0;
  const int status =
      ::posix_spawn(&child, OMNINAV_PROGRAM, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(ends[1]);
  if (status != 0) {
    ::close(ends[0]);
    return {-1, -1};
  }
  return {child, ends[0]};
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class CameraCommands : public CommandLineTest {};

// Timing never changes results: a camera delivering the video's frames at their pace gives the
// outputs of the video read as fast as it goes, byte for byte.
TEST_F(CameraCommands, ACameraGivesTheResultsOfTheSameFramesReadFromTheVideo) {
  const std::filesystem::path video = folder_ / "turning.avi";
  if (!write_turning_video(video, 24, 100.0)) GTEST_SKIP() << kNoWriter;
  const std::string camera = "camera:" + video.string();

  const std::filesystem::path video_csv = folder_ / "video.csv",
                              camera_csv = folder_ / "camera.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", video.string(), "--out", video_csv.string()}), 0)
      << errors_;
  ASSERT_EQ(run_omninav({"compass", "--input", camera, "--out", camera_csv.string()}), 0)
      << errors_;
  EXPECT_NE(errors_.find("24 frames processed; 0 frames dropped"), std::string::npos) << errors_;
  EXPECT_EQ(read_file(camera_csv), read_file(video_csv));
  EXPECT_EQ(csv_rows(read_file(camera_csv)).size(), 25u);

  const std::filesystem::path video_map = folder_ / "video.vmem",
                              camera_map = folder_ / "camera.vmem";
  ASSERT_EQ(run_omninav({"explore", "--input", video.string(), "--out", video_map.string()}), 0)
      << errors_;
  ASSERT_EQ(run_omninav({"explore", "--input", camera, "--out", camera_map.string()}), 0)
      << errors_;
  const memory::VisualMemory from_video = memory::load_map(video_map);
  const memory::VisualMemory from_camera = memory::load_map(camera_map);
  ASSERT_GE(from_video.place_count(), 2u) << "the scene changes: more than one place";
  ASSERT_EQ(from_camera.place_count(), from_video.place_count());
  for (std::size_t i = 0; i < from_video.place_count(); ++i) {
    EXPECT_EQ(from_camera.place(i).source, from_video.place(i).source);
    EXPECT_EQ(from_camera.place(i).signature.magnitude, from_video.place(i).signature.magnitude);
    EXPECT_EQ(from_camera.place(i).heading_rad, from_video.place(i).heading_rad);
  }
  EXPECT_NE(from_camera.runs().back().description.find("24 frames processed; 0 frames dropped"),
            std::string::npos)
      << from_camera.runs().back().description;

  ASSERT_EQ(run_omninav({"localise", video_map.string(), video.string(), "--format", "csv"}), 0)
      << errors_;
  const std::string from_video_text = output_;
  ASSERT_EQ(run_omninav({"localise", video_map.string(), camera, "--format", "csv"}), 0) << errors_;
  EXPECT_EQ(output_, from_video_text);
}

TEST_F(CameraCommands, ACameraThatCannotBeOpenedIsAnInputError) {
  EXPECT_EQ(
      run_omninav({"explore", "--input", "camera:97", "--out", (folder_ / "m.vmem").string()}), 1);
  EXPECT_NE(errors_.find("camera:97"), std::string::npos) << errors_;
  EXPECT_FALSE(std::filesystem::exists(folder_ / "m.vmem"));
}

// The program itself, as a user runs it: Ctrl-C (SIGINT) in the middle of exploring a camera
// (a 10 s video at its pace) ends the run, and the map holds every frame processed until then.
TEST_F(CameraCommands, CtrlCStopsExploringWithTheMapHoldingTheFramesProcessed) {
  constexpr int kFrames = 200;
  constexpr double kFps = 20.0;
  const std::filesystem::path video = folder_ / "long.avi";
  if (!write_turning_video(video, kFrames, kFps)) GTEST_SKIP() << kNoWriter;
  const std::filesystem::path map = folder_ / "live.vmem";

  const auto [child, from_stderr] = spawn_omninav(
      config_dir_,
      {"explore", "--input", "camera:" + video.string(), "--out", map.string(), "--all-frames"}, 2);
  ASSERT_GT(child, 0);

  // Its log says when the camera is open (and its Ctrl-C handler in place); a second later about
  // 20 frames have come.
  std::string errors;
  char buffer[4096];
  while (errors.find("exploring ") == std::string::npos) {
    const ssize_t got = ::read(from_stderr, buffer, sizeof buffer);
    if (got <= 0) break;
    errors.append(buffer, static_cast<std::size_t>(got));
  }
  ASSERT_NE(errors.find("exploring "), std::string::npos) << "no start in its log:\n" << errors;
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_EQ(::kill(child, SIGINT), 0);
  for (ssize_t got; (got = ::read(from_stderr, buffer, sizeof buffer)) > 0;) {
    errors.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(from_stderr);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << ":\n" << errors;
  ASSERT_EQ(WEXITSTATUS(status), 0) << errors;
  EXPECT_NE(errors.find("stopped by Ctrl-C"), std::string::npos) << errors;

  const memory::VisualMemory memory = memory::load_map(map);
  ASSERT_EQ(memory.runs().size(), 1u);
  const memory::Run& run = memory.runs().front();
  EXPECT_GE(run.frames, 1);
  EXPECT_LT(run.frames, kFrames) << "stopped in the middle";
  EXPECT_EQ(memory.place_count(), static_cast<std::size_t>(run.frames)) << "every frame a place";
  EXPECT_NE(run.description.find("stopped by Ctrl-C"), std::string::npos) << run.description;

  // Each place is the frame of the video it names: the frames processed, in order.
  io::VideoSequence frames(video);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  int previous_index = -1;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const memory::Place& place = memory.place(i);
    EXPECT_GT(place.frame_index, previous_index);
    std::optional<io::Frame> frame;
    while ((frame = frames.next()) && frame->index < place.frame_index) {
    }
    ASSERT_TRUE(frame) << place.source;
    EXPECT_EQ(place.source, frame->source);
    EXPECT_EQ(place.signature.magnitude, extractor.compute(frame->image).magnitude) << place.source;
    previous_index = place.frame_index;
  }
}

// Another program following a live robot: `compass --input camera:... --out - --format jsonl`
// delivers each frame's row while the camera runs, at the camera's pace, not all together at
// the end; and the rows are the ones the video read directly gives.
TEST_F(CameraCommands, ALiveRunWritesEachRowWhenItsFrameIsComputed) {
  constexpr int kFrames = 30;
  constexpr double kFps = 10.0;
  const std::filesystem::path video = folder_ / "live.avi";
  if (!write_turning_video(video, kFrames, kFps)) GTEST_SKIP() << kNoWriter;

  const auto [child, from_stdout] = spawn_omninav(
      config_dir_,
      {"-q", "compass", "--input", "camera:" + video.string(), "--out", "-", "--format", "jsonl"},
      1);
  ASSERT_GT(child, 0);

  // Each line with the time it arrived.
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<Clock::time_point, std::string>> lines;
  std::string pending;
  char buffer[4096];
  for (ssize_t got; (got = ::read(from_stdout, buffer, sizeof buffer)) > 0;) {
    pending.append(buffer, static_cast<std::size_t>(got));
    for (std::size_t end; (end = pending.find('\n')) != std::string::npos;) {
      lines.emplace_back(Clock::now(), pending.substr(0, end));
      pending.erase(0, end + 1);
    }
  }
  ::close(from_stdout);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kFrames));

  // Row i comes about i frame periods after the first: the camera's pace. All rows at once at
  // the end would put every one at 0 s; the median lag allows for a loaded machine.
  std::vector<double> lags_s;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const double since_first_s =
        std::chrono::duration<double>(lines[i].first - lines.front().first).count();
    lags_s.push_back(std::abs(since_first_s - static_cast<double>(i) / kFps));
  }
  std::nth_element(lags_s.begin(), lags_s.begin() + lags_s.size() / 2, lags_s.end());
  EXPECT_LE(lags_s[lags_s.size() / 2], 1.0 / kFps) << "rows did not come at the camera's pace";
  const double spread_s =
      std::chrono::duration<double>(lines.back().first - lines.front().first).count();
  EXPECT_GE(spread_s, 0.5 * (kFrames - 1) / kFps) << "rows came together";

  // The JSON rows hold the CSV's values of the same frames read from the video.
  const std::filesystem::path video_csv = folder_ / "video.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", video.string(), "--out", video_csv.string()}), 0)
      << errors_;
  const auto rows = csv_rows(read_file(video_csv));
  ASSERT_EQ(rows.size(), lines.size() + 1);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const nlohmann::json row = nlohmann::json::parse(lines[i].second);
    EXPECT_EQ(row.at("frame").get<int>(), static_cast<int>(i));
    EXPECT_NEAR(row.at("heading_unwrapped_deg").get<double>(), std::stod(rows[i + 1][4]), 1e-9);
    EXPECT_EQ(row.at("confidence").get<std::string>(), rows[i + 1][8]);
  }
}

}  // namespace
}  // namespace omninav::cli
