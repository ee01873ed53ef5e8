// Algorithm 1 of Labrosse 2006 (§3.5) and "Fx n", against rendered ground truth.
#include "omninav/compass/visual_compass.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "compass_test_support.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/evaluation/compass_evaluation.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::compass {
namespace {

using evaluation::CompassEvaluation;
using evaluation::CompassTruth;
using testing::random_image;

struct RenderedRun {
  std::vector<CompassEstimate> estimates;
  std::vector<CompassTruth> truth;
  int references = 0;
  CompassEvaluation evaluation;
};

struct RenderedSequence {
  std::vector<CompassFrame> frames;
  std::vector<CompassTruth> truth;
};

// Renders every pose of `trajectory`, with its ground truth.
RenderedSequence render_trajectory(const sim::Trajectory& trajectory,
                                   const sim::Renderer& renderer) {
  RenderedSequence sequence;
  for (std::size_t i = 0; i < trajectory.poses.size(); ++i) {
    const sim::TimedPose& pose = trajectory.poses[i];
    sequence.frames.emplace_back(renderer.render(pose.pose, pose.time_s, static_cast<int>(i)),
                                 static_cast<int>(i));
    sequence.truth.push_back({pose.pose.heading_rad, pose.pose.floor_position(), pose.time_s});
  }
  return sequence;
}

// Renders `spec` in `world` at 360x45, with its ground truth.
RenderedSequence render_sequence(const sim::World& world, const std::string& spec) {
  const sim::Trajectory trajectory = sim::make_trajectory(spec, world);
  const sim::Renderer renderer(world, testing::render_params(360, 45));
  return render_trajectory(trajectory, renderer);
}

// Renders frames `first`..`last` (inclusive) of `spec` in the world `world_spec` at 360x45, as
// the full suite renders its routes, with their ground truth (a slice of a long route, cheaply).
RenderedSequence render_frames(const std::string& world_spec, const std::string& spec,
                               std::size_t first, std::size_t last) {
  const sim::World world = sim::load_world(world_spec, sim::WorldsConfig{});
  const sim::Trajectory trajectory = sim::make_trajectory(spec, world);
  EXPECT_GT(trajectory.poses.size(), last) << spec;
  sim::Trajectory slice;
  const std::size_t end = std::min(last + 1, trajectory.poses.size());
  slice.poses.assign(trajectory.poses.begin() + static_cast<std::ptrdiff_t>(std::min(first, end)),
                     trajectory.poses.begin() + static_cast<std::ptrdiff_t>(end));
  const sim::Renderer renderer(world, testing::render_params(360, 45));
  return render_trajectory(slice, renderer);
}

// Renders `spec` in the default room, with its ground truth.
RenderedSequence render_sequence(const std::string& spec, int width = 360, int height = 45) {
  const sim::Trajectory trajectory = sim::make_trajectory(spec, testing::room());
  return render_trajectory(trajectory, testing::room_renderer(width, height));
}

// Runs the compass on a rendered sequence, started at the true heading.
RenderedRun run_on(const RenderedSequence& sequence, const CompassParams& params) {
  RenderedRun run;
  VisualCompass compass(params, sequence.truth.front().heading_rad);
  for (const CompassFrame& frame : sequence.frames) run.estimates.push_back(compass.push(frame));
  run.truth = sequence.truth;
  run.references = compass.reference_count();
  run.evaluation = evaluation::evaluate_compass(run.estimates, run.truth, run.references);
  return run;
}

// Renders `spec` in the default room and runs the compass on it, started at the true heading.
RenderedRun run_rendered(const std::string& spec, const CompassParams& params, int width = 360,
                         int height = 45) {
  return run_on(render_sequence(spec, width, height), params);
}

CompassParams alg1(MinimiserKind kind = MinimiserKind::kLocalScan) {
  CompassParams params;
  params.matcher.minimiser.kind = kind;
  return params;
}

// The paper's Algorithm 1 exactly: without our rotation cap and global fallback.
CompassParams paper_alg1() {
  CompassParams params = alg1();
  params.sampling.max_reference_rotation_rad = 0.0;
  params.fast_turns.global_fallback = false;
  params.joint.enabled = false;
  return params;
}

CompassParams fixed_skip(int skip, MinimiserKind kind = MinimiserKind::kLocalScan) {
  CompassParams params = alg1(kind);
  params.sampling.policy = SamplingPolicy::kFixedSkip;
  params.sampling.fixed_skip_frames = skip;
  return params;
}

// Issue §4: ROTATERIGHT (on the spot, three turns clockwise, 1080°) ends within 2° of the
// truth at 360 columns. 3.77° per frame: never a whole number of columns.
TEST(VisualCompass, RotateRightOverThreeTurnsEndsWithinTwoDegrees) {
  const RenderedRun run =
      run_rendered("rotate:x=2.5,y=2.9,turns=3,rate_deg_s=-37.7,fps=10", alg1());
  ASSERT_GE(run.estimates.size(), 280u);
  EXPECT_LT(std::abs(run.evaluation.final_error_deg), 2.0);
  EXPECT_LT(run.evaluation.error_deg.max_abs, 2.0);
  // The unwrapped heading went round three times, as the truth did.
  double truth_turned = 0.0;
  for (std::size_t i = 1; i < run.truth.size(); ++i) {
    truth_turned += signed_difference(run.truth[i].heading_rad, run.truth[i - 1].heading_rad);
  }
  EXPECT_LT(rad_to_deg(truth_turned), -1070.0);
  EXPECT_NEAR(rad_to_deg(run.estimates.back().heading_rad - run.estimates.front().heading_rad),
              rad_to_deg(truth_turned), 2.0);
  EXPECT_LT(run.references, static_cast<int>(run.estimates.size()) / 2);
  EXPECT_FALSE(run.evaluation.slope_deg_per_m.has_value());  // on the spot: "n/a"
  EXPECT_TRUE(run.evaluation.slope_deg_per_s.has_value());
}

// Issue §4: CIRCLE keeps max |e| ≤ 3°. The circle of radius 0.9 m round (1.5, 2.6) has the
// box at (1.1..2.0, 2.25..2.65) inside it and the others outside, at 0.26 m or more: the
// roomiest such circle in the default room. Algorithm 1 (Table 2's parameters and our rotation
// cap, visual_compass.hpp) and the best fixed skip (Fx 1 at 5 frames per second: a reference
// every 8 cm) both keep the bound. The paper's Algorithm 1 alone (t = 0.6055, no cap) keeps
// references for up to 24 frames (61° of turn, 0.96 m) here: the bands then sit far off the
// direction of travel and parallax from furniture a few decimetres away biases each long hop
// the same way (docs/compass.md), so it is only held to a loose bound.
TEST(VisualCompass, CircleKeepsTheErrorWithinThreeDegrees) {
  const RenderedSequence circle =
      render_sequence("circle:cx=1.5,cy=2.6,radius_m=0.9,turns=1,speed_m_s=0.2,fps=5");
  const RenderedRun capped = run_on(circle, alg1());
  EXPECT_LE(capped.evaluation.error_deg.max_abs, 3.0);
  ASSERT_TRUE(capped.evaluation.slope_deg_per_m.has_value());
  EXPECT_LT(std::abs(*capped.evaluation.slope_deg_per_m), 1.0);
  const RenderedRun best_fixed = run_on(circle, fixed_skip(1));
  EXPECT_LE(best_fixed.evaluation.error_deg.max_abs, 3.0);
  ASSERT_TRUE(best_fixed.evaluation.slope_deg_per_m.has_value());
  EXPECT_LT(std::abs(*best_fixed.evaluation.slope_deg_per_m), 1.0);
  const RenderedRun threshold = run_on(circle, paper_alg1());
  EXPECT_LE(threshold.evaluation.error_deg.max_abs, 15.0);
  EXPECT_LT(threshold.references, best_fixed.references);
  for (const RenderedRun* run : {&capped, &threshold}) {
    for (const CompassEstimate& estimate : run->estimates) {
      EXPECT_TRUE(std::isfinite(estimate.heading_rad));
    }
  }
  // The cap replaced references where the threshold did not: each capped reference hop turned
  // by at most the cap and one more frame's turn (2.5° at 5 frames per second).
  EXPECT_GT(capped.references, threshold.references);
  for (std::size_t i = 1; i < capped.estimates.size(); ++i) {
    if (!capped.estimates[i].new_reference) continue;
    const int from = capped.estimates[i - 1].reference_index;
    const double hop_deg = rad_to_deg(signed_difference(
        capped.truth[i - 1].heading_rad, capped.truth[static_cast<std::size_t>(from)].heading_rad));
    EXPECT_LT(std::abs(hop_deg), 6.0 + 2.6) << "frame " << i;
  }
}

// The rotation cap needs parallax: a pure rotation on the spot (4.7° per frame, never a whole
// number of columns) keeps its references however far it turns, exactly as without the cap.
TEST(VisualCompass, RotationCapNeedsParallaxAndZeroTurnsItOff) {
  const RenderedSequence spin =
      render_sequence("rotate:x=2.5,y=2.9,turns=0.5,rate_deg_s=-23.5,fps=5");
  const RenderedRun capped = run_on(spin, alg1());
  const RenderedRun paper = run_on(spin, paper_alg1());
  EXPECT_EQ(capped.references, paper.references);
  EXPECT_LE(capped.references, 2);
  for (std::size_t i = 0; i < spin.frames.size(); ++i) {
    EXPECT_EQ(capped.estimates[i].heading_rad, paper.estimates[i].heading_rad) << i;
  }
  CompassParams negative = alg1();
  negative.sampling.max_reference_rotation_rad = -0.1;
  EXPECT_THROW(VisualCompass(negative, 0.0), UsageError);
}

// A heading measured otherwise (a recognised place of a map) re-aligns the frame it was
// measured on and every later one: the compass carries the offset on along the line (its own
// turns since are unchanged), unwrapped next to its heading, and its sigma restarts from the
// re-alignment's and grows from there. Half a turn of the CIRCLE, re-aligned at its middle on
// the true heading plus 10°.
TEST(VisualCompass, RealignMovesTheHeadingAndTheFramesAfterIt) {
  const RenderedSequence line =
      render_sequence("circle:cx=1.5,cy=2.6,radius_m=0.9,turns=0.5,speed_m_s=0.2,fps=5");
  const RenderedRun alone = run_on(line, alg1());
  VisualCompass compass(alg1(), line.truth.front().heading_rad);
  EXPECT_THROW(
      {
        CompassEstimate none;
        compass.realign(0.0, 0.0, none);
      },
      UsageError);
  const std::size_t at = line.frames.size() / 2;
  const double offset_rad = deg_to_rad(10.0);
  std::vector<CompassEstimate> estimates;
  for (std::size_t i = 0; i < line.frames.size(); ++i) {
    estimates.push_back(compass.push(line.frames[i]));
    if (i == at) {
      // The truth 10° off, given as a wrapped angle a whole turn away from the compass's.
      compass.realign(line.truth[i].heading_rad + offset_rad + 2.0 * kTwoPi, deg_to_rad(0.5),
                      estimates.back());
    }
  }
  for (std::size_t i = 0; i < at; ++i) {
    EXPECT_EQ(estimates[i].heading_rad, alone.estimates[i].heading_rad) << i;
    EXPECT_FALSE(estimates[i].realigned);
  }
  EXPECT_TRUE(estimates[at].realigned);
  EXPECT_NEAR(signed_difference(estimates[at].heading_rad, line.truth[at].heading_rad + offset_rad),
              0.0, 1e-9);
  // Unwrapped next to the compass's heading, not two turns away.
  EXPECT_LT(std::abs(estimates[at].heading_rad - alone.estimates[at].heading_rad),
            deg_to_rad(20.0));
  EXPECT_NEAR(estimates[at].heading_sigma_rad, deg_to_rad(0.5), 1e-12);
  // The turns since the re-alignment are the compass's own: every later heading moves by the
  // same jump as the re-aligned frame's.
  const double jump_rad = estimates[at].heading_rad - alone.estimates[at].heading_rad;
  for (std::size_t i = at + 1; i < line.frames.size(); ++i) {
    EXPECT_NEAR(estimates[i].heading_rad - alone.estimates[i].heading_rad, jump_rad, 1e-9) << i;
    EXPECT_FALSE(estimates[i].realigned);
    EXPECT_GE(estimates[i].heading_sigma_rad, deg_to_rad(0.5) - 1e-12) << i;
  }
}

// A pure rotation shows no parallax, whatever the world: the cap's floor, measured on the
// reference itself (d(I_r, I_r, 1 column)), keeps it off, so the compass keeps one or two
// references and adds no sub-pixel bias per hop. Half a turn at 1.268 columns a frame (the
// full suite's rate, never a whole column) in three families other than the built-in room; the
// floor fitted there (0.08·A(I_r, I_r)) took a reference every 5° in the field and the office
// and drifted 5-7° over three turns.
TEST(VisualCompass, PureRotationKeepsItsReferencesInEveryFamily) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"field", "rotate:x=11.25,y=10.05,turns=0.5,rate_deg_s=12.68,fps=10,z_m=0.1"},
      {"office", "rotate:x=7.5,y=7.05,turns=0.5,rate_deg_s=-12.68,fps=10,z_m=1"},
      {"house:rooms=2,room_min_m=2.5,room_max_m=3",
       "rotate:x=1.5,y=3.6,turns=0.5,rate_deg_s=12.68,fps=10,z_m=1"}};
  for (const auto& [world_spec, spec] : cases) {
    const sim::World world = sim::load_world(world_spec, sim::WorldsConfig{});
    const RenderedRun run = run_on(render_sequence(world, spec), alg1());
    ASSERT_GE(run.estimates.size(), 140u) << world_spec;
    EXPECT_LE(run.references, 3) << world_spec;
    EXPECT_LE(run.evaluation.error_deg.max_abs, 0.5) << world_spec;
  }
}

// Wanders that turn 15-30° between frames (10 frames/s; the first 2.4 m of the full suite's
// routes, whose sharp turns come at frames 95-117): the local scan alone, started at 0 by line 12,
// ends on the wrong side of 0 and loses the heading (measured: 176.5° in the field, 128.3° in
// the plain room); with the global fallback (FastTurns) the field's route stays within 5° of
// the truth (1.25°) and the plain room's within 8° (5.76°: its parallax, not the turns).
struct RouteCase {
  std::string world, spec;
  double bound_deg;
};

// The first 2.4 m of the full suite's wanders in the field and the plain room, with the bound the
// compass keeps on each.
std::vector<RouteCase> sharp_wanders() {
  return {
      {"field:seed=1",
       "wander:x=11.25,y=10.05,length_m=2.4,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1",
       5.0},
      {"room:size_x_m=10,size_y_m=8,boxes=16,walls=plain,seed=1",
       "wander:x=3.3,y=4.35,length_m=2.4,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1", 8.0}};
}

TEST(VisualCompass, GlobalFallbackFollowsSharpTurnsOfWanders) {
  for (const auto& [world_spec, spec, bound_deg] : sharp_wanders()) {
    const sim::World world = sim::load_world(world_spec, sim::WorldsConfig{});
    const RenderedSequence sequence = render_sequence(world, spec);
    ASSERT_GE(sequence.frames.size(), 120u) << world_spec;
    // The fallback alone: the joint rotation also catches these turns (max |e| 1.3° and 4.1°
    // without the fallback), and would hide what the fallback does.
    CompassParams fallback = alg1();
    fallback.joint.enabled = false;
    CompassParams local_only = fallback;
    local_only.fast_turns.global_fallback = false;
    const RenderedRun with_fallback = run_on(sequence, fallback);
    const RenderedRun without = run_on(sequence, local_only);
    EXPECT_LE(with_fallback.evaluation.error_deg.max_abs, bound_deg) << world_spec;
    EXPECT_GT(without.evaluation.error_deg.max_abs, 20.0) << world_spec;
  }
}

// Algorithm 1's max |e| over a rendered slice with the joint rotation (compass.yaml's default)
// and with the pure rotation alone.
struct MaxErrors {
  double with_joint_deg = 0.0;
  double pure_rotation_deg = 0.0;
};
MaxErrors max_errors_with_and_without_joint(const RenderedSequence& sequence) {
  const CompassParams joint = alg1();
  EXPECT_TRUE(joint.joint.enabled);
  CompassParams pure_rotation = joint;
  pure_rotation.joint.enabled = false;
  return {run_on(sequence, joint).evaluation.error_deg.max_abs,
          run_on(sequence, pure_rotation).evaluation.error_deg.max_abs};
}

// A turn of 105° in one frame next to a wall (frame 243 of the full suite's house-s1 wander,
// rendered: frames 236-252): the pair's global minimum is 103.7° with 𝒜_n 0.27, below t, and far
// from the last frame's turn, so the fallback's tests keep the local scan's -1.4° and the route
// stays 105° off to its end (132.9° max over the whole route; alg1-paper, lost elsewhere, 74.6°).
// The pair shows parallax: min-warping's joint rotation reads the turn, and the compass takes the
// pure rotation's minimum in its basin. Measured on the slice, max |e|: 1.9° with the joint
// rotation, 134.8° without it, 103.0° for alg1-paper.
TEST(VisualCompass, JointRotationFollowsATurnInOneFrame) {
  const RenderedSequence sequence = render_frames(
      "house:rooms=3,room_min_m=2.5,room_max_m=3.5,seed=1",
      "wander:x=2.1,y=2.4,length_m=5.1,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1", 236,
      252);
  // The truth turns by more than 90° between two successive frames of the slice.
  double sharpest_deg = 0.0;
  for (std::size_t i = 1; i < sequence.truth.size(); ++i) {
    sharpest_deg = std::max(
        sharpest_deg, std::abs(rad_to_deg(signed_difference(sequence.truth[i].heading_rad,
                                                            sequence.truth[i - 1].heading_rad))));
  }
  EXPECT_GT(sharpest_deg, 90.0);
  const MaxErrors errors = max_errors_with_and_without_joint(sequence);
  // The turn is followed with the joint rotation; without it, more than the turn is lost.
  EXPECT_LE(errors.with_joint_deg, 5.0);
  EXPECT_GT(errors.pure_rotation_deg, 90.0);
}

// A turn read in a parallax-shifted basin (frames 300-312 of the full suite's room-s1 wander,
// rendered, 2 cm apart at 10 frames/s): between frames 306 and 307 the robot turns by 19.4° while
// it travels, and the pure-rotation distance's lowest minimum is a +3.6° one, so Algorithm 1 alone
// ends the route 32° off. Min-warping reads -19.2° forwards and +19.1° backwards, and the turn
// alone has a minimum there: the joint rotation takes it. Measured on the slice, max |e|: 3.7°
// with the joint rotation, 23.0° without.
TEST(VisualCompass, JointRotationTakesTheBasinTheTranslationExplains) {
  const RenderedSequence sequence = render_frames(
      "room:seed=1",
      "wander:x=4.35,y=4.2,length_m=8,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1", 300,
      312);
  const MaxErrors errors = max_errors_with_and_without_joint(sequence);
  EXPECT_LE(errors.with_joint_deg, 5.0);
  EXPECT_GT(errors.pure_rotation_deg, 15.0);
}

// The same turn as one pair (frames 306 and 307): the pure rotation's lowest minimum is the
// parallax-shifted one; min-warping's rotation is within two search steps of the truth; the
// descent from it ends in the true basin.
TEST(VisualCompass, MinWarpingsBasinHoldsTheTurnThePureRotationMisses) {
  const RenderedSequence pair = render_frames(
      "room:seed=1",
      "wander:x=4.35,y=4.2,length_m=8,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1", 306,
      307);
  const double truth_rad = signed_difference(pair.truth[1].heading_rad, pair.truth[0].heading_rad);
  EXPECT_GT(std::abs(rad_to_deg(truth_rad)), 15.0);
  const CompassParams params = alg1();
  const PairMatcher matcher(params.matcher);
  const PairMatch pure = matcher.match(pair.frames[0], pair.frames[1]);
  EXPECT_GT(std::abs(rad_to_deg(signed_difference(pure.rotation_rad, truth_rad))), 15.0);
  const MinWarping warping(params.joint.warping, params.joint.geometry);
  const double joint_rad =
      warping.estimate(pair.frames[0].image(), pair.frames[1].image()).rotation_rad;
  EXPECT_LE(std::abs(rad_to_deg(signed_difference(joint_rad, truth_rad))), 8.0);
  const PairMatch basin = matcher.match_in_basin(
      pair.frames[0], pair.frames[1],
      static_cast<int>(std::lround(-shift_px_of_rotation(joint_rad, pair.frames[0].width()))));
  EXPECT_LE(std::abs(rad_to_deg(signed_difference(basin.rotation_rad, truth_rad))), 2.0);
}

// A view into a box (frame 1061 of the full suite's room-plain-s1 zig-zag at 30 cm, rendered:
// frames 1055-1066, the camera passing through one of the room's 16 boxes): the distance function
// is flat (featureless), so its global minimum, however deep against the local one, is noise. The
// truth does not turn over the slice; taking that minimum (the much deeper minimum's rule, before
// it excluded featureless pairs; the rule is gone) turned the heading by 89.4°. Measured on the
// slice, max |e|: 2.7° (the flat pair's local reading), 92.0° taking the global minimum.
TEST(VisualCompass, TheGlobalMinimumOfAFeaturelessPairIsNotTaken) {
  const RenderedSequence sequence = render_frames(
      "room:size_x_m=10,size_y_m=8,boxes=16,walls=plain,seed=1",
      "zigzag:x0=3.65,y0=2.95,x1=6.35,y1=5.05,rows=8,speed_m_s=0.2,fps=10,z_m=1", 1055, 1066);
  const RenderedRun run = run_on(sequence, alg1());
  // The slice holds the featureless pair the rule must leave alone.
  const bool has_featureless =
      std::any_of(run.estimates.begin(), run.estimates.end(),
                  [](const CompassEstimate& estimate) { return estimate.flags.featureless; });
  EXPECT_TRUE(has_featureless);
  EXPECT_LE(run.evaluation.error_deg.max_abs, 10.0);
}

// The quick suite's compass routes (config/suites/quick.yaml: 180x24 at 10 frames/s; rotation on
// the spot, the circle, the wander and the bumpy wander of each family), rendered, against the
// renderer's headings: the default is no worse than the paper's Algorithm 1 on any family, the
// family's score being its worst route (max |e|). Measured (default / alg1-paper, degrees): room
// 9.9 / 27.2, house 18.1 / 107.6, field 79.2 / 171.2, office 9.2 / 28.2, ofstad 13.3 / 177.0. Route
// by route it is no worse except the field's circle (27.9 against 26.6°: docs/compass.md "Known
// limits", the sub-pixel fit pulled towards whole columns).
TEST(VisualCompass, DefaultIsNoWorseThanThePapersAlgorithm1OnAnyQuickFamily) {
  struct Family {
    std::string name, world;
    double x_m, y_m, radius_m, z_m;  // the layout's free centre, the circle, the camera height
  };
  const std::string ofstad_obj = "worlds/ofstad/ofstad.obj";
  const std::vector<Family> families{
      {"room", "room", 4.35, 4.2, 0.65, 1.0},
      {"house", "house:rooms=2,room_min_m=2.5,room_max_m=3", 1.5, 3.6, 0.55, 1.0},
      {"field", "field", 11.25, 10.05, 1.0, 0.1},
      {"office", "office", 7.5, 7.05, 0.8, 1.0},
      {"ofstad", (omninav::testing::shared_data_dir() / ofstad_obj).string(), -0.06, -0.06, 1.0,
       1.0}};
  for (const Family& family : families) {
    if (family.name == "ofstad" &&
        !std::filesystem::exists(omninav::testing::shared_data_dir() / ofstad_obj)) {
      std::printf("skipping ofstad: %s not found\n", ofstad_obj.c_str());
      continue;
    }
    sim::WorldsConfig worlds;
    worlds.obj.scale_to_m = 20.0;  // the quick suite's obj_scale_to_m
    const sim::World world = sim::load_world(family.world, worlds);
    const sim::Renderer renderer(world, testing::render_params(180, 24));
    const std::string tail = fmt::format(",fps=10,z_m={}", family.z_m);
    const std::string wander =
        fmt::format("wander:x={},y={},length_m=4,speed_m_s=0.2,clearance_m=0.15,seed=1", family.x_m,
                    family.y_m) +
        tail;
    const std::vector<std::string> routes{
        fmt::format("rotate:x={},y={},turns=3,rate_deg_s=51.7", family.x_m, family.y_m) + tail,
        fmt::format("circle:cx={},cy={},radius_m={},speed_m_s=0.2", family.x_m, family.y_m,
                    family.radius_m) +
            tail,
        wander, wander + ",pitch_noise_deg=2,roll_noise_deg=2,noise_seed=1"};
    double ours_deg = 0.0, paper_deg = 0.0;
    std::string figures;
    const std::vector<std::string> names{"rotate", "circle", "wander", "bumpy"};
    for (std::size_t r = 0; r < routes.size(); ++r) {
      const std::string& route = routes[r];
      const RenderedSequence sequence =
          render_trajectory(sim::make_trajectory(route, world), renderer);
      const double ours = run_on(sequence, alg1()).evaluation.error_deg.max_abs;
      const double paper = run_on(sequence, paper_alg1()).evaluation.error_deg.max_abs;
      ours_deg = std::max(ours_deg, ours);
      paper_deg = std::max(paper_deg, paper);
      figures += fmt::format(" {}: {:.2f} / {:.2f};", names[r], ours, paper);
    }
    EXPECT_LE(ours_deg, paper_deg) << family.name << " (default / alg1-paper)" << figures;
  }
}

// The heading's standard deviation against ground truth: on the first 4 m of the full suite's
// wanders in three families (room, office, house), the share of frames whose error is within 1
// and 2 sigma (compass.yaml's scale, chosen on the zoo: docs/compass.md "Uncertainty"). And the
// chain: a frame's heading is its reference's plus a measured rotation, so its sigma is never
// below its reference's; the sigma varies from frame to frame and grows along the route.
// Measured: frames within 1 / 2 sigma, room 162 / 200, office 144 / 191, house 62 / 119 of 200
// (0.61 / 0.85 together; the house's route loses 24.5° at a sharp turn).
TEST(VisualCompass, HeadingSigmaCoversTheErrorAndAddsUpAlongTheChain) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"room:size_x_m=10,size_y_m=8,boxes=16,walls=plain,seed=1",
       "wander:x=3.3,y=4.35,length_m=4,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1"},
      {"office:seed=1",
       "wander:x=7.5,y=7.05,length_m=4,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1"},
      {"house:rooms=3,room_min_m=2.5,room_max_m=3.5,seed=1",
       "wander:x=2.1,y=2.4,length_m=4,speed_m_s=0.2,clearance_m=0.15,seed=1,fps=10,z_m=1"}};
  int frames = 0, within_1 = 0, within_2 = 0;
  for (const auto& [world_spec, spec] : cases) {
    const sim::World world = sim::load_world(world_spec, sim::WorldsConfig{});
    const RenderedRun run = run_on(render_sequence(world, spec), alg1());
    ASSERT_GE(run.estimates.size(), 190u) << world_spec;
    std::map<int, double> sigma_of_frame;
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    for (const CompassEstimate& estimate : run.estimates) {
      const double sigma = estimate.heading_sigma_rad;
      sigma_of_frame[estimate.frame_index] = sigma;
      ASSERT_TRUE(std::isfinite(sigma)) << world_spec << " frame " << estimate.frame_index;
      if (estimate.frame_index == 0) {
        EXPECT_EQ(sigma, 0.0);
        continue;
      }
      EXPECT_GE(sigma, sigma_of_frame.at(estimate.reference_index))
          << world_spec << " frame " << estimate.frame_index << ", reference "
          << estimate.reference_index;
      smallest = std::min(smallest, sigma);
      largest = std::max(largest, sigma);
    }
    EXPECT_GT(largest, 3.0 * smallest) << world_spec;
    EXPECT_GT(run.estimates.back().heading_sigma_rad, 2.0 * run.estimates[10].heading_sigma_rad)
        << world_spec;
    int route_1 = 0, route_2 = 0;
    for (std::size_t i = 1; i < run.estimates.size(); ++i) {
      const double error = std::abs(run.evaluation.errors_deg[i]);
      const double sigma_deg = rad_to_deg(run.estimates[i].heading_sigma_rad);
      route_1 += error <= sigma_deg ? 1 : 0;
      route_2 += error <= 2.0 * sigma_deg ? 1 : 0;
    }
    const int route_frames = static_cast<int>(run.estimates.size()) - 1;
    frames += route_frames;
    within_1 += route_1;
    within_2 += route_2;
  }
  const double share_1 = static_cast<double>(within_1) / frames;
  const double share_2 = static_cast<double>(within_2) / frames;
  EXPECT_GE(share_1, 0.5);
  EXPECT_LE(share_1, 0.85);
  EXPECT_GE(share_2, 0.85);
}

// Every minimiser gives the same run on a sequence of exact rolls (integer columns, so the
// answer is exact), and each frame's heading is right to rounding.
TEST(VisualCompass, RolledSequencesAreTrackedExactlyByEveryMinimiser) {
  const cv::Mat base = testing::render_room(2.2, 1.6, 0.0);
  std::vector<CompassFrame> frames;
  std::vector<int> rolls;
  int roll = 0;
  for (int i = 0; i < 40; ++i) {
    roll += (i % 7) - 2;  // −2..4 columns per frame, turning both ways
    rolls.push_back(roll);
    frames.emplace_back(roll_columns(base, roll), i);
  }
  for (const MinimiserKind kind :
       {MinimiserKind::kExhaustive, MinimiserKind::kLocalScan, MinimiserKind::kFft}) {
    for (const bool threshold : {true, false}) {
      CompassParams params = threshold ? alg1(kind) : fixed_skip(2, kind);
      params.matcher.distance.field_of_view.front_back = false;  // exact sub-pixel on rolls
      VisualCompass compass(params, 0.0);
      for (std::size_t i = 0; i < frames.size(); ++i) {
        const CompassEstimate estimate = compass.push(frames[i]);
        const double truth = rotation_of_shift_px(rolls[i] - rolls[0], 360);
        ASSERT_NEAR(estimate.heading_rad, truth, 1e-9)
            << to_string(kind) << " threshold " << threshold << " frame " << i;
      }
    }
  }
}

// "Fx n": a new reference every n + 1 frames; Fx 0 compares successive frames (the 2004
// compass); each reference is measured against the one before.
TEST(VisualCompass, FixedSkipUsesEveryNPlusOneThFrameAsReference) {
  const cv::Mat base = random_image(90, 8, 3, 3);
  for (const int skip : {0, 1, 3, 11}) {
    VisualCompass compass(fixed_skip(skip), 0.0);
    std::vector<int> references;
    for (int i = 0; i < 30; ++i) {
      const CompassEstimate estimate = compass.push(CompassFrame(roll_columns(base, i), i));
      references.push_back(estimate.reference_index);
      EXPECT_EQ(estimate.reference_index, i == 0 ? 0 : ((i - 1) / (skip + 1)) * (skip + 1))
          << "skip " << skip << " frame " << i;
    }
    // Frames that served as a reference: 0, n+1, 2(n+1), ... up to the last but one frame.
    EXPECT_EQ(compass.reference_count(), 28 / (skip + 1) + 1) << skip;
  }
  EXPECT_EQ(describe(fixed_skip(3).sampling), "Fx 3");
  EXPECT_EQ(describe(alg1().sampling), "Atm 0.6055 cap 4°");
  EXPECT_EQ(describe(paper_alg1().sampling), "Atm 0.6055");
}

// Algorithm 1 switches the reference when the normalised amplitude drops below t, to the
// previous frame, and the firewall moves the reference orientation only then.
TEST(VisualCompass, SwitchesTheReferenceWhenTheAmplitudeFallsBelowTheThreshold) {
  const RenderedRun run =
      run_rendered("line:x0=0.6,y0=1.6,x1=2.6,y1=1.6,speed_m_s=0.2,fps=5", alg1());
  int switches = 0;
  for (std::size_t i = 1; i < run.estimates.size(); ++i) {
    const CompassEstimate& estimate = run.estimates[i];
    if (estimate.new_reference) {
      ++switches;
      EXPECT_EQ(estimate.reference_index, static_cast<int>(i) - 1);
    } else {
      EXPECT_GE(estimate.amplitude_norm, 0.6055) << "frame " << i;
      EXPECT_EQ(estimate.reference_index, run.estimates[i - 1].reference_index);
    }
  }
  EXPECT_GT(switches, 0);
  EXPECT_EQ(run.references, switches + 1);
  EXPECT_LT(run.evaluation.error_deg.max_abs, 5.0);
}

// Degenerate input: featureless frames give a heading that stays put, flagged, never NaN;
// frames of another size are refused with the frame's name.
TEST(VisualCompass, DegenerateInputNeverGivesNaN) {
  for (const MinimiserKind kind : {MinimiserKind::kExhaustive, MinimiserKind::kLocalScan,
                                   MinimiserKind::kFft, MinimiserKind::kPhase}) {
    VisualCompass compass(alg1(kind), 0.3);
    for (int i = 0; i < 6; ++i) {
      const cv::Mat uniform(20, 360, CV_8UC3, cv::Scalar(10 * i, 50, 50));
      const CompassEstimate estimate = compass.push(CompassFrame(uniform, i));
      EXPECT_TRUE(std::isfinite(estimate.heading_rad));
      EXPECT_TRUE(std::isfinite(estimate.amplitude_norm));
      EXPECT_NEAR(estimate.heading_rad, 0.3, 1e-12);
      if (i > 0) {
        EXPECT_TRUE(estimate.flags.featureless) << to_string(kind);
      }
    }
  }
  VisualCompass compass(alg1(), 0.0);
  compass.push(CompassFrame(random_image(360, 20, 3, 1), 0, "first.png"));
  try {
    compass.push(CompassFrame(random_image(360, 21, 3, 2), 1, "taller.png"));
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("taller.png"), std::string::npos) << error.what();
  }
  EXPECT_THROW(compass.push(CompassFrame(random_image(360, 20, 1, 2), 2, "grey.png")), InputError);
}

// Real images (a camera carried along a route, wavy horizon): the heading moves smoothly, and
// over spans short enough for a direct match to be reliable, the rotation measured directly
// agrees with the one Algorithm 1 integrated.
TEST(VisualCompass, RealRouteIsSmoothAndConsistent) {
  OMNINAV_REQUIRE_SHARED_DATA("real/ftl-arena/route");
  VisualCompass compass(alg1(), 0.0);
  std::vector<CompassEstimate> estimates;
  std::vector<CompassFrame> frames;
  for (int i = 0; i < 130; ++i) {
    frames.emplace_back(testing::ftl_route_image(i), i);
    estimates.push_back(compass.push(frames.back()));
    EXPECT_TRUE(std::isfinite(estimates.back().heading_rad));
    if (i > 0) {
      EXPECT_LT(std::abs(rad_to_deg(estimates.back().rotation_rad)), 10.0) << i;
    }
  }
  int compared = 0;
  for (int i = 0; i + 8 < 130; i += 10) {
    const PairMatch direct = compass.matcher().match(frames[static_cast<std::size_t>(i)],
                                                     frames[static_cast<std::size_t>(i + 8)], 0);
    if (direct.amplitude_norm < 0.5) continue;  // too different to match directly
    const double integrated =
        signed_difference(estimates[static_cast<std::size_t>(i + 8)].heading_rad,
                          estimates[static_cast<std::size_t>(i)].heading_rad);
    EXPECT_NEAR(rad_to_deg(integrated), rad_to_deg(direct.rotation_rad), 3.0) << "frames " << i;
    ++compared;
  }
  EXPECT_GE(compared, 5);
}

}  // namespace
}  // namespace omninav::compass
