// The `simulate` tool through its real command line: exit codes, the one-line errors,
// the summary line and the CSV (design.md section 6).

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"
#include "cli_helpers.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <ball_collision_sim/MotionTransition.h>
#include <ball_collision_sim/PocketedBall.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <fcntl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace ball_collision_sim::test::cli;

namespace
{
const std::string kDataDir = BCS_TEST_DATA_DIR;
const std::string kGoodScene = kDataDir + "/good_small.yaml";

/// A bad scene: exit 2, nothing on stdout, one stderr line naming the file and the key.
void expectSceneError(const RunResult& result, const std::string& scene_path, const std::string& key)
{
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.out, "");
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.back(), '\n');
  EXPECT_EQ(lines(result.err).size(), 1u) << result.err;
  EXPECT_TRUE(startsWith(result.err, "simulate: error: " + scene_path)) << result.err;
  EXPECT_TRUE(contains(result.err, key)) << "no '" << key << "' in: " << result.err;
}

TEST_F(SimulateCli, BadScenesExitTwoWithOneLineNamingTheKey)
{
  // The reasons are the core's and the reader's words; the key is the contract.
  const std::vector<std::pair<std::string, std::string>> cases{
    {"bad_negative_radius.yaml", ": balls[0].radius"},
    {"bad_nan.yaml", ": balls[0].position"},
    {"bad_parallel_wall.yaml", ": walls[0]."},
    {"bad_overlap.yaml", ": balls[1]"},
    {"bad_off_floor.yaml", ": balls[0].position"},
    {"bad_unknown_key.yaml", ": balls[0].radus: unknown key"},
    {"bad_wrong_type.yaml", ": walls[0].u: expected a list of 3 numbers"},
    {"bad_malformed.yaml", "bad_malformed.yaml:4:"},
    {"empty.yaml", ": the scene must be a YAML map"},
    {"bad_top_level_list.yaml", ": the scene must be a YAML map"},
    {"no_such_file.yaml", ": cannot open file (No such file or directory)"},
  };
  for (const auto& [file, key] : cases)
  {
    SCOPED_TRACE(file);
    const std::string scene = kDataDir + "/" + file;
    expectSceneError(run({scene, "--duration", "1", "--csv", path("out.csv")}), scene, key);
    EXPECT_FALSE(fs::exists(path("out.csv"))) << "a bad scene must not leave a CSV behind";
  }
}

struct CommandLineCase
{
  std::vector<std::string> args;
  std::string mentions;  // a word the error must contain
};

TEST_F(SimulateCli, BadCommandLinesExitTwoWithAUsageHint)
{
  const std::vector<CommandLineCase> cases{
    {{}, "scene"},
    {{kGoodScene}, "--duration"},
    {{"--duration", "1"}, "scene"},
    {{kGoodScene, "--duration", "1", "--frobnicate"}, "--frobnicate"},
    {{kGoodScene, "--duration", "1", "-x"}, "-x"},
    {{kGoodScene, "--duration", "-1"}, "--duration"},
    {{kGoodScene, "--duration", "abc"}, "--duration"},
    {{kGoodScene, "--duration", "nan"}, "--duration"},
    {{kGoodScene, "--duration", "inf"}, "--duration"},
    {{kGoodScene, "--duration", "1e300"}, "--duration"},  // (more steps than a run may take)
    {{kGoodScene, "--duration"}, "--duration"},
    {{kGoodScene, "--duration", "--csv", "x.csv"}, "--duration"},
    {{kGoodScene, "--duration", "1", "--duration", "2"}, "--duration"},
    {{kGoodScene, "--duration", "1", "--sample-every", "0"}, "--sample-every"},
    {{kGoodScene, "--duration", "1", "--sample-every", "-3"}, "--sample-every"},
    {{kGoodScene, "--duration", "1", "--sample-every", "2.5"}, "--sample-every"},
    {{kGoodScene, "--duration", "1", "--threads", "-1"}, "--threads"},
    {{kGoodScene, "--duration", "1", "--threads", "1.5"}, "--threads"},
    {{kGoodScene, "--duration", "1", "--threads", "1025"}, "--threads"},
    {{kGoodScene, "--duration", "1", "--threads", "2", "--threads", "2"}, "--threads"},
    {{kGoodScene, "--duration", "1", "--csv"}, "--csv"},
    {{kGoodScene, kGoodScene, "--duration", "1"}, "unexpected argument"},
  };
  for (const CommandLineCase& c : cases)
  {
    std::string shown;
    for (const std::string& arg : c.args)
    {
      shown += " " + arg;
    }
    SCOPED_TRACE("simulate" + shown);
    const RunResult result = run(c.args);
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.out, "");
    const std::vector<std::string> err = lines(result.err);
    ASSERT_GE(err.size(), 1u);
    EXPECT_TRUE(startsWith(err[0], "simulate: error: ")) << result.err;
    EXPECT_TRUE(contains(err[0], c.mentions)) << result.err;
    EXPECT_TRUE(contains(result.err, "--help")) << "no usage hint: " << result.err;
  }
}

TEST_F(SimulateCli, BagHoldsTheNodesTopicsStampedWithSimulatedTime)
{
  const RunResult result = run({kGoodScene, "--duration", "0.5", "--bag", path("x.bag"), "--marker-rate", "10"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(path("x.bag.active")));
  rosbag::Bag bag(path("x.bag"), rosbag::bagmode::Read);
  std::map<std::string, int> counts;
  double last_clock = -1, last_states = -1;
  int marker_sets = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag))
  {
    ++counts[m.getTopic()];
    if (const auto clock = m.instantiate<rosgraph_msgs::Clock>())
    {
      EXPECT_GE(clock->clock.toSec(), last_clock);
      last_clock = clock->clock.toSec();
    }
    if (const auto states = m.instantiate<ball_collision_sim::BallStateArray>())
    {
      EXPECT_NEAR(states->header.stamp.toSec(), last_states < 0 ? 0.0 : last_states + 0.01, 1e-9);
      last_states = states->header.stamp.toSec();
      EXPECT_EQ(states->header.frame_id, "world");
    }
    if (const auto markers = m.instantiate<visualization_msgs::MarkerArray>())
      if (!markers->markers.empty() && markers->markers[0].ns == "balls")
        ++marker_sets;
  }
  // a state per step and the start; markers at 10 Hz of simulated time and at the start
  EXPECT_EQ(counts["/ball_sim/ball_states"], 51);
  EXPECT_EQ(counts["/clock"], 51);
  EXPECT_EQ(marker_sets, 6);
  EXPECT_EQ(counts["/ball_sim/scene"], 1);
  EXPECT_GT(counts["/tf"], 0);
  EXPECT_NEAR(last_clock, 0.5, 1e-9);
}


// On a terminal a progress bar goes to stderr; into a file or pipe, nothing of it.
TEST_F(SimulateCli, ProgressBarOnlyOnATerminal)
{
  const RunResult plain = run({std::string(BCS_CONFIG_DIR) + "/random_gas.yaml", "--duration", "2"});
  ASSERT_EQ(plain.exit_code, 0);
  EXPECT_EQ(plain.err, "");
  // `script` gives the tool a terminal
  const std::string command = "script -qec " +
                              shellQuote(std::string(BCS_SIMULATE_EXE) + " " + BCS_CONFIG_DIR +
                                         "/random_gas.yaml --duration 2") +
                              " /dev/null > " + shellQuote(path("tty.txt")) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string shown = readFile(path("tty.txt"));
  EXPECT_TRUE(contains(shown, "ETA")) << shown;
  EXPECT_TRUE(contains(shown, "real time")) << shown;
  EXPECT_TRUE(contains(shown, "100%")) << shown;
  EXPECT_TRUE(contains(shown, "summary: steps=400")) << shown;
}

TEST_F(SimulateCli, UnwritableBagIsABadCommandLine)
{
  const RunResult result = run({kGoodScene, "--duration", "1", "--bag", path("no/such/dir/x.bag")});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(startsWith(result.err, "simulate: error: --bag: " + path("no/such/dir/x.bag"))) << result.err;
}

// The bag keeps the node's rates and switches: tf at tf_rate of simulated time (none at
// 0), a collision message per handled collision unless publish_collisions is false.
TEST_F(SimulateCli, BagFollowsTheScenesTfRateAndCollisionSwitch)
{
  const auto bagCounts = [&](const std::string& extra, std::string* summary) {
    const std::string scene = path("scene.yaml");
    {
      std::ofstream out(scene);
      out << readFile(kGoodScene) << extra;
    }
    const RunResult result = run({scene, "--duration", "0.5", "--bag", path("x.bag")});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    *summary = result.out;
    std::map<std::string, int> counts;
    rosbag::Bag bag(path("x.bag"), rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag))
      ++counts[m.getTopic()];
    return counts;
  };
  std::string summary;
  auto counts = bagCounts("tf_rate: 20\npublish_collisions: true\n", &summary);
  EXPECT_EQ(counts["/tf"], 11);  // steps 0, 5, ..., 50
  const int events = static_cast<int>(field(lines(summary).back(), "events"));
  EXPECT_GT(events, 0);
  EXPECT_EQ(counts["/ball_sim/collisions"], events);
  counts = bagCounts("tf_rate: 0\npublish_collisions: false\n", &summary);
  EXPECT_EQ(counts["/tf"], 0);
  EXPECT_EQ(counts["/ball_sim/collisions"], 0);
  EXPECT_EQ(counts["/ball_sim/ball_states"], 51);
}

// The bag's tf frames are the node's: <frame_prefix>ball_<id>, with the scene's prefix
// where it sets one, none by default (the node's in the root namespace).
TEST_F(SimulateCli, BagTfFramesTakeTheScenesFramePrefix)
{
  const auto childFrames = [&](const std::string& extra) {
    const std::string scene = path("scene.yaml");
    {
      std::ofstream out(scene);
      out << readFile(kGoodScene) << extra;
    }
    const RunResult result = run({scene, "--duration", "0.1", "--bag", path("x.bag")});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    std::set<std::string> frames;
    rosbag::Bag bag(path("x.bag"), rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/tf")))
    {
      const tf2_msgs::TFMessage::ConstPtr tf = m.instantiate<tf2_msgs::TFMessage>();
      for (const auto& t : tf->transforms)
        frames.insert(t.child_frame_id);
    }
    return frames;
  };
  const std::set<std::string> plain = childFrames("");
  ASSERT_FALSE(plain.empty());
  EXPECT_EQ(plain.count("ball_1"), 1u);
  const std::set<std::string> prefixed = childFrames("frame_prefix: \"sim2/\"\n");
  EXPECT_EQ(prefixed.size(), plain.size());
  for (const std::string& frame : plain)
    EXPECT_EQ(prefixed.count("sim2/" + frame), 1u) << frame;
}

// Ctrl-C during a long run: exit 130, and a valid bag of the run so far under the final
// name, nothing left under the temporary one.
TEST_F(SimulateCli, InterruptClosesAValidBag)
{
  const std::string bag_path = path("long.bag");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0)
  {
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, 1);
    dup2(devnull, 2);
    execl(BCS_SIMULATE_EXE, BCS_SIMULATE_EXE, kGoodScene.c_str(), "--duration", "1e6", "--bag", bag_path.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // wait until the run is under way
  for (int k = 0; k < 200 && !fs::exists(bag_path + ".active"); ++k)
    usleep(10000);
  usleep(500000);
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_FALSE(fs::exists(bag_path + ".active"));
  ASSERT_TRUE(fs::exists(bag_path));
  rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
  rosbag::View states(bag, rosbag::TopicQuery("/ball_sim/ball_states"));
  EXPECT_GT(states.size(), 10u);
  EXPECT_LT(states.getEndTime().toSec(), 1e6);
}

TEST_F(SimulateCli, HelpGoesToStdoutAndExitsZero)
{
  for (const char* flag : {"--help", "-h"})
  {
    SCOPED_TRACE(flag);
    const RunResult result = run({flag});
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_TRUE(startsWith(result.out, "usage: simulate SCENE.yaml --duration SECONDS")) << result.out;
    EXPECT_EQ(result.err, "");
  }
  // --help wins over anything else on the line.
  EXPECT_EQ(run({"--frobnicate", "--help"}).exit_code, 0);
}

TEST_F(SimulateCli, UnwritableCsvIsAnErrorNamingThePath)
{
  const std::string csv = path("no_such_folder/out.csv");
  const RunResult result = run({kGoodScene, "--duration", "0.1", "--csv", csv});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(lines(result.err).size(), 1u) << result.err;
  EXPECT_TRUE(startsWith(result.err, "simulate: error: --csv: " + csv + ": cannot open")) << result.err;
}


struct CsvRow
{
  double t;
  int id;
  double x, y, z, vx, vy, vz;
};

std::vector<CsvRow> parseCsv(const std::string& text, std::string* header)
{
  std::vector<std::string> all = lines(text);
  std::vector<CsvRow> rows;
  if (all.empty())
  {
    return rows;
  }
  *header = all[0];
  for (std::size_t i = 1; i < all.size(); ++i)
  {
    CsvRow row{};
    char tail = 0;
    const int fields = std::sscanf(all[i].c_str(), "%lf,%d,%lf,%lf,%lf,%lf,%lf,%lf%c", &row.t, &row.id, &row.x, &row.y,
                                   &row.z, &row.vx, &row.vy, &row.vz, &tail);
    EXPECT_EQ(fields, 8) << "row " << i << ": " << all[i];
    rows.push_back(row);
  }
  return rows;
}

/// 1/2 m |v|^2 - m <g, p> over a block of rows, with the masses of the scene by ball id.
double energyOf(const std::vector<CsvRow>& rows, std::size_t first, std::size_t count,
                const ball_collision_sim::core::Scene& scene)
{
  const std::vector<ball_collision_sim::core::BallDef> balls = ball_collision_sim::core::allBalls(scene);
  double energy = 0.0;
  for (std::size_t i = first; i < first + count; ++i)
  {
    const CsvRow& row = rows[i];
    // ball k of the scene's list has id k + 1
    EXPECT_GE(row.id, 1);
    EXPECT_LE(static_cast<std::size_t>(row.id), balls.size());
    const double m = balls.at(static_cast<std::size_t>(row.id) - 1).mass;
    const ball_collision_sim::core::Vec3 p(row.x, row.y, row.z);
    const ball_collision_sim::core::Vec3 v(row.vx, row.vy, row.vz);
    energy += 0.5 * m * v.squaredNorm() - m * scene.gravity.dot(p);
  }
  return energy;
}

TEST_F(SimulateCli, GoodSceneWritesTheSummaryAndTheCsv)
{
  const std::string csv = path("out.csv");
  const RunResult result = run({kGoodScene, "--duration", "0.5", "--csv", csv, "--sample-every", "5"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const std::vector<std::string> out = lines(result.out);
  ASSERT_EQ(out.size(), 1u) << "stdout must hold only the summary:\n" << result.out;
  const Summary summary = parseSummary(out.back());

  const ball_collision_sim::core::Scene scene = ball_collision_sim::yaml::loadValidScene(kGoodScene);
  EXPECT_EQ(summary.steps, 50u);  // 0.5 s / 0.01 s
  EXPECT_EQ(summary.floor_impacts, 0u);  // every ball on the floor from the start
  EXPECT_GE(summary.wall_s, 0.0);
  EXPECT_EQ(summary.balls_lost, 0);

  std::string header;
  const std::vector<CsvRow> rows = parseCsv(readFile(csv), &header);
  EXPECT_EQ(header, "t,id,x,y,z,vx,vy,vz");
  const std::size_t balls = scene.balls.size();
  const std::size_t samples = 50 / 5;
  ASSERT_EQ(rows.size(), balls * (samples + 1));
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const std::size_t sample = i / balls;
    EXPECT_NEAR(rows[i].t, static_cast<double>(sample * 5) * scene.dt, 1e-12) << "row " << i;
  }

  // The summary's energies are those of the first and the last sample, to round-off.
  const double start = energyOf(rows, 0, balls, scene);
  EXPECT_NEAR(summary.energy_start, start, 1e-12 * std::abs(start)) << "csv gives " << start;
  const double end = energyOf(rows, rows.size() - balls, balls, scene);
  EXPECT_NEAR(summary.energy_end, end, 1e-12 * std::abs(end)) << "csv gives " << end;
  // Restitution 1 on a flat floor keeps the energy.
  EXPECT_NEAR(summary.energy_end, summary.energy_start, 1e-9 * std::abs(summary.energy_start));
}

// --threads: the step on 2 and 3 threads writes the CSV and summary's events of 1, byte
// for byte (4,000 balls: past StepSettings::parallel_min_balls, so the loops are split),
// and 0 takes every core.
TEST_F(SimulateCli, ThreadsWriteTheSameCsv)
{
  const std::string scene = path("many.yaml");
  {
    std::ofstream out(scene);
    out << "restitution: 0.9\nfloor: {type: plane, point: [-4, -4, 0], u: [8, 0, 0], v: [0, 8, 0]}\n"
           "walls:\n  - {point: [-4, -4, 0], u: [8, 0, 0], v: [0, 0, 0.3]}\n"
           "  - {point: [-4, 4, 0], u: [8, 0, 0], v: [0, 0, 0.3]}\n"
           "  - {point: [-4, -4, 0], u: [0, 8, 0], v: [0, 0, 0.3]}\n"
           "  - {point: [4, -4, 0], u: [0, 8, 0], v: [0, 0, 0.3]}\n"
           "random_balls: {count: 4000, seed: 3, radius: [0.03, 0.05], speed: [0, 3]}\n";
  }
  std::string first_csv, first_events;
  for (const char* threads : {"1", "2", "3", "0"})
  {
    const std::string csv = path(std::string("threads") + threads + ".csv");
    const RunResult result = run({scene, "--duration", "0.2", "--csv", csv, "--sample-every", "4", "--threads", threads});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::string summary = lines(result.out).back();
    const std::string events = summary.substr(summary.find("events="), summary.find(" wall_s") - summary.find("events="));
    if (first_csv.empty())
    {
      first_csv = readFile(csv);
      first_events = events;
      ASSERT_GT(parseSummary(summary).events, 1000u);
      continue;
    }
    EXPECT_TRUE(readFile(csv) == first_csv) << "--threads " << threads << ": the CSV differs from 1 thread's";
    EXPECT_EQ(events, first_events) << "--threads " << threads;
  }
}

// A ball dropped from 0.5 m (placement as_given) lands on the floor: the summary counts it.
TEST_F(SimulateCli, TheSummaryCountsFloorImpacts)
{
  const std::string scene = path("drop.yaml");
  {
    std::ofstream out(scene);
    out << "floor: {type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: 0.5}\n"
           "balls:\n  - {position: [0, 0, 0.6], radius: 0.1, placement: as_given}\n";
  }
  // it falls 0.5 m in about 0.32 s
  const RunResult result = run({scene, "--duration", "1"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<std::string> out = lines(result.out);
  ASSERT_FALSE(out.empty());
  const Summary summary = parseSummary(out.back());
  EXPECT_GE(summary.floor_impacts, 1u) << out.back();
  EXPECT_EQ(summary.balls_lost, 0);
}

TEST_F(SimulateCli, StepAndSampleCounts)
{
  struct Case
  {
    std::vector<std::string> args;
    std::uint64_t steps;
    std::size_t samples;  // after t = 0
  };
  const std::vector<Case> cases{
    {{"--duration", "1"}, 100, 100},
    {{"--duration", "0.07"}, 7, 7},  // 0.07 / 0.01 is 7.000000000000001 in doubles: no 8th step
    {{"--duration=0.5", "--sample-every=7"}, 50, 7},
    {{"--duration", "0.005"}, 1, 1},  // a part of a step is a whole step
    {{"--duration", "0"}, 0, 0},
  };
  const std::size_t balls = ball_collision_sim::yaml::loadValidScene(kGoodScene).balls.size();
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.args[0]);
    std::vector<std::string> args{kGoodScene, "--csv", path("out.csv")};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const RunResult result = run(args);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(parseSummary(lines(result.out).back()).steps, c.steps);
    std::string header;
    EXPECT_EQ(parseCsv(readFile(path("out.csv")), &header).size(), balls * (c.samples + 1));
  }
}

TEST_F(SimulateCli, WithoutCsvOnlyTheSummary)
{
  const RunResult result = run({kGoodScene, "--duration", "0.2"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  ASSERT_EQ(lines(result.out).size(), 1u) << result.out;
  EXPECT_EQ(parseSummary(lines(result.out)[0]).steps, 20u);
}

TEST_F(SimulateCli, TwoRunsWriteTheSameBits)
{
  ASSERT_EQ(run({kGoodScene, "--duration", "2", "--csv", path("a.csv")}).exit_code, 0);
  ASSERT_EQ(run({kGoodScene, "--duration", "2", "--csv", path("b.csv")}).exit_code, 0);
  const std::string a = readFile(path("a.csv"));
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a == readFile(path("b.csv")));
}
}  // namespace

namespace
{
// peers_table reads compare_peers' CSV and checks this package's figures against the
// targets: each verdict follows from the numbers of the same run, and a file that is not
// that CSV stops it with exit 2 and names what is missing.
TEST_F(SimulateCli, PeersTableChecksTheTargetsOfOneRun)
{
  {
    std::ofstream out(path("peers.csv"));
    out << "engine,scene,balls,steps,median_ns_per_ball_step,kinetic_end_over_start,max_overlap_m,escaped\n"
           "ball_collision_sim,S1,1000,1000,100,1,0,0\n"
           "ode,S1,1000,1000,1900,1.1,0.03,0\n"
           "ball_collision_sim,S1,10000,1000,140,1.0000000001,0,0\n"
           "ode,S1,10000,1000,3000,1.1,0.06,0\n"
           "bullet,S1,10000,500,2800,1.01,0.05,1\n"
           "ball_collision_sim,S1,100000,400,160,0.999,2e-9,0\n"
           "ode,S1,100000,150,3000,1.01,0.05,0\n"
           "ball_collision_sim,S2,100,100,9000,1,0,3\n";
  }
  const std::string table = "/usr/bin/python3 " + std::string(BCS_CONFIG_DIR) + "/../bench/peers_table ";
  ASSERT_EQ(std::system((table + shellQuote(path("peers.csv")) + " > " + shellQuote(path("t.md")) + " 2>&1").c_str()),
            0)
      << readFile(path("t.md"));
  const std::string md = readFile(path("t.md"));
  for (const char* line : {
           "| ode | S1 | 10000 | 1000 | 3,000 | 1.1 | 0.06 | 0 |",
           "| S1 10000 balls: ns per ball-step | 140 | <= 150 | met |",
           "| S1 10000 balls: fastest peer (bullet) / this | 20.0x | >= 20x | met |",
           "| S1 100000 balls: ns per ball-step | 160 | <= 150 | MISSED |",
           "| S1 100000 balls: fastest peer (ode) / this | 18.8x | >= 20x | MISSED |",
           "| S1 ns at 100000 over ns at 1000 balls | 1.60x | <= 1.5x | MISSED |",
           "| S1 10000 balls: kinetic end / start - 1 | 1e-10 | <= 1e-09 | met |",
           "| S1 100000 balls: kinetic end / start - 1 | 0.001 | <= 1e-09 | MISSED |",
           "| S1 100000 balls: largest overlap [m] | 2e-09 | <= 1e-09 | MISSED |",
           "| S2 100 balls: escaped | 3 | 0 | MISSED |",
       })
    EXPECT_TRUE(contains(md, line)) << line << "\n" << md;
  // (the time targets are set at 10^4 balls and beyond)
  EXPECT_FALSE(contains(md, "| S1 1000 balls: fastest peer")) << md;

  {
    std::ofstream out(path("not_peers.csv"));
    out << "name,iterations,real_time\nBM_S1,5,0.17\n";
  }
  const int status = std::system((table + shellQuote(path("not_peers.csv")) + " > " + shellQuote(path("e.txt")) + " 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_TRUE(contains(readFile(path("e.txt")), "no column engine")) << readFile(path("e.txt"));
}
}  // namespace

// With friction the CSV appends the angular velocity, and the summary's energies count
// the spins' k m r^2 |w|^2 / 2: the billiards break, 12 s, from the cue ball sliding
// without spin to every ball at rest; the bag holds the motion transitions.
TEST_F(SimulateCli, FrictionAppendsTheSpinAndTransitions)
{
  const std::string scene_path = std::string(BCS_CONFIG_DIR) + "/billiards.yaml";
  const std::string csv = path("break.csv");
  const RunResult result =
      run({scene_path, "--duration", "12", "--csv", csv, "--sample-every", "100", "--bag", path("break.bag")});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<std::string> all = lines(readFile(csv));
  ASSERT_GT(all.size(), 2u);
  EXPECT_EQ(all[0], "t,id,x,y,z,vx,vy,vz,wx,wy,wz");
  const ball_collision_sim::core::Scene scene = ball_collision_sim::yaml::loadValidScene(scene_path);
  const std::size_t balls = scene.balls.size();
  // (the energies of the first sample's rows and of the last's: a ball in a pocket has
  // no row after it dropped)
  double start = 0, end = 0, first_t = -1, last_t = -1;
  std::size_t last_rows = 0;
  for (std::size_t i = 1; i < all.size(); ++i)
  {
    double t, x, y, z, vx, vy, vz, wx, wy, wz;
    int id;
    char tail = 0;
    ASSERT_EQ(std::sscanf(all[i].c_str(), "%lf,%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf%c", &t, &id, &x, &y, &z, &vx,
                          &vy, &vz, &wx, &wy, &wz, &tail),
              11)
        << all[i];
    const ball_collision_sim::core::BallDef& b = scene.balls.at(static_cast<std::size_t>(id) - 1);
    const double e = 0.5 * b.mass * (vx * vx + vy * vy + vz * vz) +
                     0.5 * b.inertia * b.mass * b.radius * b.radius * (wx * wx + wy * wy + wz * wz) +
                     b.mass * 9.81 * z;
    if (first_t < 0)
      first_t = t;
    if (t == first_t)
      start += e;
    if (t != last_t)
    {
      last_t = t;
      end = 0;
      last_rows = 0;
    }
    end += e;
    ++last_rows;
    EXPECT_TRUE(t < 12 - 1e-9 || vx * vx + vy * vy + wx * wx + wy * wy + wz * wz == 0.0)
        << "ball " << id << " still moves at the end";
  }
  const Summary summary = parseSummary(lines(result.out).back());
  EXPECT_NEAR(summary.energy_start, start, 1e-12 * start);
  EXPECT_NEAR(summary.energy_end, end, 1e-12 * end);
  EXPECT_LT(summary.energy_end, summary.energy_start);
  EXPECT_GE(summary.balls_pocketed, 1u);
  EXPECT_EQ(last_rows + summary.balls_pocketed, balls);

  rosbag::Bag bag(path("break.bag"));
  std::uint64_t pocketed = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ball_sim/pocketed")))
    if (const auto msg = m.instantiate<ball_collision_sim::PocketedBall>())
    {
      ++pocketed;
      EXPECT_EQ(m.getTime(), msg->header.stamp);
      EXPECT_GE(msg->pocket, 0);
      EXPECT_LT(msg->pocket, 6);
    }
  EXPECT_EQ(pocketed, summary.balls_pocketed);
  int transitions = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ball_sim/motion_transitions")))
    if (const auto msg = m.instantiate<ball_collision_sim::MotionTransition>())
    {
      ++transitions;
      EXPECT_NE(msg->before, msg->after);
      EXPECT_GT(msg->header.stamp.toSec(), 0.0);
    }
  bag.close();
  EXPECT_GE(transitions, static_cast<int>(balls));  // every ball stops at least
}
