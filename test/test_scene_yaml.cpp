// The YAML scene reader: every field, the defaults, and one clear line per mistake.

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
using ball_collision_sim::core::FloorDef;
using ball_collision_sim::core::Scene;
using ball_collision_sim::core::Vec2;
using ball_collision_sim::core::Vec3;
using ball_collision_sim::yaml::loadSceneFile;
using ball_collision_sim::yaml::loadValidScene;
using ball_collision_sim::yaml::parseScene;
using ball_collision_sim::yaml::parseSceneFile;
using ball_collision_sim::yaml::SceneError;

const std::string kDataDir = BCS_TEST_DATA_DIR;
const std::string kConfigDir = BCS_CONFIG_DIR;

/// The SceneError message of parsing `text` as "t.yaml", or "<no error>".
std::string errorOf(const std::string& text)
{
  try
  {
    parseScene(text, "t.yaml");
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "<no error>";
}

template <typename Load>
std::string errorOfLoad(Load load, const std::string& path)
{
  try
  {
    load(path);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "<no error>";
}

bool startsWith(const std::string& text, const std::string& prefix)
{
  return text.rfind(prefix, 0) == 0;
}

void expectVec(const Vec3& actual, double x, double y, double z)
{
  EXPECT_EQ(actual.x(), x);
  EXPECT_EQ(actual.y(), y);
  EXPECT_EQ(actual.z(), z);
}

TEST(SceneYaml, ReadsEveryField)
{
  const auto file = parseSceneFile(R"(
frame_id: map
dt: 0.005
real_time_factor: 0.5
gravity: [0.1, -0.2, -9.5]
restitution: 0.9
floor:
  type: biquadratic
  control_points:
    - [[-2, -2, 0.1], [-2, 0, 0.2], [-2, 2, 0.3]]
    - [[0, -2, 0.4], [0, 0, -0.5], [0, 2, 0.6]]
    - [[2, -2, 0.7], [2, 0, 0.8], [2, 2, 0.9]]
walls:
  - {point: [-2, -2, 0], u: [4, 0, 0], v: [0, 0, 0.5]}
  - point: [2, -2, 0]
    u: [0, 4, 0]
    v: [0, 0, 0.5]
    restitution: 0.7
balls:
  - {position: [0.5, 0.25, 0.3], velocity: [1, -0.5, 0.125], radius: 0.1, mass: 2.5}
  - {position: [-0.5, 0, 0.2], radius: 0.2}
random_balls:
  count: 17
  seed: 12345678901234567890
  radius: [0.01, 0.02]
  mass: [0.5, 1.5]
  speed: [0.25, 3]
  region: {min: [-1, -0.5], max: [1, 0.5]}
marker_rate: 30
tf_rate: 50.5
tf_max_balls: 100
)");
  const Scene& scene = file.scene;
  EXPECT_EQ(scene.frame_id, "map");
  EXPECT_EQ(scene.dt, 0.005);
  EXPECT_EQ(file.node.real_time_factor, 0.5);
  EXPECT_EQ(file.node.marker_rate, 30);
  EXPECT_EQ(file.node.tf_rate, 50.5);
  EXPECT_EQ(file.node.tf_max_balls, 100);
  expectVec(scene.gravity, 0.1, -0.2, -9.5);
  EXPECT_EQ(scene.restitution, 0.9);

  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->type, FloorDef::Type::kBiquadratic);
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      SCOPED_TRACE("control point " + std::to_string(i) + ", " + std::to_string(j));
      // Written so that x follows the row, y the column and z counts 0.1 .. 0.9 (but -0.5).
      const double z = (i == 1 && j == 1) ? -0.5 : 0.1 * (3 * i + j + 1);
      const Vec3& p = scene.floor->control_points[i][j];
      EXPECT_EQ(p.x(), -2.0 + 2.0 * i);
      EXPECT_EQ(p.y(), -2.0 + 2.0 * j);
      EXPECT_NEAR(p.z(), z, 1e-15);
    }
  }

  ASSERT_EQ(scene.walls.size(), 2u);
  expectVec(scene.walls[0].point, -2, -2, 0);
  expectVec(scene.walls[0].u, 4, 0, 0);
  expectVec(scene.walls[0].v, 0, 0, 0.5);
  EXPECT_FALSE(scene.walls[0].restitution.has_value());
  expectVec(scene.walls[1].point, 2, -2, 0);
  expectVec(scene.walls[1].u, 0, 4, 0);
  expectVec(scene.walls[1].v, 0, 0, 0.5);
  ASSERT_TRUE(scene.walls[1].restitution.has_value());
  EXPECT_EQ(*scene.walls[1].restitution, 0.7);

  ASSERT_EQ(scene.balls.size(), 2u);
  expectVec(scene.balls[0].position, 0.5, 0.25, 0.3);
  expectVec(scene.balls[0].velocity, 1, -0.5, 0.125);
  EXPECT_EQ(scene.balls[0].radius, 0.1);
  EXPECT_EQ(scene.balls[0].mass, 2.5);
  expectVec(scene.balls[1].position, -0.5, 0, 0.2);
  EXPECT_EQ(scene.balls[1].radius, 0.2);

  ASSERT_TRUE(scene.random_balls.has_value());
  const auto& random = *scene.random_balls;
  EXPECT_EQ(random.count, 17);
  EXPECT_EQ(random.seed, UINT64_C(12345678901234567890));
  EXPECT_EQ(random.radius.min, 0.01);
  EXPECT_EQ(random.radius.max, 0.02);
  EXPECT_EQ(random.mass.min, 0.5);
  EXPECT_EQ(random.mass.max, 1.5);
  EXPECT_EQ(random.speed.min, 0.25);
  EXPECT_EQ(random.speed.max, 3.0);
  ASSERT_TRUE(random.region.has_value());
  EXPECT_EQ(random.region->min, Vec2(-1, -0.5));
  EXPECT_EQ(random.region->max, Vec2(1, 0.5));
}

TEST(SceneYaml, ReadsAPlaneFloor)
{
  const Scene scene = parseScene("floor: {type: plane, point: [1, 2, 3], u: [4, 5, 6], v: [7, 8, 9]}");
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->type, FloorDef::Type::kPlane);
  expectVec(scene.floor->point, 1, 2, 3);
  expectVec(scene.floor->u, 4, 5, 6);
  expectVec(scene.floor->v, 7, 8, 9);
}

// Flight's fields: the floor's restitution (either floor type) and each ball's placement.
TEST(SceneYaml, ReadsFloorRestitutionAndBallPlacement)
{
  using ball_collision_sim::core::BallPlacement;
  const Scene plane = parseScene(R"(
floor: {type: plane, restitution: 0.5}
balls:
  - {position: [0, 0, 0.1], radius: 0.1}
  - {position: [1, 0, 0.1], radius: 0.1, placement: on_floor}
  - {position: [0, 1, 0.6], velocity: [0, 0, 2], radius: 0.1, placement: as_given}
  - {position: [1, 1, 0.6], radius: 0.1, placement: "as_given"}
)");
  ASSERT_TRUE(plane.floor.has_value());
  ASSERT_TRUE(plane.floor->restitution.has_value());
  EXPECT_EQ(*plane.floor->restitution, 0.5);
  ASSERT_EQ(plane.balls.size(), 4u);
  EXPECT_EQ(plane.balls[0].placement, BallPlacement::kOnFloor);
  EXPECT_EQ(plane.balls[1].placement, BallPlacement::kOnFloor);
  EXPECT_EQ(plane.balls[2].placement, BallPlacement::kAsGiven);
  EXPECT_EQ(plane.balls[3].placement, BallPlacement::kAsGiven);
  expectVec(plane.balls[2].position, 0, 1, 0.6);
  expectVec(plane.balls[2].velocity, 0, 0, 2);

  const Scene curved = parseScene(R"(
floor:
  type: biquadratic
  restitution: 0
  control_points:
    - [[-2, -2, 0], [-2, 0, 0], [-2, 2, 0]]
    - [[0, -2, 0], [0, 0, 0], [0, 2, 0]]
    - [[2, -2, 0], [2, 0, 0], [2, 2, 0]]
)");
  ASSERT_TRUE(curved.floor.has_value());
  ASSERT_TRUE(curved.floor->restitution.has_value());
  EXPECT_EQ(*curved.floor->restitution, 0.0);

  // absent: unset, so that ball-floor impacts take the scene's restitution
  EXPECT_FALSE(parseScene("floor: {type: plane}").floor->restitution.has_value());
}

TEST(SceneYaml, AppliesTheDocumentedDefaults)
{
  const Scene defaults;
  const auto file = parseSceneFile("balls: [{position: [1, 2, 3], radius: 0.5}]\nfloor: {}\nrandom_balls: {count: 3}");
  const Scene& scene = file.scene;
  EXPECT_EQ(scene.frame_id, "world");
  EXPECT_EQ(scene.dt, 0.01);
  EXPECT_EQ(file.node.real_time_factor, 1.0);
  expectVec(scene.gravity, 0, 0, -9.81);
  EXPECT_EQ(scene.restitution, 1.0);
  EXPECT_TRUE(scene.walls.empty());

  ASSERT_EQ(scene.balls.size(), 1u);
  expectVec(scene.balls[0].velocity, 0, 0, 0);
  EXPECT_EQ(scene.balls[0].mass, 1.0);

  // An empty floor map is a plane with the struct's documented corner and edges.
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->type, FloorDef::Type::kPlane);
  EXPECT_EQ(scene.floor->point, FloorDef().point);
  EXPECT_EQ(scene.floor->u, FloorDef().u);
  EXPECT_EQ(scene.floor->v, FloorDef().v);

  ASSERT_TRUE(scene.random_balls.has_value());
  const ball_collision_sim::core::RandomBallsDef random_defaults;
  EXPECT_EQ(scene.random_balls->count, 3);
  EXPECT_EQ(scene.random_balls->seed, random_defaults.seed);
  EXPECT_EQ(scene.random_balls->radius.min, random_defaults.radius.min);
  EXPECT_EQ(scene.random_balls->radius.max, random_defaults.radius.max);
  EXPECT_EQ(scene.random_balls->mass.min, random_defaults.mass.min);
  EXPECT_EQ(scene.random_balls->speed.max, random_defaults.speed.max);
  EXPECT_FALSE(scene.random_balls->region.has_value());

  // A map with nothing in it is the all-default scene.
  const Scene empty = parseScene("{}");
  EXPECT_FALSE(empty.floor.has_value());
  EXPECT_TRUE(empty.balls.empty());
  EXPECT_FALSE(empty.random_balls.has_value());
  EXPECT_EQ(empty.dt, defaults.dt);
}

TEST(SceneYaml, EmptySectionsMeanAbsent)
{
  const Scene scene = parseScene("floor:\nwalls:\nballs:\nrandom_balls: ~\n");
  EXPECT_FALSE(scene.floor.has_value());
  EXPECT_TRUE(scene.walls.empty());
  EXPECT_TRUE(scene.balls.empty());
  EXPECT_FALSE(scene.random_balls.has_value());
}

TEST(SceneYaml, AcceptsIntegersWhereRealsAreExpected)
{
  const auto file = parseSceneFile(
      "dt: 1\nrestitution: 0\ngravity: [0, 0, -10]\nballs: [{position: [1, -2, +3], radius: 1, mass: 2}]\n"
      "random_balls: {count: +4, radius: [1, 2]}\nreal_time_factor: 0");
  const Scene& scene = file.scene;
  EXPECT_EQ(scene.dt, 1.0);
  EXPECT_EQ(scene.restitution, 0.0);
  expectVec(scene.gravity, 0, 0, -10);
  expectVec(scene.balls[0].position, 1, -2, 3);
  EXPECT_EQ(scene.balls[0].radius, 1.0);
  EXPECT_EQ(scene.balls[0].mass, 2.0);
  EXPECT_EQ(scene.random_balls->count, 4);
  EXPECT_EQ(scene.random_balls->radius.min, 1.0);
  EXPECT_EQ(file.node.real_time_factor, 0.0);
}

TEST(SceneYaml, AcceptsNumberSpellings)
{
  const Scene scene = parseScene("dt: 1e-3\nrestitution: .5\ngravity: [1., -2.5E+1, !!float 3]");
  EXPECT_EQ(scene.dt, 1e-3);
  EXPECT_EQ(scene.restitution, 0.5);
  expectVec(scene.gravity, 1, -25, 3);
}

TEST(SceneYaml, ReadsNanAndInfinityAsNumbersForValidateToReject)
{
  const Scene scene = parseScene("balls: [{position: [.nan, .inf, -.Inf], radius: +.INF, mass: .NaN}]");
  EXPECT_TRUE(std::isnan(scene.balls[0].position.x()));
  EXPECT_EQ(scene.balls[0].position.y(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(scene.balls[0].position.z(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(scene.balls[0].radius, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(scene.balls[0].mass));

  const auto issues = ball_collision_sim::core::validate(scene);
  ASSERT_FALSE(issues.empty());
  EXPECT_EQ(issues[0].key, "balls[0].position");
}

TEST(SceneYaml, AcceptsAndIgnoresNodeOnlyKeys)
{
  std::string text;
  for (const auto key : ball_collision_sim::yaml::kNodeOnlyKeys)
  {
    if (key == "publish_collisions" || key == "start_paused" || key == "collision_flashes" || key == "publish_clock")
      text += std::string(key) + ": false\n";
    else if (key == "ball_color")
      text += std::string(key) + ": id\n";
    else if (key == "frame_prefix")
      text += std::string(key) + ": sim_a/\n";
    else
      text += std::string(key) + ": 10\n";
  }
  const auto file = parseSceneFile(text);
  EXPECT_EQ(file.node.marker_rate, 10);
  EXPECT_EQ(file.node.tf_max_balls, 10);
  EXPECT_FALSE(file.node.publish_collisions);
  EXPECT_FALSE(file.node.collision_flashes);
  EXPECT_EQ(file.node.ball_color, ball_collision_sim::BallColor::kId);
  EXPECT_EQ(file.node.speed_color_max, 10);
  EXPECT_EQ(file.node.publish_clock, false);
  EXPECT_EQ(file.node.frame_prefix, "sim_a/");
  EXPECT_EQ(errorOf("tf_rate: fast"), "t.yaml: tf_rate: expected a number, got fast");
  EXPECT_EQ(errorOf("frame_prefix: /a/"), "t.yaml: frame_prefix: must not start with '/' (tf2 frame names do not), got \"/a/\"");
  EXPECT_EQ(errorOf("publish_clock: yes"), "t.yaml: publish_clock: expected true or false, got yes");
  EXPECT_EQ(errorOf("start_paused: 1"), "t.yaml: start_paused: expected true or false, got 1");
  EXPECT_EQ(errorOf("tf_max_balls: 2.5"), "t.yaml: tf_max_balls: expected an integer, got 2.5");
  EXPECT_EQ(file.node.threads, 10);
  EXPECT_EQ(errorOf("threads: two"), "t.yaml: threads: expected an integer, got two");
}

struct ErrorCase
{
  const char* yaml;
  const char* message;  // the whole message expected
};

TEST(SceneYaml, EachMistakeGivesOneLineNamingTheKeyAndTheReason)
{
  const std::vector<ErrorCase> cases{
    // unknown keys
    {"balls:\n  - {position: [0, 0, 0], radius: 1}\n  - {position: [1, 0, 0], radius: 1}\n"
     "  - {position: [2, 0, 0], radius: 1}\n  - {position: [3, 0, 0], radus: 1}\n",
     "t.yaml: balls[3].radus: unknown key (expected one of: position, velocity, radius, mass, angular_velocity, inertia, placement)"},
    {"dtt: 0.1", "t.yaml: dtt: unknown key (expected one of: frame_id, dt, gravity, restitution, floor, friction, walls, "
                 "balls, random_balls, pockets, real_time_factor, marker_rate, tf_rate, tf_max_balls, state_rate, "
                 "publish_collisions, start_paused, click_radius, click_mass, status_period, max_balls, "
                 "marker_list_threshold, play_max_balls, ball_color, speed_color_max, collision_flashes, publish_clock, frame_prefix, threads)"},
    {"floor: {type: plane, control_points: []}",
     "t.yaml: floor.control_points: unknown key (expected one of: type, point, u, v, restitution)"},
    {"random_balls: {count: 1, region: {min: [0, 0], max: [1, 1], mid: [0, 0]}}",
     "t.yaml: random_balls.region.mid: unknown key (expected one of: min, max)"},
    {"dt: 0.1\ndt: 0.2", "t.yaml: dt: duplicate key"},
    // wrong types
    {"dt: [1, 2]", "t.yaml: dt: expected a number, got a list"},
    {"dt: {a: 1}", "t.yaml: dt: expected a number, got a map"},
    {"dt: true", "t.yaml: dt: expected a number, got true"},
    {"dt: \"0.01\"", "t.yaml: dt: expected a number, got the string \"0.01\""},
    {"dt: !!str 0.01", "t.yaml: dt: expected a number, got the string \"0.01\""},
    {"dt:", "t.yaml: dt: expected a number, got null"},
    {"dt: 0x10", "t.yaml: dt: expected a number, got 0x10"},
    {"dt: 1e999", "t.yaml: dt: number out of range of a double, got 1e999"},
    {"frame_id: [a]", "t.yaml: frame_id: expected a string, got a list"},
    {"walls:\n  - {point: [0, 0, 0], u: 2, v: [0, 0, 1]}", "t.yaml: walls[0].u: expected a list of 3 numbers, got 2"},
    {"walls:\n  - {point: [0, 0, 0], u: [1, 0], v: [0, 0, 1]}",
     "t.yaml: walls[0].u: expected a list of 3 numbers, got a list of 2 items"},
    {"gravity: [0, x, 1]", "t.yaml: gravity[1]: expected a number, got x"},
    {"balls: [{position: [0, 0, 0], radius: yes}]", "t.yaml: balls[0].radius: expected a number, got yes"},
    {"random_balls: {count: 2.5}", "t.yaml: random_balls.count: expected an integer, got 2.5"},
    {"random_balls: {count: 99999999999}", "t.yaml: random_balls.count: integer out of range, got 99999999999"},
    {"random_balls: {count: 1, seed: -1}", "t.yaml: random_balls.seed: expected an integer >= 0, got -1"},
    {"random_balls: {count: 1, radius: 0.1}",
     "t.yaml: random_balls.radius: expected a list [min, max] of 2 numbers, got 0.1"},
    {"random_balls: {count: 1, region: {min: [0, 0, 0], max: [1, 1]}}",
     "t.yaml: random_balls.region.min: expected a list of 2 numbers [x, y], got a list of 3 items"},
    {"floor: {type: sphere}", "t.yaml: floor.type: expected plane or biquadratic, got sphere"},
    {"floor: {restitution: high}", "t.yaml: floor.restitution: expected a number, got high"},
    {"floor: {type: biquadratic, restitution: [0.5], control_points: []}",
     "t.yaml: floor.restitution: expected a number, got a list"},
    {"balls:\n  - {position: [0, 0, 0], radius: 1}\n  - {position: [1, 0, 0], radius: 1}\n"
     "  - {position: [2, 0, 0], radius: 1, placement: x}\n",
     "t.yaml: balls[2].placement: expected on_floor or as_given, got x"},
    {"balls: [{position: [0, 0, 0], radius: 1, placement: \"flying\"}]",
     "t.yaml: balls[0].placement: expected on_floor or as_given, got the string \"flying\""},
    {"balls: [{position: [0, 0, 0], radius: 1, placement: [as_given]}]",
     "t.yaml: balls[0].placement: expected on_floor or as_given, got a list"},
    {"balls: [{position: [0, 0, 0], radius: 1, placement:}]",
     "t.yaml: balls[0].placement: expected on_floor or as_given, got null"},
    {"floor: {type: biquadratic, control_points: [[], []]}",
     "t.yaml: floor.control_points: expected 3 rows of 3 points [x, y, z], got a list of 2 items"},
    {"floor: {type: biquadratic, control_points: [[[0,0,0],[0,1,0],[0,2,0]], [[1,0,0],[1,1,0]], []]}",
     "t.yaml: floor.control_points[1]: expected a row of 3 points [x, y, z], got a list of 2 items"},
    {"floor: {type: biquadratic, control_points: [[[0,0,0],[0,1,0],[0,2,0]], [[1,0,0],[1,1,0],[1,2]], []]}",
     "t.yaml: floor.control_points[1][2]: expected a list of 3 numbers, got a list of 2 items"},
    // a list where a map is expected, and the reverse
    {"floor: [1, 2, 3]", "t.yaml: floor: expected a map, got a list"},
    {"balls:\n  - [0, 0, 0]", "t.yaml: balls[0]: expected a map, got a list"},
    {"balls: {position: [0, 0, 0], radius: 1}", "t.yaml: balls: expected a list, got a map"},
    {"random_balls: {count: 1, region: [0, 1]}", "t.yaml: random_balls.region: expected a map, got a list"},
    // missing required keys
    {"balls:\n  - {position: [0, 0, 0], radius: 1}\n  - {position: [1, 0, 0], radius: 1}\n  - {position: [2, 0, 0]}",
     "t.yaml: balls[2].radius: required"},
    {"balls: [{radius: 1}]", "t.yaml: balls[0].position: required"},
    {"walls: [{point: [0, 0, 0], u: [1, 0, 0], v: [0, 0, 1]}, {point: [0, 0, 0], u: [1, 0, 0]}]",
     "t.yaml: walls[1].v: required"},
    {"floor: {type: biquadratic}", "t.yaml: floor.control_points: required"},
    {"random_balls: {seed: 3}", "t.yaml: random_balls.count: required"},
    {"random_balls: {count: 1, region: {min: [0, 0]}}", "t.yaml: random_balls.region.max: required"},
    {"pockets: [{position: [0, 0]}]", "t.yaml: pockets[0].radius: required"},
    {"pockets: [{position: [0, 0, 0], radius: 0.1}]",
     "t.yaml: pockets[0].position: expected a list of 2 numbers [x, y], got a list of 3 items"},
    {"pockets: [{position: [0, 0], radius: 0.1, depth: 1}]",
     "t.yaml: pockets[0].depth: unknown key (expected one of: position, radius)"},
    {"pockets: {position: [0, 0], radius: 0.1}", "t.yaml: pockets: expected a list, got a map"},
    // not a scene at all
    {"", "t.yaml: the scene must be a YAML map, got an empty document"},
    {"# only a comment\n", "t.yaml: the scene must be a YAML map, got an empty document"},
    {"- dt: 1\n- dt: 2\n", "t.yaml: the scene must be a YAML map, got a list"},
    {"hello", "t.yaml: the scene must be a YAML map, got hello"},
    {"dt: 1\n---\ndt: 2\n", "t.yaml: expected one YAML document, found more"},
    {"[1, 2]: 3", "t.yaml: keys must be names, got a list as a key"},
  };
  for (const ErrorCase& c : cases)
  {
    SCOPED_TRACE(c.yaml);
    const std::string message = errorOf(c.yaml);
    EXPECT_EQ(message, c.message);
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

TEST(SceneYaml, MalformedYamlGivesTheLineAndColumn)
{
  const std::string message = errorOf("dt: 0.01\nballs:\n  - {position: [0, 0, 0.1, radius: 0.1}\n");
  EXPECT_TRUE(startsWith(message, "t.yaml:3:")) << message;
  // "t.yaml:3:COLUMN: what yaml-cpp says"
  const std::size_t colon = message.find(':', std::string("t.yaml:3:").size());
  ASSERT_NE(colon, std::string::npos) << message;
  EXPECT_GT(message.size(), colon + 2) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);

  EXPECT_TRUE(startsWith(errorOf("a: b: c"), "t.yaml:1:")) << errorOf("a: b: c");
  EXPECT_TRUE(startsWith(errorOf("dt: 1\nwalls:\n\t- 1\n"), "t.yaml:3:")) << errorOf("dt: 1\nwalls:\n\t- 1\n");
}

TEST(SceneYaml, TheDefaultSourceNameIsString)
{
  try
  {
    parseScene("dt: x");
    FAIL() << "no error";
  }
  catch (const SceneError& e)
  {
    EXPECT_EQ(std::string(e.what()), "<string>: dt: expected a number, got x");
  }
}

TEST(SceneYamlFile, MissingFile)
{
  const std::string path = kDataDir + "/no_such_file.yaml";
  EXPECT_EQ(errorOfLoad(loadSceneFile, path), path + ": cannot open file (No such file or directory)");
  EXPECT_EQ(errorOfLoad(loadValidScene, path), path + ": cannot open file (No such file or directory)");
}

TEST(SceneYamlFile, DirectoryIsNotAFile)
{
  EXPECT_TRUE(startsWith(errorOfLoad(loadSceneFile, kDataDir), kDataDir + ": cannot ")) << errorOfLoad(loadSceneFile, kDataDir);
}

TEST(SceneYamlFile, EmptyFile)
{
  const std::string path = kDataDir + "/empty.yaml";
  EXPECT_EQ(errorOfLoad(loadSceneFile, path), path + ": the scene must be a YAML map, got an empty document");
}

TEST(SceneYamlFile, ListInsteadOfAMap)
{
  const std::string path = kDataDir + "/bad_top_level_list.yaml";
  EXPECT_EQ(errorOfLoad(loadSceneFile, path), path + ": the scene must be a YAML map, got a list");
}

TEST(SceneYamlFile, MalformedFileNamesItsLine)
{
  const std::string path = kDataDir + "/bad_malformed.yaml";
  EXPECT_TRUE(startsWith(errorOfLoad(loadSceneFile, path), path + ":4:")) << errorOfLoad(loadSceneFile, path);
}

TEST(SceneYamlFile, ParseErrorsComeBeforeValidation)
{
  const std::string path = kDataDir + "/bad_unknown_key.yaml";
  EXPECT_EQ(errorOfLoad(loadValidScene, path),
            path + ": balls[0].radus: unknown key (expected one of: position, velocity, radius, mass, angular_velocity, inertia, placement)");
  const std::string wrong_type = kDataDir + "/bad_wrong_type.yaml";
  EXPECT_EQ(errorOfLoad(loadValidScene, wrong_type), wrong_type + ": walls[0].u: expected a list of 3 numbers, got 2");
}

TEST(SceneYamlFile, LoadValidSceneReportsValidateIssuesWithTheKey)
{
  // The reasons are the core's words; only the key prefix is this reader's contract.
  const std::vector<std::pair<std::string, std::string>> cases{
    {"bad_negative_radius.yaml", "balls[0].radius: "},
    {"bad_nan.yaml", "balls[0].position"},
    {"bad_parallel_wall.yaml", "walls[0]."},
    {"bad_overlap.yaml", "balls[1]"},
    {"bad_off_floor.yaml", "balls[0].position"},
  };
  for (const auto& [file, key] : cases)
  {
    SCOPED_TRACE(file);
    const std::string path = kDataDir + "/" + file;
    EXPECT_NO_THROW(loadSceneFile(path));  // the reader itself does not validate
    const std::string message = errorOfLoad(loadValidScene, path);
    EXPECT_TRUE(startsWith(message, path + ": " + key)) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

std::vector<std::filesystem::path> configFiles()
{
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigDir))
  {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml")
    {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A click adds the scene's most common ball (by radius and mass) unless the scene sets
// click_radius or click_mass: pool balls on a pool table, not the 0.1 m default.
TEST(SceneYamlFile, ClicksAddTheScenesMostCommonBall)
{
  const std::string balls = "floor: {}\nballs:\n"
                            "  - {position: [0.0, 0, 0], radius: 0.03, mass: 0.2}\n"
                            "  - {position: [0.2, 0, 0], radius: 0.028575, mass: 0.17}\n"
                            "  - {position: [0.4, 0, 0], radius: 0.028575, mass: 0.17}\n"
                            "  - {position: [0.6, 0, 0], radius: 0.028575, mass: 0.17}\n";
  auto file = parseSceneFile(balls);
  EXPECT_EQ(file.node.click_radius, 0.028575);
  EXPECT_EQ(file.node.click_mass, 0.17);
  file = parseSceneFile(balls + "click_radius: 0.05\n");
  EXPECT_EQ(file.node.click_radius, 0.05);
  EXPECT_EQ(file.node.click_mass, 0.17);
  file = parseSceneFile("floor: {}\nrandom_balls: {count: 5, radius: [0.02, 0.04], mass: [1, 3]}");
  EXPECT_DOUBLE_EQ(file.node.click_radius, 0.03);
  EXPECT_DOUBLE_EQ(file.node.click_mass, 2.0);
  file = parseSceneFile("floor: {}");
  EXPECT_EQ(file.node.click_radius, 0.1);
  EXPECT_EQ(file.node.click_mass, 1.0);
  // (the pool table: its object balls)
  const auto pool = ball_collision_sim::yaml::loadValidSceneFile(kConfigDir + "/billiards.yaml");
  const auto& last = pool.scene.balls.back();
  EXPECT_EQ(pool.node.click_radius, last.radius);
  EXPECT_EQ(pool.node.click_mass, last.mass);
  EXPECT_LT(pool.node.click_radius, 0.05);
}

TEST(ConfigScenes, EveryConfigFileLoadsValidatesAndRuns)
{
  const std::vector<std::filesystem::path> files = configFiles();
  std::set<std::string> names;
  for (const auto& file : files)
  {
    names.insert(file.stem().string());
  }
  for (const char* expected : {"default", "billiards", "bowl", "newtons_cradle", "random_gas"})
  {
    EXPECT_EQ(names.count(expected), 1u) << "config/" << expected << ".yaml is missing";
  }

  for (const auto& file : files)
  {
    SCOPED_TRACE(file.string());
    Scene scene;
    try
    {
      scene = loadValidScene(file.string());
    }
    catch (const SceneError& e)
    {
      ADD_FAILURE() << e.what();
      continue;
    }
    // The scene builds a world that runs a few steps without losing a ball.
    ball_collision_sim::core::World world(scene);
    const std::size_t ball_count = world.balls().size();
    EXPECT_GT(ball_count, 0u);
    for (int i = 0; i < 10; ++i)
    {
      world.step();
    }
    EXPECT_EQ(world.balls().size(), ball_count);
    EXPECT_EQ(world.lostBalls(), 0);
    EXPECT_TRUE(std::isfinite(world.energy().total()));
  }
}

TEST(ConfigScenes, DefaultIsTheSeedsDemo)
{
  const Scene scene = loadValidScene(kConfigDir + "/default.yaml");
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->type, FloorDef::Type::kBiquadratic);
  // Not flat: the centre control point is off the plane of the corners.
  EXPECT_NE(scene.floor->control_points[1][1].z(), scene.floor->control_points[0][0].z());
  EXPECT_EQ(scene.walls.size(), 4u);
  ASSERT_EQ(scene.balls.size(), 12u);
  std::set<double> radii;
  for (const auto& ball : scene.balls)
  {
    EXPECT_GE(ball.radius, 0.05);
    EXPECT_LE(ball.radius, 0.2);
    radii.insert(ball.radius);
  }
  EXPECT_GE(radii.size(), 4u);
}

TEST(ConfigScenes, BilliardsRackLeavesAGap)
{
  const Scene scene = loadValidScene(kConfigDir + "/billiards.yaml");
  ASSERT_EQ(scene.balls.size(), 16u);
  EXPECT_EQ(scene.restitution, 0.95);
  // six cushions, open at the pockets, around the 2.54 m x 1.27 m playing surface
  ASSERT_EQ(scene.walls.size(), 6u);
  ball_collision_sim::core::Vec3 lo = scene.walls[0].point, hi = lo;
  for (const auto& wall : scene.walls)
    for (const auto& corner : {wall.point, ball_collision_sim::core::Vec3(wall.point + wall.u)})
    {
      lo = lo.cwiseMin(corner);
      hi = hi.cwiseMax(corner);
    }
  EXPECT_NEAR(hi.x() - lo.x(), 2.54, 1e-12);
  EXPECT_NEAR(hi.y() - lo.y(), 1.27, 1e-12);
  ASSERT_EQ(scene.pockets.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_EQ(scene.pockets[k].radius, k < 4 ? 0.062 : 0.0645) << "pocket " << k;
  ASSERT_TRUE(scene.floor.has_value());
  for (const auto& ball : scene.balls)
  {
    EXPECT_EQ(ball.radius, 0.028575);
    EXPECT_EQ(ball.mass, 0.170097);
  }
  for (const auto& wall : scene.walls)
    EXPECT_EQ(wall.restitution, 0.85);
  ASSERT_TRUE(scene.friction.has_value());
  EXPECT_EQ(scene.friction->sliding, 0.2);
  EXPECT_EQ(scene.friction->rolling, 0.01);
  EXPECT_EQ(scene.friction->spinning, 0.044);
  EXPECT_NEAR(scene.balls[0].velocity.norm(), 8.0, 1e-12);
  for (std::size_t i = 1; i < scene.balls.size(); ++i)
  {
    for (std::size_t j = i + 1; j < scene.balls.size(); ++j)
    {
      const double gap = (scene.balls[i].position - scene.balls[j].position).norm() - 2 * 0.028575;
      EXPECT_GE(gap, 1e-6 - 1e-12) << "balls " << i << " and " << j;
    }
  }
}

// The break on the pool table with friction: every ball slides, rolls and stops within
// 30 s, with the energy (spins' included) never rising in a step and no ball lost; at
// least one drops into a pocket, its centre then on the pocket's circle.
TEST(ConfigScenes, BilliardsBreakComesToRest)
{
  using ball_collision_sim::core::MotionKind;
  using ball_collision_sim::core::World;
  World world(loadValidScene(kConfigDir + "/billiards.yaml"));
  double energy = world.energy().total();
  double rise = 0;
  bool all_still = false;
  std::set<MotionKind> seen;
  std::size_t pocketed = 0;
  const auto& pockets = world.scene().pockets;
  for (int step = 0; step < 15000 && !all_still; ++step)
  {
    world.step();
    for (const auto& dropped : world.lastPocketed())
    {
      ++pocketed;
      const auto& pocket = pockets.at(static_cast<std::size_t>(dropped.pocket));
      const double off = (dropped.ball.position.head<2>() - pocket.position).norm();
      EXPECT_NEAR(off, pocket.radius, 1e-12) << "ball " << dropped.ball.id;
    }
    const double now = world.energy().total();
    rise = std::max(rise, now - energy);
    energy = now;
    all_still = true;
    for (std::size_t k = 0; k < world.balls().size(); ++k)
    {
      seen.insert(world.motionKind(k));
      all_still = all_still && world.motionKind(k) == MotionKind::kStationary;
    }
  }
  EXPECT_TRUE(all_still);
  EXPECT_GE(pocketed, 1u);
  EXPECT_EQ(world.balls().size() + pocketed, 16u);
  EXPECT_LE(rise, 1e-13);
  EXPECT_EQ(world.energy().kinetic + world.energy().rotational, 0.0);
  EXPECT_EQ(world.lostBalls(), 0);
  EXPECT_EQ(seen.count(MotionKind::kSliding), 1u);
  EXPECT_EQ(seen.count(MotionKind::kRolling), 1u);
}

TEST(ConfigScenes, NewtonsCradleBallsTouchExactly)
{
  const Scene scene = loadValidScene(kConfigDir + "/newtons_cradle.yaml");
  ASSERT_EQ(scene.balls.size(), 6u);
  // balls[1..5] are the row; each touches the next.
  for (std::size_t i = 1; i + 1 < scene.balls.size(); ++i)
  {
    const auto& a = scene.balls[i];
    const auto& b = scene.balls[i + 1];
    EXPECT_EQ(a.radius, b.radius);
    const double distance = (a.position - b.position).norm();
    EXPECT_GE(distance, a.radius + b.radius - 1e-9);
    EXPECT_LE(distance, a.radius + b.radius + 1e-9);
  }
}

TEST(ConfigScenes, RandomGasPlacesAllItsBalls)
{
  const Scene scene = loadValidScene(kConfigDir + "/random_gas.yaml");
  ASSERT_TRUE(scene.random_balls.has_value());
  EXPECT_EQ(scene.random_balls->count, 200);
  EXPECT_EQ(ball_collision_sim::core::placeRandomBalls(scene).size(), 200u);
}
}  // namespace

// The scene written out reads back to the same scene (the same world, to the bit), with
// every default spelled out and each real in its shortest exact form.
TEST(SceneWriter, WritesWhatReadsBackToTheSameBits)
{
  using ball_collision_sim::core::World;
  using ball_collision_sim::yaml::writeScene;
  std::vector<std::string> paths;
  for (const std::filesystem::path& config : configFiles())  // (the scenes: not config/*.rviz)
    paths.push_back(config.string());
  paths.push_back(kDataDir + "/node_scene.yaml");
  paths.push_back(kDataDir + "/good_small.yaml");
  for (const std::string& path : paths)
  {
    const auto file = ball_collision_sim::yaml::loadValidSceneFile(path);
    const std::string text = writeScene(file.scene, file.node);
    const auto again = parseSceneFile(text, path + " (written)");
    EXPECT_EQ(writeScene(again.scene, again.node), text) << path;
    EXPECT_EQ(World(again.scene).stateHash(), World(file.scene).stateHash()) << path;
    EXPECT_EQ(again.scene.restitution, file.scene.restitution) << path;
    EXPECT_EQ(again.node.real_time_factor, file.node.real_time_factor) << path;
    EXPECT_EQ(again.node.max_balls, file.node.max_balls) << path;
    EXPECT_EQ(again.scene.walls.size(), file.scene.walls.size()) << path;
  }
  Scene odd;
  odd.dt = 0.1 + 0.2;  // 0.30000000000000004: 17 digits are the shortest here
  odd.restitution = 0.15;
  odd.gravity = Vec3(1e-7, -3, 2.5e20);
  odd.frame_id = "map \"x\"";
  ball_collision_sim::NodeSettings node;
  node.frame_prefix = "";
  const std::string text = writeScene(odd, node);
  EXPECT_NE(text.find("dt: 0.30000000000000004\n"), std::string::npos) << text;
  EXPECT_NE(text.find("restitution: 0.15\n"), std::string::npos) << text;
  // reals stay reals for YAML 1.1 readers (rosparam): a point, and a signed exponent
  EXPECT_NE(text.find("gravity: [1.0e-07, -3.0, 2.5e+20]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("frame_prefix: \"\"\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("placement"), std::string::npos) << "on_floor is the default, not written\n" << text;
  const auto back = parseSceneFile(text);
  EXPECT_EQ(back.scene.dt, odd.dt);
  EXPECT_EQ(back.scene.gravity, odd.gravity);
  EXPECT_EQ(back.scene.frame_id, odd.frame_id);
  EXPECT_EQ(back.node.frame_prefix, "");
  EXPECT_FALSE(back.node.publish_clock.has_value());
}

// Flight's fields are written only where they differ from the default, and read back equal.
TEST(SceneWriter, WritesFloorRestitutionAndAsGivenPlacement)
{
  using ball_collision_sim::core::BallDef;
  using ball_collision_sim::core::BallPlacement;
  using ball_collision_sim::yaml::writeScene;
  for (const FloorDef::Type type : {FloorDef::Type::kPlane, FloorDef::Type::kBiquadratic})
  {
    SCOPED_TRACE(type == FloorDef::Type::kPlane ? "plane" : "biquadratic");
    Scene scene;
    scene.floor = FloorDef();
    scene.floor->type = type;
    scene.floor->restitution = 0.35;
    BallDef resting;
    resting.position = Vec3(0.5, 0, 0.1);
    BallDef thrown;
    thrown.position = Vec3(-0.5, 0.25, 0.75);
    thrown.velocity = Vec3(1, 0, 2.5);
    thrown.placement = BallPlacement::kAsGiven;
    scene.balls = {resting, thrown};
    const std::string text = writeScene(scene, ball_collision_sim::NodeSettings());
    EXPECT_NE(text.find("  restitution: 0.35\n"), std::string::npos) << text;
    EXPECT_NE(text.find("placement: as_given}"), std::string::npos) << text;
    EXPECT_EQ(text.find("on_floor"), std::string::npos) << text;
    const Scene back = parseScene(text, "written");
    ASSERT_TRUE(back.floor.has_value());
    EXPECT_EQ(back.floor->type, type);
    EXPECT_EQ(back.floor->restitution, scene.floor->restitution);
    ASSERT_EQ(back.balls.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i)
    {
      EXPECT_EQ(back.balls[i].placement, scene.balls[i].placement) << i;
      EXPECT_EQ(back.balls[i].position, scene.balls[i].position) << i;
      EXPECT_EQ(back.balls[i].velocity, scene.balls[i].velocity) << i;
    }
    EXPECT_EQ(writeScene(back, ball_collision_sim::NodeSettings()), text);
  }
  // unset stays unset: no floor restitution is written
  Scene plain;
  plain.floor = FloorDef();
  const std::string text = writeScene(plain, ball_collision_sim::NodeSettings());
  EXPECT_EQ(text.find("  restitution:"), std::string::npos) << text;
  EXPECT_FALSE(parseScene(text).floor->restitution.has_value());
}
