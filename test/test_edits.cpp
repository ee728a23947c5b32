// Edits of a running world as the node's services make them: where a ball lands, setting
// a ball's state, pushing it, balls that leave the world, and the ids objects get.
#include "fixtures.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace ball_collision_sim::test;
using ball_collision_sim::core::AddResult;
using ball_collision_sim::core::Ball;
using ball_collision_sim::core::BallEdit;
using ball_collision_sim::core::kFirstId;
using ball_collision_sim::core::Landing;
using ball_collision_sim::core::Vec2;
using ball_collision_sim::core::World;

namespace
{
/// The bowl z = a (x^2 + y^2) of fixtures' bowl(4, 0.5): a = 4 h / L^2.
constexpr double kBowlA = 4 * 0.5 / 16;

/// An edit that moves a ball to `position` with `velocity`, its spin rolling's.
BallEdit moveTo(const Vec3& position, const Vec3& velocity)
{
  BallEdit edit;
  edit.position = position;
  edit.velocity = velocity;
  return edit;
}

/// Distance from p to the paraboloid z = a (x^2 + y^2), by Newton's method on the foot's
/// radius in the plane through the axis and p (the foot lies in it).
double distanceToBowl(const Vec3& p)
{
  const double rho = std::hypot(p.x(), p.y());
  double s = rho;  // the foot's distance from the axis
  for (int it = 0; it < 100; ++it)
  {
    // d/ds of |(s, a s^2) - (rho, z)|^2 / 2 = (s - rho) + (a s^2 - z) 2 a s
    const double f = (s - rho) + (kBowlA * s * s - p.z()) * 2 * kBowlA * s;
    const double df = 1 + 2 * kBowlA * (3 * kBowlA * s * s - p.z());
    s -= f / df;
  }
  return std::hypot(s - rho, kBowlA * s * s - p.z());
}
}  // namespace

// add_ball's landing: the centre keeps its place across gravity and goes to one radius
// above the floor, whether it was given far above the floor, on it or below it.
TEST(Landing, UnderThePointOnACurvedFloorWhateverTheHeight)
{
  Scene scene;
  scene.floor = bowl(4, 0.5);
  World world(scene);
  for (const double z : {-3.0, -0.2, 0.0, 0.1, 0.37, 5.0})
    for (const Vec2& at : {Vec2(0, 0), Vec2(1.3, -0.4), Vec2(-1.7, 1.1)})
    {
      BallDef def = ball(at.x(), at.y(), 0.3, 0.2, 0.15);
      def.position.z() = z;
      const AddResult added = world.addBall(def, Landing::kUnder);
      ASSERT_TRUE(added.ok) << added.error << " at z = " << z;
      const Ball& b = *world.findBall(added.id);
      EXPECT_NEAR(b.position.x(), at.x(), 1e-12) << z;
      EXPECT_NEAR(b.position.y(), at.y(), 1e-12) << z;
      EXPECT_NEAR(distanceToBowl(b.position), 0.15, 1e-12) << z;
      EXPECT_GT(b.position.z(), kBowlA * at.squaredNorm()) << z;  // above the floor, not under it
      ASSERT_TRUE(world.removeBall(added.id));
    }
}

// On a tilted plane the centre goes along gravity to the plane's offset: a closed form.
TEST(Landing, UnderThePointOnATiltedPlane)
{
  Scene scene;
  FloorDef f;
  f.point = Vec3(-2, -2, 0);
  f.u = Vec3(4, 0, -1);  // falls 1 m over 4 m along +x
  f.v = Vec3(0, 4, 0);
  scene.floor = f;
  World world(scene);
  const Vec3 n = f.u.cross(f.v).normalized();
  const double r = 0.2;
  BallDef def = ball(0.5, 0.3, 1, 0, r);
  def.position.z() = 7;
  const AddResult added = world.addBall(def, Landing::kUnder);
  ASSERT_TRUE(added.ok) << added.error;
  const Ball& b = *world.findBall(added.id);
  // plane height under x is -(x + 2) / 4, and the centre is r / n.z above it
  EXPECT_NEAR(b.position.z(), -(0.5 + 2) / 4 + r / n.z(), 1e-14);
  EXPECT_NEAR(b.position.x(), 0.5, 1e-15);
  EXPECT_NEAR(b.position.y(), 0.3, 1e-15);
  EXPECT_NEAR(b.velocity.dot(n), 0, 1e-15);  // its velocity is along the floor
}

// AS_GIVEN (kExact) takes a centre only where it already rests; the scene's rule
// (kNearest) refuses a centre more than 2 r above the floor; both change nothing then.
TEST(Landing, ExactAndNearestRefuseACentreAboveTheFloor)
{
  Scene scene = flatScene();
  World world(scene);
  const std::uint64_t before = world.stateHash();
  BallDef high = ball(0.5, 0.5, 0, 0, 0.1);
  high.position.z() = 0.35;
  for (const Landing landing : {Landing::kExact, Landing::kNearest})
  {
    const AddResult refused = world.addBall(high, landing);
    EXPECT_FALSE(refused.ok);
    EXPECT_EQ(refused.error.rfind("position: ", 0), 0u) << refused.error;
    EXPECT_EQ(world.stateHash(), before);
  }
  EXPECT_TRUE(world.addBall(high, Landing::kUnder).ok);
  BallDef resting = ball(-0.5, 0.5, 0, 0, 0.1);
  const AddResult exact = world.addBall(resting, Landing::kExact);
  ASSERT_TRUE(exact.ok) << exact.error;
  EXPECT_EQ(world.findBall(exact.id)->position, resting.position);
  BallDef off = ball(3, 0.5, 0, 0, 0.1);
  const AddResult outside = world.addBall(off, Landing::kUnder);
  EXPECT_FALSE(outside.ok);
  EXPECT_NE(outside.error.find("off the floor"), std::string::npos) << outside.error;
}

// Ids start at 1 (0, what an empty request field holds, names nothing), for balls and
// walls alike, and are never given twice.
TEST(Ids, StartAtOneAndOnlyGrow)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(-1, 0, 0, 0), ball(1, 0, 0, 0)};
  World world(scene);
  EXPECT_EQ(kFirstId, 1);
  EXPECT_EQ(world.balls()[0].id, 1);
  EXPECT_EQ(world.balls()[1].id, 2);
  EXPECT_EQ(world.walls()[0].id, 1);
  EXPECT_EQ(world.walls()[3].id, 4);
  EXPECT_FALSE(world.removeBall(0));
  EXPECT_FALSE(world.removeWall(0));
  ASSERT_TRUE(world.removeBall(2));
  EXPECT_EQ(world.addBall(ball(0, 1, 0, 0)).id, 3);
  world.reset();
  EXPECT_EQ(world.balls()[1].id, 2);
  EXPECT_EQ(world.addBall(ball(0, 1, 0, 0)).id, 3);
}

// set_ball_state: the ball keeps its id, radius, mass and turn, and moves on from its
// new state at once: it meets a wall at the time the closed form gives.
TEST(SetBallState, KeepsTheBallAndRunsFromTheNewState)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(-1, 0, 0.3, 0.2, 0.1, 2.0), ball(1, 1, 0, 0, 0.2, 3.0)};
  World world(scene);
  for (int k = 0; k < 10; ++k)
    world.step();
  const Ball before = *world.findBall(1);
  // to (0.5, -1), 1.5 m/s toward the south wall at y = -2 (z given wrong: it lands)
  const AddResult set = world.setBallState(1, moveTo(Vec3(0.5, -1, 3), Vec3(0, -1.5, 0.7)));
  ASSERT_TRUE(set.ok) << set.error;
  const Ball& b = *world.findBall(1);
  EXPECT_EQ(b.id, 1);
  EXPECT_EQ(b.radius, before.radius);
  EXPECT_EQ(b.mass, before.mass);
  EXPECT_EQ(b.orientation.coeffs(), before.orientation.coeffs());
  EXPECT_EQ(b.position, Vec3(0.5, -1, 0.1));
  EXPECT_EQ(b.velocity, Vec3(0, -1.5, 0));
  EXPECT_EQ(world.balls().size(), 2u);
  const double t0 = world.time();
  std::vector<ball_collision_sim::core::CollisionEvent> events;
  while (events.empty())
  {
    world.step();
    events = world.lastEvents();
  }
  EXPECT_EQ(events[0].ball, 1);
  EXPECT_EQ(events[0].other, 1);  // wall 1, the south one
  EXPECT_NEAR(events[0].time, t0 + (1 - 0.1) / 1.5, 1e-12);
}

// A refused set changes nothing: no such ball, an overlap with another ball or a wall,
// off the floor, bad numbers. Moving a ball onto part of where it is now is allowed.
TEST(SetBallState, RefusedChangesNothing)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(-1, 0, 0.3, 0.2, 0.1), ball(1, 1, 0, 0, 0.2)};
  World world(scene);
  world.step();
  const std::uint64_t before = world.stateHash();
  struct Case
  {
    int id;
    Vec3 position, velocity;
    const char* key;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Case cases[] = {
      {7, Vec3(0, 0, 0.1), Vec3::Zero(), "id"},
      {0, Vec3(0, 0, 0.1), Vec3::Zero(), "id"},
      {1, Vec3(1.1, 1.1, 0.1), Vec3::Zero(), "position"},  // overlaps ball 2
      {1, Vec3(1.95, 0, 0.1), Vec3::Zero(), "position"},   // overlaps wall 4
      {1, Vec3(2.5, 0, 0.1), Vec3::Zero(), "position"},    // off the floor
      {1, Vec3(nan, 0, 0.1), Vec3::Zero(), "position"},
      {1, Vec3(0, 0, 0.1), Vec3(1e9, 0, 0), "velocity"},
  };
  for (const Case& c : cases)
  {
    const AddResult result = world.setBallState(c.id, moveTo(c.position, c.velocity));
    EXPECT_FALSE(result.ok) << c.key;
    EXPECT_EQ(result.error.rfind(c.key, 0), 0u) << result.error;
    EXPECT_EQ(world.stateHash(), before) << c.key;
  }
  const Vec3 at = world.findBall(1)->position;
  EXPECT_TRUE(world.setBallState(1, moveTo(at + Vec3(0.05, 0, 0), Vec3::Zero())).ok);
}

// What an edit leaves out the ball keeps, bit for bit: its place (on the floor, and in
// flight, where the default placement must not drop it onto the floor), its velocity, and
// with friction its spin where its velocity is kept; a new velocity without a spin rolls.
TEST(SetBallState, WhatTheEditLeavesOutIsKept)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.friction = friction(0.2, 0.01);
  BallDef spun = ball(-1, 0, 0.3, 0.2, 0.1, 2.0);
  spun.angular_velocity = Vec3(1, -2, 3);
  scene.balls = {spun, ball(1, 1, 0, 0, 0.2, 3.0)};
  World world(scene);
  world.step();
  const Ball at = *world.findBall(1);
  const Vec3 spin = world.angularVelocity(0);
  ASSERT_NE(spin, Vec3::Zero());

  BallEdit faster;
  faster.velocity = Vec3(0.5, -0.25, 0.75);  // (its part off the floor is dropped)
  ASSERT_TRUE(world.setBallState(1, faster).ok);
  EXPECT_EQ(world.findBall(1)->position, at.position);
  EXPECT_EQ(world.findBall(1)->velocity, Vec3(0.5, -0.25, 0));
  EXPECT_NEAR((world.angularVelocity(0) - Vec3(0, 0, 1).cross(Vec3(0.5, -0.25, 0)) / 0.1).norm(), 0, 1e-13);

  BallEdit spin_only;
  spin_only.angular_velocity = spin;
  ASSERT_TRUE(world.setBallState(1, spin_only).ok);
  EXPECT_EQ(world.findBall(1)->position, at.position);
  EXPECT_EQ(world.findBall(1)->velocity, Vec3(0.5, -0.25, 0));
  EXPECT_EQ(world.angularVelocity(0), spin);

  BallEdit moved;
  moved.position = Vec3(0.5, -1, 0.7);
  ASSERT_TRUE(world.setBallState(1, moved).ok);
  EXPECT_EQ(world.findBall(1)->position, Vec3(0.5, -1, 0.1));
  EXPECT_EQ(world.findBall(1)->velocity, Vec3(0.5, -0.25, 0));
  EXPECT_EQ(world.angularVelocity(0), spin);
  EXPECT_EQ(world.inertia(0), ball_collision_sim::core::kSolidInertia);

  BallEdit hollow;
  hollow.inertia = 2.0 / 3;
  ASSERT_TRUE(world.setBallState(1, hollow).ok);
  EXPECT_EQ(world.inertia(0), 2.0 / 3);
  EXPECT_EQ(world.findBall(1)->position, Vec3(0.5, -1, 0.1));
  EXPECT_EQ(world.angularVelocity(0), spin);

  // in flight, a new velocity under the default placement: it stays up there and flies on
  BallDef high = ball(0, 1, 0, 0);
  high.position.z() = 0.4;
  const AddResult up = world.addBall(high, Landing::kAsGiven);
  ASSERT_TRUE(up.ok) << up.error;
  BallEdit thrown;
  thrown.velocity = Vec3(0.1, 0, 0.5);
  ASSERT_TRUE(world.setBallState(up.id, thrown).ok);
  EXPECT_EQ(world.findBall(up.id)->position, high.position);
  EXPECT_EQ(world.findBall(up.id)->velocity, Vec3(0.1, 0, 0.5));
  EXPECT_TRUE(world.findBall(up.id)->flying());
}

// A k so small that k m r^2 is a denormal (1 / I infinite) is refused, nothing changed:
// set on a sliding, spinning ball with friction it made the spin NaN at the next step.
// The least k taken keeps every number finite.
TEST(SetBallState, InertiaTooSmallForItsBallIsRefused)
{
  Scene scene = flatScene(-1.5, 1.5, -0.75, 0.75);
  scene.friction = friction(0.2, 0.01, 0.044);
  BallDef spinning = ball(0.2, -0.4, 0, 1, 0.05, 0.17);
  spinning.angular_velocity = Vec3(0, 0, 30);
  scene.balls = {spinning};
  World world(scene);
  const std::uint64_t before = world.stateHash();
  BallEdit tiny;
  tiny.inertia = std::numeric_limits<double>::min();
  const AddResult refused = world.setBallState(1, tiny);
  EXPECT_FALSE(refused.ok);
  EXPECT_EQ(refused.error.rfind("inertia: ", 0), 0u) << refused.error;
  EXPECT_EQ(world.stateHash(), before);
  BallEdit least;
  least.inertia = ball_collision_sim::core::kMinInertia;
  ASSERT_TRUE(world.setBallState(1, least).ok);
  for (int k = 0; k < 100; ++k)
  {
    world.step();
    ASSERT_TRUE(world.angularVelocity(0).allFinite() && world.balls()[0].velocity.allFinite()) << "step " << k;
  }
}

// apply_impulse: dv = J / m exactly; on a floor that does not bounce (floor.restitution
// 0) the part into the floor goes into it, and momentum changes by the impulse along the
// floor; refused without a ball or a finite impulse. On one that bounces (e = 1), the
// ball comes back off the floor as fast as it was pressed into it, and flies.
TEST(ApplyImpulse, ChangesTheVelocityByImpulseOverMass)
{
  Scene scene = flatScene();
  scene.balls = {ball(-1, 0, 0.3, 0.2, 0.1, 2.5)};
  {
    World bouncy(scene);
    bouncy.step();
    const Vec3 v0 = bouncy.findBall(1)->velocity;
    ASSERT_TRUE(bouncy.applyImpulse(1, Vec3(1.0, -0.5, -4.0)).ok);
    EXPECT_TRUE(bouncy.findBall(1)->flying());
    EXPECT_NEAR((bouncy.findBall(1)->velocity - (v0 + Vec3(0.4, -0.2, 1.6))).norm(), 0, 1e-15);
  }
  scene.floor->restitution = 0.0;
  World world(scene);
  world.step();
  const Vec3 p0 = world.momentum();
  const Vec3 v0 = world.findBall(1)->velocity;
  const AddResult pushed = world.applyImpulse(1, Vec3(1.0, -0.5, -4.0));
  ASSERT_TRUE(pushed.ok) << pushed.error;
  EXPECT_NEAR((world.findBall(1)->velocity - (v0 + Vec3(0.4, -0.2, 0))).norm(), 0, 1e-15);
  EXPECT_NEAR((world.momentum() - p0 - Vec3(1.0, -0.5, 0)).norm(), 0, 1e-15);
  const std::uint64_t before = world.stateHash();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& [id, impulse] : {std::pair{2, Vec3(1, 0, 0)}, std::pair{0, Vec3(1, 0, 0)},
                                    std::pair{1, Vec3(inf, 0, 0)}, std::pair{1, Vec3(1e300, 0, 0)}})
  {
    const AddResult refused = world.applyImpulse(id, impulse);
    EXPECT_FALSE(refused.ok);
    EXPECT_TRUE(refused.error.rfind("id", 0) == 0 || refused.error.rfind("impulse", 0) == 0) << refused.error;
    EXPECT_EQ(world.stateHash(), before);
  }
  // the ball then moves with the new velocity: 10 steps of 0.01 s later
  const Vec3 start = world.findBall(1)->position, v = world.findBall(1)->velocity;
  for (int k = 0; k < 10; ++k)
    world.step();
  EXPECT_NEAR((world.findBall(1)->position - (start + 0.1 * v)).norm(), 0, 1e-12);
}

// A ball that rolls off the floor (its wall removed) falls from its edge and is taken out
// at the step its centre is its radius below the floor, once, with the others untouched;
// without a floor, the walls' bounds.
TEST(LostBalls, LeavingTheFloorIsFoundOnceAndTakenOut)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(1.0, 0, 2.0, 0), ball(-1, 1, 0, 0.1), ball(0, -1, 0.2, 0)};
  World world(scene);
  ASSERT_TRUE(world.removeWall(4));  // the east wall at x = 2
  std::vector<ball_collision_sim::core::LostBall> lost;
  int found_at = -1;
  for (int k = 1; k <= 100; ++k)
  {
    world.step();
    for (auto& gone : world.removeLostBalls())
    {
      lost.push_back(gone);
      found_at = k;
    }
  }
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].ball.id, 1);
  EXPECT_NE(lost[0].reason.find("left the floor"), std::string::npos) << lost[0].reason;
  // its foot passes x = 2 at t = 0.5 s and it falls off the floor: its centre is r below
  // the floor's lowest point (z = 0) sqrt(4 r / g) = 0.2019 s later, found at the end of
  // step 71 (x = 2.42)
  EXPECT_NE(lost[0].reason.find("fell past its edge"), std::string::npos) << lost[0].reason;
  EXPECT_EQ(found_at, 71);
  EXPECT_NEAR(lost[0].ball.position.x(), 1.0 + 2.0 * 0.71, 1e-12);
  EXPECT_NEAR(lost[0].ball.position.z(), 0.1 - 0.5 * 9.81 * 0.21 * 0.21, 1e-12);
  EXPECT_EQ(lost[0].motion, ball_collision_sim::core::MotionKind::kFlying);
  EXPECT_EQ(world.balls().size(), 2u);
  EXPECT_EQ(world.balls()[0].id, 2);
  EXPECT_NEAR(world.findBall(2)->position.y(), 1 + 0.1, 1e-12);
  EXPECT_EQ(world.lostBalls(), 0);

  Scene open;  // no floor, no gravity: a box of walls with a side missing
  open.gravity = Vec3::Zero();
  addBox(open, -1, 1, -1, 1);
  open.walls.pop_back();
  open.balls = {ball(0, 0, 1, 0), ball(0, 0.5, 0, 0)};
  World free(open);
  std::size_t gone = 0;
  for (int k = 0; k < 200; ++k)
  {
    free.step();
    gone += free.removeLostBalls().size();
  }
  EXPECT_EQ(gone, 1u);
  EXPECT_EQ(free.balls().size(), 1u);
  EXPECT_EQ(free.balls()[0].id, 2);
}
