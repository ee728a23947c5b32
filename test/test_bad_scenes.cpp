// Bad scenes, one table row each, through the reader and validate() as the node and
// `simulate` use them: each gives one line that names the key and the reason. Files:
// empty, garbage bytes, missing, a directory.
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <unistd.h>
#include <string>
#include <vector>

namespace
{
using ball_collision_sim::core::Scene;
using ball_collision_sim::yaml::loadValidScene;
using ball_collision_sim::yaml::parseScene;
using ball_collision_sim::yaml::SceneError;

const std::string kDataDir = BCS_TEST_DATA_DIR;

/// A good scene: a 2 m x 2 m floor, one wall along its lower edge, one ball; each row
/// changes one thing. `ball`, `wall`, `floor` and `extra` replace the parts.
std::string scene(const std::string& ball = "{position: [0, 0, 0.1], radius: 0.1}",
                  const std::string& wall = "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
                  const std::string& floor = "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0]}",
                  const std::string& extra = "")
{
  return "floor: " + floor + "\nwalls:\n  - " + wall + "\nballs:\n  - " + ball + "\n" + extra;
}

std::string withExtra(const std::string& extra)
{
  return scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
               "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0]}", extra);
}

/// What the node and `simulate` report for this text: the reader's error, or validate()'s
/// issues, prefixed by the source; "" when the scene is good.
std::string problemOf(const std::string& text)
{
  try
  {
    // the scene and the node's settings beside it, as simulate and the node check them
    auto file = ball_collision_sim::yaml::parseSceneFile(text, "t.yaml");
    const auto issues = ball_collision_sim::yaml::check(file);
    return issues.empty() ? "" : "t.yaml: " + ball_collision_sim::core::joinIssues(issues);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
}

struct Row
{
  const char* what;
  std::string yaml;
  const char* key;     ///< the message starts with "t.yaml: <key>: "
  const char* reason;  ///< ... and contains this
};

TEST(BadScenes, TheBaseSceneIsGood)
{
  EXPECT_EQ(problemOf(scene()), "");
  ball_collision_sim::core::World world(parseScene(scene()));
  EXPECT_EQ(world.balls().size(), 1u);
}

TEST(BadScenes, EachGivesOneLineNamingTheKeyAndTheReason)
{
  const std::vector<Row> rows{
      // numbers that are not numbers
      {"radius NaN", scene("{position: [0, 0, 0.1], radius: .nan}"), "balls[0].radius", "must be finite (got nan)"},
      {"radius inf", scene("{position: [0, 0, 0.1], radius: .inf}"), "balls[0].radius", "must be finite (got inf)"},
      {"mass -inf", scene("{position: [0, 0, 0.1], radius: 0.1, mass: -.inf}"), "balls[0].mass", "must be finite"},
      {"position NaN", scene("{position: [.nan, 0, 0.1], radius: 0.1}"), "balls[0].position", "must be finite"},
      {"velocity inf", scene("{position: [0, 0, 0.1], velocity: [0, .inf, 0], radius: 0.1}"), "balls[0].velocity",
       "must be finite"},
      {"wall u NaN", scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [.nan, 0, 0], v: [0, 0, 1]}"),
       "walls[0].u", "must be finite"},
      {"floor point inf",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{point: [-1, .inf, 0], u: [2, 0, 0], v: [0, 2, 0]}"),
       "floor.point", "must be finite"},
      {"dt NaN", withExtra("dt: .nan"), "dt", "must be finite"},
      {"gravity inf", withExtra("gravity: [0, 0, -.inf]"), "gravity", "must be finite"},
      {"restitution NaN", withExtra("restitution: .nan"), "restitution", "must be finite"},
      // zero and negative
      {"radius 0", scene("{position: [0, 0, 0.1], radius: 0}"), "balls[0].radius", "must be > 0 (got 0)"},
      {"radius -0.1", scene("{position: [0, 0, 0.1], radius: -0.1}"), "balls[0].radius", "must be > 0 (got -0.1)"},
      {"mass 0", scene("{position: [0, 0, 0.1], radius: 0.1, mass: 0}"), "balls[0].mass", "must be > 0 (got 0)"},
      {"mass -2", scene("{position: [0, 0, 0.1], radius: 0.1, mass: -2}"), "balls[0].mass", "must be > 0 (got -2)"},
      {"dt 0", withExtra("dt: 0"), "dt", "must be in (0, 10] s (got 0)"},
      {"dt negative", withExtra("dt: -0.01"), "dt", "must be in (0, 10] s"},
      {"restitution negative", withExtra("restitution: -0.5"), "restitution", "must be in [0, 1] (got -0.5)"},
      {"restitution above 1", withExtra("restitution: 1.5"), "restitution", "must be in [0, 1] (got 1.5)"},
      {"wall restitution 2",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 1], restitution: 2}"),
       "walls[0].restitution", "must be in [0, 1]"},
      {"random radius 0", withExtra("random_balls: {count: 3, radius: [0, 0.1]}"), "random_balls.radius",
       "minimum must be >= 1e-06"},
      {"random mass negative", withExtra("random_balls: {count: 3, mass: [-1, 1]}"), "random_balls.mass",
       "minimum must be >= 1e-12"},
      {"random count negative", withExtra("random_balls: {count: -1}"), "random_balls.count",
       "must be in [0, 10000000] (got -1)"},
      {"random range upside down", withExtra("random_balls: {count: 3, radius: [0.1, 0.05]}"), "random_balls.radius",
       "maximum 0.05 is below minimum 0.1"},
      {"real_time_factor negative", withExtra("real_time_factor: -1"), "real_time_factor", "must be >= 0"},
      {"max_balls 0", withExtra("max_balls: 0"), "max_balls", "must be >= 1 (got 0)"},
      {"threads negative", withExtra("threads: -2"), "threads", "must be in [0, 1024] (0 = every core; got -2)"},
      {"tf_rate negative", withExtra("tf_rate: -30"), "tf_rate", "must be in [0, 1e6] Hz (got -30)"},
      {"click_radius 0", withExtra("click_radius: 0"), "click_radius", "must be > 0"},
      // a denormal period is 0 ns to a timer, which would fire without pause
      {"status_period a denormal", withExtra("status_period: 4.9e-324"), "status_period",
       "must be 0 (no status line) or in [0.01, 1e6] s (got 5e-324)"},
      {"status_period 1 ms", withExtra("status_period: 0.001"), "status_period", "or in [0.01, 1e6] s (got 0.001)"},
      // friction, spin and inertia
      {"friction sliding negative", withExtra("friction: {sliding: -0.2}"), "friction.sliding",
       "must be in [0, 10] (got -0.2)"},
      {"friction rolling NaN", withExtra("friction: {rolling: .nan}"), "friction.rolling", "must be finite"},
      {"friction unknown key", withExtra("friction: {slidng: 0.2}"), "friction.slidng", "unknown key"},
      {"friction wall 20", withExtra("friction: {wall: 20}"), "friction.wall", "must be in [0, 10] (got 20)"},
      {"friction not a map", withExtra("friction: 0.2"), "friction", "expected a map"},
      {"inertia a word", scene("{position: [0, 0, 0.1], radius: 0.1, inertia: wooden}"), "balls[0].inertia",
       "expected solid, hollow or a number k in [0.01, 1]"},
      {"inertia 1.5", scene("{position: [0, 0, 0.1], radius: 0.1, inertia: 1.5}"), "balls[0].inertia",
       "must be solid, hollow or a number k in [0.01, 1] (got 1.5)"},
      {"inertia 0", scene("{position: [0, 0, 0.1], radius: 0.1, inertia: 0}"), "balls[0].inertia",
       "must be solid, hollow or a number k in [0.01, 1] (got 0)"},
      // a k so small that k m r^2 is a denormal, 1 / I infinite
      {"inertia DBL_MIN", scene("{position: [0, 0, 0.1], radius: 0.1, inertia: 2.2250738585072014e-308}"),
       "balls[0].inertia", "must be solid, hollow or a number k in [0.01, 1] (got 2.2250738585072014e-308)"},
      {"inertia 0.009", scene("{position: [0, 0, 0.1], radius: 0.1, inertia: 0.009}"), "balls[0].inertia",
       "[0.01, 1] (got 0.009)"},
      {"random inertia -1", withExtra("random_balls: {count: 1, inertia: -1}"), "random_balls.inertia",
       "[0.01, 1] (got -1)"},
      {"angular velocity of 2", scene("{position: [0, 0, 0.1], radius: 0.1, angular_velocity: [1, 2]}"),
       "balls[0].angular_velocity", "expected a list of 3 numbers"},
      {"angular velocity NaN", scene("{position: [0, 0, 0.1], radius: 0.1, angular_velocity: [0, .nan, 0]}"),
       "balls[0].angular_velocity", "must be finite"},
      // absurd sizes
      {"radius 1e300", scene("{position: [0, 0, 0.1], radius: 1e300}"), "balls[0].radius", "must be <= 1e+06 m (got 1e+300)"},
      {"radius 1e-320", scene("{position: [0, 0, 0.1], radius: 1e-320}"), "balls[0].radius", "must be >= 1e-06 m"},
      {"mass 1e300", scene("{position: [0, 0, 0.1], radius: 0.1, mass: 1e300}"), "balls[0].mass", "must be <= 1e+12 kg"},
      {"mass 1e-320", scene("{position: [0, 0, 0.1], radius: 0.1, mass: 1e-320}"), "balls[0].mass", "must be >= 1e-12 kg"},
      {"position 1e300", scene("{position: [1e300, 0, 0.1], radius: 0.1}"), "balls[0].position",
       "length must be <= 1e+06 m (got 1e+300)"},
      {"velocity 1e300", scene("{position: [0, 0, 0.1], velocity: [1e300, 1e300, 0], radius: 0.1}"),
       "balls[0].velocity", "length must be <= 1e+07 m/s"},
      {"wall u 1e300", scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [1e300, 0, 0], v: [0, 0, 1]}"),
       "walls[0].u", "length must be <= 1e+06 m"},
      {"wall u 1e-200", scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [1e-200, 0, 0], v: [0, 0, 1]}"),
       "walls[0].u", "length must be >= 1e-06 m"},
      {"floor u 1e300",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{point: [-1, -1, 0], u: [1e300, 0, 0], v: [0, 2, 0]}"),
       "floor.u", "length must be <= 1e+06 m"},
      {"dt 1e300", withExtra("dt: 1e300"), "dt", "must be in (0, 10] s (got 1e+300)"},
      {"gravity 1e300", withExtra("gravity: [0, 0, -1e300]"), "gravity", "length must be <= 1e+06 m/s^2"},
      {"marker_rate 1e300", withExtra("marker_rate: 1e300"), "marker_rate", "must be in [0, 1e6] Hz"},
      {"random count 1e7 + 1", withExtra("random_balls: {count: 10000001}"), "random_balls.count",
       "must be in [0, 10000000]"},
      {"random balls that cannot fit", withExtra("random_balls: {count: 100000, radius: [0.1, 0.1]}"),
       "random_balls.count", "room for only"},
      // geometry
      // (numbers in their shortest form: 0.25 - 0.1875 is 0.0625 exactly; 0.2 - 0.15 would
      // print as 0.05000000000000002)
      {"ball overlaps a ball",
       scene("{position: [0, 0, 0.125], radius: 0.125}\n  - {position: [0.1875, 0, 0.125], radius: 0.125}"),
       "balls[1]", "overlaps balls[0] by 0.0625 m"},
      {"ball overlaps a wall", scene("{position: [0, -0.95, 0.1], radius: 0.1}"), "balls[0]", "overlaps walls[0] by"},
      {"ball off the floor", scene("{position: [5, 0, 0.1], radius: 0.1}"), "balls[0].position", "off the floor"},
      {"ball below the floor", scene("{position: [0, 0, -0.5], radius: 0.1}"), "balls[0].position",
       "below the surface"},
      {"ball above the floor", scene("{position: [0, 0, 1], radius: 0.1}"), "balls[0].position", "above the surface"},
      {"wall v parallel to u",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [1, 0, 0]}"), "walls[0].v",
       "parallel to walls[0].u"},
      {"wall v against u",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [-3, 0, 0]}"),
       "walls[0].v", "parallel to walls[0].u"},
      {"wall u zero", scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [0, 0, 0], v: [0, 0, 1]}"),
       "walls[0].u", "must be non-zero"},
      {"wall v zero", scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0]}"),
       "walls[0].v", "must be non-zero"},
      {"floor v parallel",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{point: [-1, -1, 0], u: [2, 0, 0], v: [4, 0, 0]}"),
       "floor.v", "parallel to floor.u"},
      {"floor without a normal",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{type: biquadratic, control_points: [[[0,0,0],[1,0,0],[2,0,0]], [[1,0,0],[2,0,0],[3,0,0]], "
             "[[2,0,0],[3,0,0],[4,0,0]]]}"),
       "floor.control_points", "degenerate surface"},
      {"random balls without a floor", "random_balls: {count: 3}", "random_balls", "needs a floor"},
      // flight: the floor's restitution and the balls' placement
      {"floor restitution 1.5",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: 1.5}"),
       "floor.restitution", "must be in [0, 1] (got 1.5)"},
      {"floor restitution negative",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: -0.1}"),
       "floor.restitution", "must be in [0, 1] (got -0.1)"},
      {"floor restitution a word",
       scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
             "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: soft}"),
       "floor.restitution", "expected a number, got soft"},
      {"placement a word", scene("{position: [0, 0, 0.1], radius: 0.1, placement: x}"), "balls[0].placement",
       "expected on_floor or as_given, got x"},
      {"placement a number", scene("{position: [0, 0, 0.1], radius: 0.1, placement: 1}"), "balls[0].placement",
       "expected on_floor or as_given, got 1"},
      {"as_given below the floor", scene("{position: [0, 0, 0.05], radius: 0.1, placement: as_given}"),
       "balls[0].position", "below the floor"},
      // wrong types (integers where reals are expected are fine: see below)
      {"radius a word", scene("{position: [0, 0, 0.1], radius: big}"), "balls[0].radius",
       "expected a number, got big"},
      {"radius a string", scene("{position: [0, 0, 0.1], radius: \"0.1\"}"), "balls[0].radius",
       "expected a number, got the string \"0.1\""},
      {"radius true", scene("{position: [0, 0, 0.1], radius: true}"), "balls[0].radius", "expected a number, got true"},
      {"radius a list", scene("{position: [0, 0, 0.1], radius: [0.1]}"), "balls[0].radius",
       "expected a number, got a list"},
      {"radius null", scene("{position: [0, 0, 0.1], radius: }"), "balls[0].radius", "expected a number, got null"},
      {"position a number", scene("{position: 3, radius: 0.1}"), "balls[0].position",
       "expected a list of 3 numbers, got 3"},
      {"position two numbers", scene("{position: [0, 0], radius: 0.1}"), "balls[0].position",
       "expected a list of 3 numbers, got a list of 2 items"},
      {"position hex", scene("{position: [0x10, 0, 0.1], radius: 0.1}"), "balls[0].position[0]",
       "expected a number, got 0x10"},
      {"balls a map", "balls: {position: [0, 0, 0.1], radius: 0.1}", "balls", "expected a list, got a map"},
      {"floor a list", "floor: [1, 2]", "floor", "expected a map, got a list"},
      {"count a real", withExtra("random_balls: {count: 2.0}"), "random_balls.count", "expected an integer, got 2.0"},
      {"max_balls a real", withExtra("max_balls: 1e3"), "max_balls", "expected an integer, got 1e3"},
      {"start_paused 1", withExtra("start_paused: 1"), "start_paused", "expected true or false, got 1"},
      {"frame_id a map", withExtra("frame_id: {a: 1}"), "frame_id", "expected a string, got a map"},
      {"dt 1e999", withExtra("dt: 1e999"), "dt", "number out of range of a double"},
      {"radius misspelt", scene("{position: [0, 0, 0.1], radus: 0.1}"), "balls[0].radus", "unknown key"},
      {"radius missing", scene("{position: [0, 0, 0.1]}"), "balls[0].radius", "required"},
      {"dt twice", withExtra("dt: 0.1\ndt: 0.2"), "dt", "duplicate key"},
  };
  for (const Row& row : rows)
  {
    SCOPED_TRACE(row.what);
    const std::string message = problemOf(row.yaml);
    EXPECT_EQ(message.rfind(std::string("t.yaml: ") + row.key + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(row.reason), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// The same fields done right: a ball given above the floor, a floor restitution in [0, 1].
TEST(BadScenes, AsGivenAboveTheFloorAndFloorRestitutionAreGood)
{
  EXPECT_EQ(problemOf(scene("{position: [0, 0, 0.6], velocity: [0.5, 0, 1], radius: 0.1, placement: as_given}")), "");
  EXPECT_EQ(problemOf(scene("{position: [0, 0, 0.1], radius: 0.1, placement: as_given}")), "");
  EXPECT_EQ(problemOf(scene("{position: [0, 0, 0.1], radius: 0.1}", "{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 0.3]}",
                            "{type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0], restitution: 0}")),
            "");
}

TEST(BadScenes, IntegersAreAcceptedWhereRealsAreExpected)
{
  const auto file = ball_collision_sim::yaml::parseSceneFile(
      "floor: {type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0]}\n"
      "walls: [{point: [-1, -1, 0], u: [2, 0, 0], v: [0, 0, 1], restitution: 1}]\n"
      "balls: [{position: [0, 0, 1], velocity: [1, -2, 0], radius: 1, mass: 3}]\n"
      "dt: 1\nrestitution: 0\ngravity: [0, 0, -10]\nreal_time_factor: 2\nmarker_rate: 10\n"
      "random_balls: {count: 0, radius: [1, 2], mass: [1, 1], speed: [0, 1]}");
  const Scene& s = file.scene;
  EXPECT_TRUE(ball_collision_sim::core::validate(s).empty()) << ball_collision_sim::core::joinIssues(ball_collision_sim::core::validate(s));
  EXPECT_EQ(s.balls[0].radius, 1.0);
  EXPECT_EQ(s.balls[0].mass, 3.0);
  EXPECT_EQ(s.balls[0].velocity.y(), -2.0);
  EXPECT_EQ(*s.walls[0].restitution, 1.0);
  EXPECT_EQ(s.dt, 1.0);
  EXPECT_EQ(s.gravity.z(), -10.0);
  EXPECT_EQ(file.node.real_time_factor, 2.0);
  EXPECT_EQ(s.random_balls->radius.max, 2.0);
}

/// The message of loadValidScene(path), or "<no error>".
std::string fileProblem(const std::string& path)
{
  try
  {
    loadValidScene(path);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "<no error>";
}

/// Bytes written to a fresh file under /tmp.
std::string tempFile(const std::string& name, const std::string& bytes)
{
  const std::string path = "/tmp/bcs_bad_scenes_" + std::to_string(::getpid()) + "_" + name;
  FILE* file = std::fopen(path.c_str(), "wb");
  std::fwrite(bytes.data(), 1, bytes.size(), file);
  std::fclose(file);
  return path;
}

TEST(BadScenes, Files)
{
  struct FileRow
  {
    const char* what;
    std::string path;
    const char* reason;  ///< the message is "<path>: " + something containing this
  };
  std::string binary;
  for (int k = 0; k < 256; ++k)
    binary += static_cast<char>((k * 73 + 11) & 0xff);  // every byte value, NUL and invalid UTF-8 among them
  const std::vector<FileRow> rows{
      {"empty", kDataDir + "/empty.yaml", "the scene must be a YAML map, got an empty document"},
      {"only blanks", tempFile("blank.yaml", "\n   \n\n"), "the scene must be a YAML map, got an empty document"},
      {"garbage bytes", kDataDir + "/garbage.bin", ""},
      {"every byte value", tempFile("bytes.bin", binary), ""},
      {"a NUL in a value", tempFile("nul.yaml", std::string("dt: 0.0\0" "1\n", 11)), "byte 7 is NUL: not a YAML text file"},
      {"a control byte as the document", tempFile("ctrl.yaml", "\x01\x02\x03"), "the scene must be a YAML map, got"},
      {"text, not YAML structure", tempFile("prose.yaml", "hello world"), "the scene must be a YAML map, got hello world"},
      {"missing", kDataDir + "/no_such_file.yaml", "cannot open file (No such file or directory)"},
      {"a directory", kDataDir, "cannot read file"},
      {"truncated", tempFile("truncated.yaml", "balls:\n  - {position: [0, 0, 0.1], radi"), ""},
  };
  for (const FileRow& row : rows)
  {
    SCOPED_TRACE(row.what);
    const std::string message = fileProblem(row.path);
    EXPECT_EQ(message.rfind(row.path + ":", 0), 0u) << message;
    EXPECT_GT(message.size(), row.path.size() + 3) << message;
    EXPECT_NE(message.find(row.reason), std::string::npos) << message;
    // one line of printable text (bytes of the file shown escaped)
    for (const char c : message)
      EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << "byte " << int(c) << " in: " << message;
  }
}
}  // namespace
