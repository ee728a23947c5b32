// scripts/plot_run on bags that simulate wrote: the plots looked at as pictures (by
// test/check_plots: sizes, no blank page, titles, units, integer counts, a colour and an
// id for each ball), and the energies it prints, potential measured above each ball's
// lowest resting level on the scene's floor.

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"
#include "cli_helpers.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

using namespace ball_collision_sim::test::cli;

namespace
{
const std::string kConfigDir = BCS_CONFIG_DIR;
const std::string kPlotRun = kConfigDir + "/../scripts/plot_run";
const std::string kCheckPlots = kConfigDir + "/../test/check_plots";
constexpr double kG = 9.81;

class PlotRun : public SimulateCli
{
protected:
  /// plot_run on a bag (plots into `plots`) with more arguments.
  RunResult plot(const std::string& bag, const std::vector<std::string>& more = {})
  {
    std::vector<std::string> args{kPlotRun, bag, "--out", path("plots")};
    args.insert(args.end(), more.begin(), more.end());
    return runProgram("/usr/bin/python3", args);
  }

  /// The line plot_run prints on a bag it draws.
  std::string plotLine(const std::string& bag, const std::vector<std::string>& more = {})
  {
    const RunResult result = plot(bag, more);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    const std::vector<std::string> out = lines(result.out);
    return out.empty() ? "" : out.back();
  }

  /// test/check_plots passes the plots of a run of `balls` balls.
  void expectReadablePlots(int balls)
  {
    const RunResult result =
        runProgram("/usr/bin/python3", {kCheckPlots, path("plots"), "--balls", std::to_string(balls)});
    EXPECT_EQ(result.exit_code, 0) << result.out << result.err;
  }

  /// The summary line of simulate on a scene, with its bag at `bag`.
  Summary simulate(const std::string& scene, const std::string& duration, const std::string& bag)
  {
    const RunResult result = run({scene, "--duration", duration, "--bag", bag});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    const std::vector<std::string> out = lines(result.out);
    return out.empty() ? Summary{} : parseSummary(out.back());
  }

  std::string writeScene(const std::string& name, const std::string& text)
  {
    std::ofstream(path(name)) << text;
    return path(name);
  }
};

// The bowl of config/bowl.yaml: z = 0.25 (x^2 + y^2) on [-1, 1]^2, its bottom at the origin.
const char* const kBowl =
    "floor:\n  type: biquadratic\n  control_points:\n"
    "    - [[-1.0, -1.0, 0.5], [-1.0, 0.0, 0.0], [-1.0, 1.0, 0.5]]\n"
    "    - [[ 0.0, -1.0, 0.0], [ 0.0, 0.0, -0.5], [ 0.0, 1.0, 0.0]]\n"
    "    - [[ 1.0, -1.0, 0.5], [ 1.0, 0.0, 0.0], [ 1.0, 1.0, 0.5]]\n";
}  // namespace

// 200 balls of different sizes on a level floor at z = 0: every plot is drawn and readable,
// and the energy plot_run computes from the ball states is the summary's less the balls'
// potential energy at rest on the floor, sum m g r.
TEST_F(PlotRun, AGasAgreesWithTheSummaryAboveItsRestingLevel)
{
  const Summary summary = simulate(kConfigDir + "/random_gas.yaml", "2", path("gas.bag"));
  const std::string out = plotLine(path("gas.bag"));
  for (const char* name : {"energy.png", "momentum.png", "collisions.png", "trajectories.png", "speeds.png"})
    EXPECT_TRUE(fs::exists(path("plots") + "/" + name)) << name;
  EXPECT_FALSE(fs::exists(path("plots") + "/heights.png")) << "no ball flies in random_gas";
  EXPECT_EQ(field(out, "samples"), static_cast<double>(summary.steps + 1));  // a state per step and the start

  double resting = 0;
  rosbag::Bag bag(path("gas.bag"));
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ball_sim/ball_states")))
  {
    // (the message held while its balls are read: a range-for keeps no temporary alive)
    const auto first = m.instantiate<ball_collision_sim::BallStateArray>();
    for (const auto& b : first->balls)
      resting += b.mass * kG * b.radius;
    break;
  }
  bag.close();
  ASSERT_GT(resting, 1.0);
  EXPECT_NEAR(field(out, "rest_level_start"), resting, 1e-12 * resting) << out;
  EXPECT_NEAR(field(out, "rest_level_end"), resting, 1e-12 * resting) << out;
  EXPECT_NEAR(field(out, "energy_start"), summary.energy_start - resting, 1e-12 * summary.energy_start) << out;
  EXPECT_NEAR(field(out, "energy_end"), summary.energy_end - resting, 1e-12 * summary.energy_end) << out;
  expectReadablePlots(200);
}

// The billiards break on a level table, 12 s until every ball rests: the potential energy
// is 0 throughout, the energy starts as the cue ball's 1/2 m v^2 and ends at 0 (a ball in
// a pocket takes its energy with it); the 16 balls are drawn in 16 colours with their
// ids, the motion states counted in whole balls.
TEST_F(PlotRun, ABilliardsBreakEndsWithNoEnergyLeft)
{
  const std::string scene_path = kConfigDir + "/billiards.yaml";
  const Summary summary = simulate(scene_path, "12", path("break.bag"));
  const std::string out = plotLine(path("break.bag"));
  const ball_collision_sim::core::Scene scene = ball_collision_sim::yaml::loadValidScene(scene_path);
  ASSERT_EQ(scene.balls.size(), 16u);
  double resting = 0;
  for (const ball_collision_sim::core::BallDef& b : scene.balls)
    resting += b.mass * kG * b.radius;
  const double cue = 0.5 * scene.balls[0].mass * scene.balls[0].velocity.squaredNorm();
  EXPECT_NEAR(field(out, "energy_start"), cue, 1e-12 * cue) << out;
  EXPECT_NEAR(field(out, "energy_start") + field(out, "rest_level_start"), summary.energy_start,
              1e-12 * summary.energy_start)
      << out;
  EXPECT_NEAR(field(out, "rest_level_start"), resting, 1e-12 * resting) << out;
  EXPECT_NEAR(field(out, "energy_end"), 0.0, 1e-12 * cue) << "every ball rests on the table: " << out;
  EXPECT_TRUE(fs::exists(path("plots") + "/states.png"));
  expectReadablePlots(16);
}

// A ball dropped from 0.5 m above its resting height: its potential energy is m g 0.5 at
// the start, where the summary's (from z = 0) is m g 0.6; its height is plotted.
TEST_F(PlotRun, ADroppedBallsHeightAboveTheFloor)
{
  const std::string scene = writeScene(
      "drop.yaml", "floor: {type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: 0.5}\n"
                   "balls:\n  - {position: [0, 0, 0.6], radius: 0.1, placement: as_given}\n");
  const Summary summary = simulate(scene, "1", path("drop.bag"));
  const std::string out = plotLine(path("drop.bag"));
  EXPECT_NEAR(field(out, "energy_start"), summary.energy_start * 5 / 6, 1e-12 * summary.energy_start) << out;
  EXPECT_NEAR(field(out, "rest_level_start"), summary.energy_start / 6, 1e-12 * summary.energy_start) << out;
  EXPECT_TRUE(fs::exists(path("plots") + "/heights.png"));
  expectReadablePlots(1);
}

// On the curved floor of a bowl, a ball at rest at the bottom has no potential energy: its
// resting level is the bottom's height plus its radius along the normal there. A scene file
// given with --scene wins over the bag's: a level floor 0.2 m below the bottom puts the same
// ball m g 0.2 above its resting level. A bad scene file is named with its key, and nothing
// is drawn.
TEST_F(PlotRun, ABallAtRestAtTheBottomOfABowlHasNoPotentialEnergy)
{
  const std::string scene = writeScene(
      "bowl.yaml", std::string(kBowl) + "balls:\n  - {position: [0, 0, 0.05], radius: 0.05, mass: 2.0}\n");
  simulate(scene, "0.1", path("bowl.bag"));
  const std::string out = plotLine(path("bowl.bag"));
  EXPECT_NEAR(field(out, "energy_start"), 0.0, 1e-12) << out;
  EXPECT_NEAR(field(out, "energy_end"), 0.0, 1e-12) << out;
  EXPECT_NEAR(field(out, "rest_level_start"), 2.0 * kG * 0.05, 1e-12) << out;
  expectReadablePlots(1);

  const std::string level = writeScene("level.yaml", "floor: {point: [-1, -1, -0.2], u: [2, 0, 0], v: [0, 2, 0]}\n");
  const std::string given = plotLine(path("bowl.bag"), {"--scene", level});
  EXPECT_NEAR(field(given, "energy_start"), 2.0 * kG * 0.2, 1e-12) << given;
  EXPECT_NEAR(field(given, "rest_level_start"), 2.0 * kG * (-0.2 + 0.05), 1e-12) << given;

  fs::remove_all(path("plots"));
  const std::string cone = writeScene("cone.yaml", "floor: {type: cone}\n");
  const RunResult bad = plot(path("bowl.bag"), {"--scene", cone});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "plot_run: error: " + cone + ": floor.type: must be plane or biquadratic (got 'cone')\n");
  EXPECT_FALSE(fs::exists(path("plots")));
  const RunResult missing = plot(path("bowl.bag"), {"--scene", path("no_such.yaml")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.err, "--scene: cannot read " + path("no_such.yaml"))) << missing.err;
  EXPECT_FALSE(fs::exists(path("plots")));
}
