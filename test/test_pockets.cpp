// Pockets against closed forms: a ball on a line, frictionless or rolling against
// rolling resistance, drops at the time its centre crosses the pocket's circle (straight
// in, and off centre by b: the chord's near end at D - sqrt(r^2 - b^2)); one passing
// beside the circle keeps rolling; a ball right behind another rolls through the place
// where the first dropped and drops at its own time; a ball in flight passes over a pocket
// and drops where it lands inside one; a ball that pushed on one that drops rolls on
// without it; and scenes with bad pockets are refused by key.
#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;

PocketDef pocket(double x, double y, double radius)
{
  PocketDef p;
  p.position = Vec2(x, y);
  p.radius = radius;
  return p;
}

/// Steps until `t`, gathering what dropped on the way.
std::vector<PocketedBall> runUntil(World& world, double t)
{
  std::vector<PocketedBall> out;
  while (world.time() < t - 1e-9)
  {
    world.step();
    out.insert(out.end(), world.lastPocketed().begin(), world.lastPocketed().end());
  }
  return out;
}

/// Where a centre at distance `along` from a pocket's centre line, `beside` off it,
/// first meets the circle: the near end of the chord.
double chordEntry(double along, double beside, double radius)
{
  return along - std::sqrt(radius * radius - beside * beside);
}
}  // namespace

// Frictionless, at 1.5 m/s toward a pocket 1.2 m ahead of radius 0.06, straight in and
// 0.04 m off its centre line: it drops at s / v, and its last state is the one there.
TEST(Pockets, LineDropsWhereItsCentreCrossesTheCircle)
{
  for (const double beside : {0.0, 0.04})
  {
    Scene scene = flatScene();
    scene.pockets = {pocket(-1.5, 1.5, 0.05), pocket(1.0, beside, 0.06)};
    scene.balls = {ball(-0.2, 0.0, 1.5, 0.0), ball(-1.0, -1.0, 0.0, 0.0)};
    World world(scene);
    const double t = chordEntry(1.2, beside, 0.06) / 1.5;
    const std::vector<PocketedBall> dropped = runUntil(world, 1.0);
    ASSERT_EQ(dropped.size(), 1u);
    const PocketedBall& out = dropped[0];
    EXPECT_NEAR(out.time, t, 1e-14) << "b = " << beside;
    EXPECT_EQ(out.pocket, 1);
    EXPECT_EQ(out.ball.id, 1);
    EXPECT_NEAR(out.ball.position.x(), 1.0 - std::sqrt(0.06 * 0.06 - beside * beside), 1e-14);
    EXPECT_NEAR(out.ball.position.y(), 0.0, 1e-15);
    EXPECT_NEAR(Vec2(out.ball.position.x() - 1.0, out.ball.position.y() - beside).norm(), 0.06, 1e-14);
    EXPECT_EQ(out.ball.velocity, Vec3(1.5, 0.0, 0.0));
    EXPECT_EQ(out.motion, MotionKind::kRolling);
    // it left the world; the other ball is still there, and no ball is lost
    ASSERT_EQ(world.balls().size(), 1u);
    EXPECT_EQ(world.balls()[0].id, 2);
    EXPECT_EQ(world.stats().pocketed_balls, 1u);
    EXPECT_EQ(world.lostBalls(), 0);
  }
}

// Passing 0.061 m beside a pocket of radius 0.06, the centre never crosses the circle.
TEST(Pockets, PassingBesideTheCircleKeepsRolling)
{
  Scene scene = flatScene();
  scene.pockets = {pocket(0.5, 0.061, 0.06)};
  scene.balls = {ball(-0.5, 0.0, 1.0, 0.0)};
  World world(scene);
  EXPECT_TRUE(runUntil(world, 1.2).empty());
  ASSERT_EQ(world.balls().size(), 1u);
  EXPECT_NEAR(world.balls()[0].position.x(), 0.7, 1e-12);
}

// Rolling on cloth (mu_r = 0.01): s(t) = v0 t - mu_r g t^2 / 2, so the centre reaches
// the circle at t = 2 s / (v0 + sqrt(v0^2 - 2 mu_r g s)); its speed there is v0 - mu_r g t.
TEST(Pockets, RollingBallDropsAtTheTimeItsDecelerationGives)
{
  Scene scene = flatScene();
  scene.friction = friction(0.2, 0.01, 0.044);
  scene.pockets = {pocket(1.5, 0.03, 0.062)};
  BallDef b = ball(-0.5, 0.0, 1.2, 0.0, 0.028575, 0.170097);
  scene.balls = {b};  // (rolling: its spin is rolling's by default)
  World world(scene);
  const double a = 0.01 * kG, s = chordEntry(2.0, 0.03, 0.062), v0 = 1.2;
  const double t = 2 * s / (v0 + std::sqrt(v0 * v0 - 2 * a * s));
  const std::vector<PocketedBall> dropped = runUntil(world, 3.0);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_NEAR(dropped[0].time, t, 1e-13);
  EXPECT_NEAR(dropped[0].ball.velocity.x(), v0 - a * t, 1e-13);
  EXPECT_EQ(dropped[0].motion, MotionKind::kRolling);
  // rolling: w = n x v / r
  EXPECT_NEAR((dropped[0].angular_velocity - Vec3::UnitZ().cross(dropped[0].ball.velocity) / b.radius).norm(), 0.0,
              1e-12);
  EXPECT_TRUE(world.balls().empty());
}

// Two balls in a line, 0.21 m apart (centres) at the same speed: the first drops 0.0025 s
// into a step of 0.01 s, and the second reaches where it dropped 0.005 s later, in the
// same step; it meets nothing there and drops 0.21 / v after the first.
TEST(Pockets, NothingMeetsADroppedBall)
{
  Scene scene = flatScene();
  scene.pockets = {pocket(1.205, 0.0, 0.2)};
  scene.balls = {ball(0.0, 0.0, 2.0, 0.0), ball(-0.21, 0.0, 2.0, 0.0)};
  World world(scene);
  std::vector<PocketedBall> dropped;
  for (int k = 0; k < 100; ++k)
  {
    world.step();
    EXPECT_TRUE(world.lastEvents().empty()) << "an impact at step " << k;
    dropped.insert(dropped.end(), world.lastPocketed().begin(), world.lastPocketed().end());
  }
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_NEAR(dropped[0].time, 1.005 / 2.0, 1e-14);
  EXPECT_NEAR(dropped[1].time, 1.215 / 2.0, 1e-14);
  EXPECT_EQ(dropped[1].ball.id, 2);
}

// A ball in flight passes over a pocket; one that lands inside a pocket's circle drops
// where it lands, at t = sqrt(2 h / g) (h the centre's height above its resting height).
TEST(Pockets, FlightPassesOverAndDropsWhereItLands)
{
  for (const double pocket_x : {0.2, 0.45})
  {
    Scene scene = flatScene();
    scene.floor->restitution = 0.0;
    scene.pockets = {pocket(pocket_x, 0.0, 0.1)};
    BallDef b = ball(0.0, 0.0, 2.0, 0.0);
    b.position.z() = 0.1 + 0.2;
    b.placement = BallPlacement::kAsGiven;
    scene.balls = {b};
    World world(scene);
    const double t_land = std::sqrt(2 * 0.2 / kG), x_land = 2.0 * t_land;  // x_land = 0.404
    // (over the pocket at 0.2, then rolling on away from it; into the one at 0.45)
    const std::vector<PocketedBall> dropped = runUntil(world, 1.0);
    if (pocket_x + 0.1 < x_land)
    {
      EXPECT_TRUE(dropped.empty()) << "over the pocket at " << pocket_x;
      continue;
    }
    ASSERT_EQ(dropped.size(), 1u) << "the pocket at " << pocket_x;
    EXPECT_GT(x_land, pocket_x - 0.1);  // (it lands inside the circle)
    EXPECT_NEAR(dropped[0].time, t_land, 1e-12);
    EXPECT_NEAR(dropped[0].ball.position.x(), x_land, 1e-12);
  }
}

// Down a 10 degree slope with friction, a solid ball rolls behind a hollow one, touching
// it: the hollow one rolls slower alone (g sin / (1 + k), k = 2/3 against 2/5), so the
// solid one pushes it and the two roll as one group. The hollow one drops into a pocket;
// the solid one rolls on without it, never held back, at g sin cos / (1 + 2/5) along x,
// and drops too. Nothing overlaps and no energy is made.
TEST(Pockets, ABallThatPushedADroppedOneGoesOn)
{
  const double slope = 10 * M_PI / 180;
  Scene scene;
  FloorDef f;
  f.point = Vec3(-1, -1, 0);
  f.u = Vec3(2, 0, -2 * std::tan(slope));  // downhill along +x
  f.v = Vec3(0, 2, 0);
  scene.floor = f;
  scene.friction = friction(0.3, 0.0);
  for (const double x : {0.0, -0.2 - 1e-12})
  {
    BallDef b = ball(x, 0.0, 0.0, 0.0);
    b.position.z() = -(x + 1) * std::tan(slope) + 0.102;  // (onto the slope)
    b.inertia = x == 0.0 ? kHollowInertia : kSolidInertia;
    scene.balls.push_back(b);
  }
  scene.pockets = {pocket(0.8, 0.0, 0.1)};
  World world(scene);
  // (the energy of the balls still there never grows: of both, then of the one left)
  double before = world.energy().total();
  std::vector<PocketedBall> dropped;
  std::uint64_t resting = 0;
  double speed = 0.0;
  for (int k = 0; k < 300 && !world.balls().empty(); ++k)
  {
    const std::size_t count = world.balls().size();
    world.step();
    if (const Ball* solid = world.findBall(2))
    {
      // (once it has caught up with the hollow one, and pushes it)
      if (resting > 0)
      {
        EXPECT_GE(solid->velocity.x(), speed) << "ball 2 held back at step " << k;
      }
      if (count == 1)
      {
        EXPECT_NEAR(solid->velocity.x() - speed, 0.01 * kG * std::sin(slope) * std::cos(slope) / 1.4, 1e-12);
      }
      speed = solid->velocity.x();
    }
    const double now = world.energy().total();
    if (world.balls().size() == count)
    {
      EXPECT_LE(now, before + 1e-12) << "step " << k;
    }
    before = now;
    if (world.balls().size() == 2)
    {
      resting = world.stats().resting_contacts;
      EXPECT_GE((world.balls()[0].position - world.balls()[1].position).norm(), 0.2 - 1e-9);
    }
    dropped.insert(dropped.end(), world.lastPocketed().begin(), world.lastPocketed().end());
  }
  EXPECT_GT(resting, 0u) << "the two balls never pushed on each other";
  EXPECT_TRUE(world.balls().empty());
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_EQ(dropped[0].ball.id, 1);
  EXPECT_LT(dropped[0].time, dropped[1].time);
}

// Pockets need a floor under their centres and a radius > 0; each fault names its key.
TEST(Pockets, BadPocketsAreRefusedByKey)
{
  Scene scene = flatScene();
  scene.pockets = {pocket(0.0, 0.0, 0.0), pocket(3.0, 0.0, 0.1), pocket(0.0, std::nan(""), 0.1)};
  const std::vector<SceneIssue> issues = validate(scene);
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].key, "pockets[0].radius");
  EXPECT_EQ(issues[1].key, "pockets[1].position");
  EXPECT_NE(issues[1].reason.find("over the floor"), std::string::npos) << issues[1].reason;
  EXPECT_EQ(issues[2].key, "pockets[2].position");
  Scene floorless = scene;
  floorless.floor.reset();
  floorless.pockets = {pocket(0.0, 0.0, 0.1)};
  const std::vector<SceneIssue> none = validate(floorless);
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].key, "pockets");
}
