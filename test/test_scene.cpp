#include "fixtures.hpp"

#include "ball_collision_sim/core/format.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
/// The issues' keys, in order.
std::vector<std::string> keys(const Scene& scene)
{
  std::vector<std::string> out;
  for (const SceneIssue& issue : validate(scene))
    out.push_back(issue.key);
  return out;
}
}  // namespace

TEST(Validate, GoodSceneHasNoIssues)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(0, 0, 1, 0), ball(0.2, 0, 0, 0)};  // touching is fine
  EXPECT_TRUE(validate(scene).empty()) << joinIssues(validate(scene));
}

TEST(Validate, EveryProblemWithItsKey)
{
  Scene scene = flatScene();
  scene.dt = 0;
  scene.restitution = 1.5;
  scene.gravity.x() = std::numeric_limits<double>::infinity();
  scene.walls = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), {}}, {Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 1, 0), {}}};
  BallDef nan_pos = ball(0, 0, 0, 0);
  nan_pos.position.y() = std::nan("");
  BallDef neg = ball(1, 1, 0, 0);
  neg.radius = -0.1;
  neg.mass = 0;
  scene.balls = {nan_pos, neg};
  const std::vector<std::string> expected = {"dt",         "gravity",          "restitution",     "walls[0].v",
                                             "walls[1].u", "balls[0].position", "balls[1].radius", "balls[1].mass"};
  EXPECT_EQ(keys(scene), expected) << joinIssues(validate(scene));
  for (const SceneIssue& issue : validate(scene))
    EXPECT_FALSE(issue.reason.empty());
}

TEST(Validate, GeometryProblems)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(0, 0, 0, 0), ball(0.15, 0, 0, 0), ball(3, 0, 0, 0), ball(1.95, 0, 0, 0)};
  const auto issues = validate(scene);
  ASSERT_EQ(issues.size(), 3u) << joinIssues(issues);
  EXPECT_EQ(issues[0].key, "balls[2].position");
  EXPECT_NE(issues[0].reason.find("off the floor"), std::string::npos);
  EXPECT_EQ(issues[1].key, "balls[3]");
  EXPECT_NE(issues[1].reason.find("overlaps walls[3]"), std::string::npos);
  EXPECT_EQ(issues[2].key, "balls[1]");
  EXPECT_NE(issues[2].reason.find("overlaps balls[0]"), std::string::npos);
}

TEST(Validate, BallFloatingAboveOrSunkInTheFloor)
{
  Scene scene = flatScene();
  BallDef high = ball(0, 0, 0, 0);
  high.position.z() = 5;
  BallDef low = ball(1, 1, 0, 0);
  low.position.z() = -0.05;
  scene.balls = {high, low};
  EXPECT_EQ(keys(scene), (std::vector<std::string>{"balls[0].position", "balls[1].position"}));
}

TEST(Validate, DegenerateBiquadraticFloor)
{
  Scene scene;
  FloorDef f;
  f.type = FloorDef::Type::kBiquadratic;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(i, 0, j);  // all in one line along x? no: the x-z plane, fine
  scene.floor = f;
  EXPECT_TRUE(validate(scene).empty()) << joinIssues(validate(scene));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(i + j, 0, 0);  // a line: no normal anywhere
  scene.floor = f;
  EXPECT_EQ(keys(scene), std::vector<std::string>{"floor.control_points"});
}

TEST(RandomBalls, PlacedClearDeterministicAndInsideTheRegion)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(0, 0, 0, 0, 0.3)};
  RandomBallsDef rb;
  rb.count = 400;
  rb.seed = 9;
  rb.radius = {0.03, 0.06};
  rb.speed = {1, 2};
  rb.region = RandomBallsDef::Region{Vec2(-1.5, -1.5), Vec2(1.5, 0.5)};
  scene.random_balls = rb;
  ASSERT_TRUE(validate(scene).empty()) << joinIssues(validate(scene));
  const std::vector<BallDef> a = placeRandomBalls(scene), b = placeRandomBalls(scene);
  ASSERT_EQ(a.size(), 400u);
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(a[k].position, b[k].position);
    EXPECT_GE(a[k].position.x(), -1.5);
    EXPECT_LE(a[k].position.y(), 0.5);
    EXPECT_NEAR(a[k].position.z(), a[k].radius, 1e-15);
    EXPECT_GE(a[k].velocity.norm(), 1 - 1e-12);
    EXPECT_LE(a[k].velocity.norm(), 2 + 1e-12);
    EXPECT_GE(a[k].radius, 0.03);
  }
  World world(scene);
  EXPECT_LT(deepestOverlap(world.balls()), 0);
  scene.random_balls->count = 5000;  // no room
  EXPECT_EQ(keys(scene), std::vector<std::string>{"random_balls.count"});
}

// check() gives the balls as the world starts them: explicit, then random, each on the
// floor with its foot point; a world built from them is the world built from the scene,
// and so is the world after a reset (which places them again from the scene).
TEST(Check, PlacesEveryBallOnceForTheWorld)
{
  Scene scene;
  scene.floor = bowl(4, 0.5);
  scene.balls = {ball(0.5, 0.2, 0.3, 0), ball(-0.8, 0.4, 0, 0.2)};
  scene.balls[0].position.z() = 0.2;
  scene.balls[1].position.z() = 0.3;
  scene.random_balls = randomBalls(40, 9, {0.05, 0.1}, {1, 2}, {0, 1});
  const SceneCheck checked = check(scene);
  ASSERT_TRUE(checked.issues.empty()) << joinIssues(checked.issues);
  ASSERT_EQ(checked.balls.size(), 42u);
  const Floor floor(*scene.floor, scene.gravity);
  ASSERT_EQ(checked.balls.feet.size(), 42u);
  for (std::size_t k = 0; k < checked.balls.size(); ++k)
  {
    // its centre one radius above its foot point, along the normal there
    const Ball& b = checked.balls.balls[k];
    const Vec2& foot = checked.balls.feet[k];
    const Vec3 centre = floor.point(foot) + b.radius * floor.normal(foot);
    EXPECT_LT((b.position - centre).norm(), 1e-12);
  }
  // the scene's own balls first, as the scene gives them but put on the floor
  EXPECT_EQ(checked.balls.balls[0].radius, scene.balls[0].radius);
  EXPECT_EQ(checked.balls.balls[1].mass, scene.balls[1].mass);
  World from_check(scene, check(scene)), from_scene(scene);
  EXPECT_EQ(from_check.stateHash(), from_scene.stateHash());
  for (int k = 0; k < 50; ++k)
  {
    from_check.step();
    from_scene.step();
  }
  EXPECT_EQ(from_check.stateHash(), from_scene.stateHash());
  from_check.reset();
  EXPECT_EQ(from_check.stateHash(), World(scene).stateHash());
  // a check with issues builds no world
  Scene bad = scene;
  bad.balls[0].radius = -1;
  const SceneCheck refused = check(bad);
  EXPECT_FALSE(refused.issues.empty());
  EXPECT_TRUE(refused.balls.empty());
  EXPECT_THROW(World(bad, refused), std::invalid_argument);
}

// With friction a world keeps each ball's own spin and moment of inertia: an explicit
// ball's from its definition, a random ball's from random_balls (no spin of its own:
// rolling; random_balls.inertia). The placed records carry neither, so the world takes
// them from the scene by the records' order; the rotational energy weighs each ball's
// spin by its own inertia.
TEST(Check, GivesEachBallItsOwnSpinAndInertiaWithFriction)
{
  Scene scene = flatScene();
  scene.friction = FrictionDef{0.2, 0.01, 0.05, 0, 0};
  BallDef spinning = ball(-1.5, -1.5, 0.3, 0);
  spinning.angular_velocity = Vec3(2, -1, 7);
  spinning.inertia = 2.0 / 3;  // hollow
  scene.balls = {spinning, ball(1.5, 1.5, 0, -0.4, 0.15, 3)};
  scene.random_balls = randomBalls(30, 4, {0.05, 0.1}, {0.5, 2}, {0.5, 2});
  scene.random_balls->inertia = 0.5;
  const World world(scene);
  ASSERT_EQ(world.balls().size(), 32u);
  EXPECT_EQ(world.angularVelocity(0), Vec3(2, -1, 7));
  double rotational = 0, of_random = 0;
  for (std::size_t k = 0; k < world.balls().size(); ++k)
  {
    const Ball& b = world.balls()[k];
    const Vec3 w = world.angularVelocity(k);
    if (k > 0)  // rolling without slip on the level floor
    {
      EXPECT_LT((w - Vec3::UnitZ().cross(b.velocity) / b.radius).norm(), 1e-12 * (1 + w.norm())) << k;
    }
    const double inertia = k == 0 ? 2.0 / 3 : k == 1 ? kSolidInertia : 0.5;
    const double e = 0.5 * inertia * b.mass * b.radius * b.radius * w.squaredNorm();
    rotational += e;
    of_random += k > 1 ? e : 0.0;
  }
  EXPECT_NEAR(world.energy().rotational, rotational, 1e-12 * rotational);
  // (the random balls move, so their inertia counts: a tenth of the total here or more)
  EXPECT_GT(of_random, 0.1 * rotational);
}

// Messages print numbers in their shortest round-trip form: each reads back to the same
// double, and one significant digit fewer would not (over 20,000 random doubles of every
// magnitude); NaN is "nan" whatever its sign bit.
TEST(FormatNumber, ShortestThatReadsBackTheSame)
{
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(formatNumber(137 * 0.001), "0.137");
  EXPECT_EQ(formatNumber(1e300), "1e+300");
  EXPECT_EQ(formatNumber(-2.5), "-2.5");
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::infinity()), "-inf");
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20000; ++trial)
  {
    double x = 0;
    do
    {
      const std::uint64_t bits = rng();
      std::memcpy(&x, &bits, sizeof x);
    } while (!std::isfinite(x));
    const std::string text = formatNumber(x);
    ASSERT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
    // (its significant digits, and whether one fewer still reads back)
    const std::string mantissa = text.substr(0, text.find_first_of("eE"));
    const std::size_t first = mantissa.find_first_not_of("-0.");
    int digits = 0;
    for (std::size_t k = first; k < mantissa.size(); ++k)
      digits += mantissa[k] >= '0' && mantissa[k] <= '9';
    // (a whole number is written out in full where that is the shorter text: its trailing
    // digits are the number's, not more precision)
    if (digits > 1 && text.find_first_of(".e") != std::string::npos)
    {
      char shorter[400];
      std::snprintf(shorter, sizeof shorter, "%.*e", digits - 2, x);
      EXPECT_NE(std::strtod(shorter, nullptr), x) << text << " reads back from " << shorter;
    }
  }
}
