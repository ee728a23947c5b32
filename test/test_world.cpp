#include "fixtures.hpp"

#include <gtest/gtest.h>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
std::vector<CollisionEvent> runCollecting(World& world, int steps)
{
  std::vector<CollisionEvent> all;
  for (int k = 0; k < steps; ++k)
  {
    world.step();
    all.insert(all.end(), world.lastEvents().begin(), world.lastEvents().end());
  }
  return all;
}
}  // namespace

// One ball runs into a row of four at rest, all touching: the momentum passes down the
// row in one instant and only the last ball leaves, at the first one's speed.
TEST(NewtonsCradle, OneInOneOut)
{
  Scene scene = flatScene(-2, 3, -1, 1);
  scene.balls = {ball(-0.3, 0, 1, 0), ball(0, 0, 0, 0), ball(0.2, 0, 0, 0), ball(0.4, 0, 0, 0), ball(0.6, 0, 0, 0)};
  World world(scene);
  const auto events = runCollecting(world, 50);
  ASSERT_EQ(events.size(), 4u);
  for (std::size_t k = 0; k < events.size(); ++k)
  {
    EXPECT_NEAR(events[k].time, 0.1, 1e-12);
    EXPECT_EQ(events[k].ball, static_cast<int>(k) + 1);  // ids start at 1
    EXPECT_EQ(events[k].other, static_cast<int>(k) + 2);
  }
  for (int i = 0; i < 4; ++i)
    EXPECT_LT(world.balls()[i].velocity.norm(), 1e-12) << i;
  EXPECT_NEAR(world.balls()[4].velocity.x(), 1, 1e-12);
}

// Two touching balls come in: two leave.
TEST(NewtonsCradle, TwoInTwoOut)
{
  Scene scene = flatScene(-2, 3, -1, 1);
  scene.balls = {ball(-0.5, 0, 1, 0), ball(-0.3, 0, 1, 0), ball(0, 0, 0, 0), ball(0.2, 0, 0, 0), ball(0.4, 0, 0, 0)};
  World world(scene);
  const double e0 = world.energy().kinetic;
  runCollecting(world, 50);
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(world.balls()[i].velocity.norm(), 1e-12) << i;
  EXPECT_NEAR(world.balls()[3].velocity.x(), 1, 1e-12);
  EXPECT_NEAR(world.balls()[4].velocity.x(), 1, 1e-12);
  EXPECT_NEAR(world.energy().kinetic, e0, 1e-14);
}

// 10^4 m/s between walls 2 m apart for 10 s: about 55,600 bounces, none missed.
TEST(FastBall, NeverTunnels)
{
  Scene scene = flatScene(-1, 1, -0.5, 0.5);
  addBox(scene, -1, 1, -0.5, 0.5);
  const double speed = 1e4, r = 0.1;
  scene.balls = {ball(0, 0, speed, 0, r)};
  World world(scene);
  std::uint64_t events = 0;
  for (int k = 0; k < 1000; ++k)
  {
    world.step();
    events += world.lastEvents().size();
    const Vec3& p = world.balls()[0].position;
    ASSERT_LE(std::abs(p.x()), 1 - r + 1e-9) << "step " << k;
    ASSERT_LE(std::abs(p.y()), 0.5 - r + 1e-9) << "step " << k;
  }
  // first impact after 0.9 m, then one every 1.8 m
  const double expected = std::floor((speed * world.time() - 0.9) / 1.8) + 1;
  EXPECT_NEAR(static_cast<double>(events), expected, 1.0);
  EXPECT_NEAR(world.balls()[0].velocity.norm(), speed, 1e-9 * speed);
  EXPECT_EQ(world.lostBalls(), 0);
}

TEST(FastBall, DiagonalInABoxStaysInside)
{
  Scene scene = flatScene(-1, 1, -1, 1);
  addBox(scene, -1, 1, -1, 1);
  scene.balls = {ball(0, 0, 7000, 3000, 0.05), ball(0.5, 0.5, -2000, 9000, 0.07, 3)};
  World world(scene);
  const double e0 = world.energy().kinetic;
  for (int k = 0; k < 1000; ++k)
  {
    world.step();
    for (const Ball& b : world.balls())
      ASSERT_LE(b.position.head<2>().cwiseAbs().maxCoeff(), 1 - b.radius + 1e-9) << k;
    ASSERT_LT(deepestOverlap(world.balls()), 1e-9);
  }
  EXPECT_NEAR(world.energy().kinetic, e0, 1e-9 * e0);
}

// A wall x = 0 from y = -0.5 to 0.5: a ball passing just beyond its end hits the
// vertical edge and leaves along the reflection about the radial normal.
TEST(WallFeatures, VerticalEdge)
{
  Scene scene = flatScene(-2, 2, -2, 2);
  scene.walls = {{Vec3(0, -0.5, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.5), {}}};
  const double r = 0.1, off = 0.05;
  scene.balls = {ball(-1, 0.5 + off, 2, 0, r)};
  World world(scene);
  const auto events = runCollecting(world, 100);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].feature, WallFeature::kEdge);
  const double x_hit = -std::sqrt(r * r - off * off);
  EXPECT_NEAR(events[0].time, (x_hit + 1) / 2, 1e-12);
  const Vec3 n = Vec3(x_hit, off, 0) / r;  // from the edge toward the centre
  const Vec3 v_in(2, 0, 0);
  EXPECT_TRUE(world.balls()[0].velocity.isApprox(v_in - 2 * v_in.dot(n) * n, 1e-12));
}

// A low wall (0.05 m, below the centre of a 0.1 m ball): a ball beyond its end hits the
// top corner; on the floor only the horizontal part of the normal acts.
TEST(WallFeatures, CornerOfALowWall)
{
  Scene scene = flatScene(-2, 2, -2, 2);
  scene.walls = {{Vec3(0, -0.5, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.05), {}}};
  const double r = 0.1, off = 0.05;
  scene.balls = {ball(-1, 0.5 + off, 2, 0, r)};
  World world(scene);
  const double e0 = world.energy().total();
  const auto events = runCollecting(world, 100);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].feature, WallFeature::kCorner);
  // centre at height r, corner at (0, 0.5, 0.05): |c - corner| = r
  const double x_hit = -std::sqrt(r * r - off * off - (r - 0.05) * (r - 0.05));
  EXPECT_NEAR(events[0].time, (x_hit + 1) / 2, 1e-12);
  const Vec3 t = Vec3(x_hit, off, 0).normalized();
  const Vec3 v_in(2, 0, 0);
  EXPECT_TRUE(world.balls()[0].velocity.isApprox(v_in - 2 * v_in.dot(t) * t, 1e-12));
  EXPECT_NEAR(world.balls()[0].velocity.z(), 0, 1e-15);
  EXPECT_NEAR(world.energy().total(), e0, 1e-12 * e0);
}

TEST(WallFeatures, TopEdgeOfALowWall)
{
  Scene scene = flatScene(-2, 2, -2, 2);
  scene.walls = {{Vec3(0, -0.5, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.05), {}}};
  scene.balls = {ball(-1, 0, 2, 0.5)};
  World world(scene);
  const auto events = runCollecting(world, 100);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].feature, WallFeature::kEdge);
  EXPECT_TRUE(world.balls()[0].velocity.isApprox(Vec3(-2, 0.5, 0), 1e-12));
}

namespace
{
/// A plane tilted by theta, downhill along +x, with a wall across its lower end.
Scene slopeWithWall(double theta, double restitution)
{
  Scene scene;
  const double L = 4;
  FloorDef f;
  f.point = Vec3(0, -1, 0);
  f.u = Vec3(L * std::cos(theta), 0, -L * std::sin(theta));
  f.v = Vec3(0, 2, 0);
  scene.floor = f;
  scene.restitution = restitution;
  const Vec3 n = f.u.cross(f.v).normalized();
  const Vec3 foot = f.point + 0.9 * f.u;  // the wall stands at 90 % of the slope
  scene.walls = {{foot, f.v, 0.5 * n, {}}};
  return scene;
}
}  // namespace

// Free balls on a sloped plane follow their parabolas exactly, within a step too: a ball
// sliding down from rest meets a wall across the fall line at t = sqrt(2 (D - r) / g_t),
// at the speed g_t t (a chord across each step would be off by about g_t dt^2 / 8 in
// place, 1e-5 s in time).
TEST(Slope, ABallSlidingDownMeetsTheWallAtTheClosedFormTime)
{
  const double theta = 0.3, r = 0.1, distance = 1.0;
  Scene scene = slopeWithWall(theta, 1.0);
  const Vec3 down = scene.floor->u.normalized();
  const Vec3 n = scene.floor->u.cross(scene.floor->v).normalized();
  BallDef b;
  b.radius = r;
  b.position = scene.walls[0].point + Vec3(0, 1, 0) - distance * down + r * n;
  scene.balls.push_back(b);
  World world(scene);
  const double g_t = 9.81 * std::sin(theta);
  const double t_hit = std::sqrt(2 * (distance - r) / g_t);
  std::vector<CollisionEvent> hits;
  for (int k = 0; k < 200 && hits.empty(); ++k)
  {
    world.step();
    hits = world.lastEvents();
  }
  ASSERT_FALSE(hits.empty());
  EXPECT_EQ(hits[0].kind, CollisionEvent::Kind::kBallWall);
  EXPECT_NEAR(hits[0].time, t_hit, 1e-13);
  EXPECT_NEAR(hits[0].approach_speed, g_t * t_hit, 1e-12);
}

// A free ball on a slope (a parabola) meets a ball resting against the wall (held there:
// a chord) at the closed-form time: the quartic's case.
TEST(Slope, AFreeBallMeetsABallRestingOnTheWallAtTheClosedFormTime)
{
  const double theta = 0.3, r = 0.1, distance = 1.0;
  Scene scene = slopeWithWall(theta, 0.5);
  const Vec3 down = scene.floor->u.normalized();
  const Vec3 n = scene.floor->u.cross(scene.floor->v).normalized();
  BallDef resting, free;
  resting.radius = free.radius = r;
  resting.position = scene.walls[0].point + Vec3(0, 1, 0) - r * down + r * n;  // against the wall
  free.position = resting.position - distance * down;  // its centre 1 m uphill
  scene.balls = {resting, free};
  World world(scene);
  const double g_t = 9.81 * std::sin(theta);
  const double t_hit = std::sqrt(2 * (distance - 2 * r) / g_t);
  const CollisionEvent* hit = nullptr;
  std::vector<CollisionEvent> events;
  for (int k = 0; k < 200 && !hit; ++k)
  {
    world.step();
    events = world.lastEvents();
    for (const CollisionEvent& e : events)
      if (e.kind == CollisionEvent::Kind::kBallBall && !e.resting)
      {
        hit = &e;
        break;
      }
  }
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->time, t_hit, 1e-13);
  EXPECT_NEAR(hit->approach_speed, g_t * t_hit, 1e-12);
}

// Without a floor a ball flies on its parabola, and meets a wall where the parabola does.
TEST(NoFloor, AThrownBallMeetsAWallWhereItsParabolaDoes)
{
  Scene scene;
  scene.walls = {{Vec3(-5, -5, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), {}}};
  BallDef b;
  b.radius = 0.1;
  b.position = Vec3(0, 0, 1);
  b.velocity = Vec3(1, 0, 2);
  scene.balls.push_back(b);
  World world(scene);
  // 1 + 2 t - g t^2 / 2 = r
  const double g = 9.81, t_hit = (2 + std::sqrt(4 + 2 * g * (1 - 0.1))) / g;
  std::vector<CollisionEvent> hits;
  for (int k = 0; k < 200 && hits.empty(); ++k)
  {
    world.step();
    hits = world.lastEvents();
  }
  ASSERT_FALSE(hits.empty());
  EXPECT_NEAR(hits[0].time, t_hit, 1e-13);
  EXPECT_NEAR(hits[0].point.x(), t_hit, 1e-12);  // x = t
  EXPECT_NEAR(hits[0].approach_speed, g * t_hit - 2, 1e-12);
}

// Without a floor, balls that cross one another's track across the ground, one falling
// past the other's height, meet only where their centres come within the sum of their
// radii: the broad phase sets nothing aside by height (its boxes span the ground's two
// axes), and the exact test sets apart those that pass above one another. Two balls of
// 0.1 m thrown at each other at 2 m/s along x, 1 m apart, start at heights 0 and h: for
// h = 0 they meet (falling together) when 1 - 4 t = 0.2; for h = 0.5 never.
TEST(NoFloor, BallsMeetByTheirCentresNotByWhereTheyAreOverTheGround)
{
  for (const double h : {0.0, 0.5})
  {
    Scene scene;
    BallDef a, b;
    a.radius = b.radius = 0.1;
    a.position = Vec3(-0.5, 0, 5);
    a.velocity = Vec3(2, 0, 0);
    b.position = Vec3(0.5, 0, 5 + h);
    b.velocity = Vec3(-2, 0, 0);
    scene.balls = {a, b};
    World world(scene);
    std::vector<CollisionEvent> hits;
    for (int k = 0; k < 50 && hits.empty(); ++k)
    {
      world.step();
      hits = world.lastEvents();
    }
    if (h == 0)
    {
      ASSERT_EQ(hits.size(), 1u);
      EXPECT_NEAR(hits[0].time, 0.2, 1e-14);
      EXPECT_NEAR(hits[0].approach_speed, 4, 1e-12);
    }
    else
    {
      EXPECT_TRUE(hits.empty()) << "met at t = " << hits[0].time;
      EXPECT_EQ(world.stats().events, 0u);
    }
  }
}

// A ball leaning on a wall on a slope stays put: no jitter and at most one contact a step.
TEST(RestingContact, BallAgainstWallOnSlopeDoesNotJitter)
{
  const double theta = 0.4, r = 0.1;
  Scene scene = slopeWithWall(theta, 1.0);
  const Vec3 down = scene.floor->u.normalized();
  const Vec3 n = scene.floor->u.cross(scene.floor->v).normalized();
  BallDef b;
  b.radius = r;
  b.position = scene.walls[0].point + Vec3(0, 1, 0) - r * down + r * n;  // touching the wall
  scene.balls = {b};
  World world(scene);
  const Vec3 start = world.balls()[0].position;
  std::size_t most = 0;
  for (int k = 0; k < 1000; ++k)
  {
    world.step();
    most = std::max(most, world.lastEvents().size());
    ASSERT_LT((world.balls()[0].position - start).norm(), 1e-9) << "step " << k;
  }
  EXPECT_LE(most, 1u);
  EXPECT_LT(world.balls()[0].velocity.norm(), 1e-9);
}

// Released above the wall with some restitution, the ball bounces, settles, then rests.
TEST(RestingContact, BouncesDieOutThenRests)
{
  const double theta = 0.4, r = 0.1;
  Scene scene = slopeWithWall(theta, 0.5);
  const Vec3 down = scene.floor->u.normalized();
  const Vec3 n = scene.floor->u.cross(scene.floor->v).normalized();
  BallDef b;
  b.radius = r;
  b.position = scene.walls[0].point + Vec3(0, 1, 0) - 1.0 * down + r * n;
  scene.balls = {b};
  World world(scene);
  for (int k = 0; k < 1000; ++k)
    world.step();
  const double gap = (world.balls()[0].position - scene.walls[0].point).dot(-down) - r;
  EXPECT_NEAR(gap, 0, 1e-9);
  EXPECT_LT(world.balls()[0].velocity.norm(), 1e-9);
  std::size_t most = 0;
  for (int k = 0; k < 100; ++k)
  {
    world.step();
    most = std::max(most, world.lastEvents().size());
  }
  EXPECT_LE(most, 1u);
  EXPECT_GT(world.stats().resting_contacts, 0u);  // (it rests as a constraint, not by bounces)
}

// A row of three balls leaning on the wall, each on the next: the pile stays put and the
// contacts stay few (no endless chain of resting events).
TEST(RestingContact, PileOfThreeAgainstWallOnSlope)
{
  const double theta = 0.3, r = 0.1;
  Scene scene = slopeWithWall(theta, 1.0);
  const Vec3 down = scene.floor->u.normalized();
  const Vec3 n = scene.floor->u.cross(scene.floor->v).normalized();
  for (int k = 0; k < 3; ++k)
  {
    BallDef b;
    b.radius = r;
    b.mass = 1.0 + k;
    b.position = scene.walls[0].point + Vec3(0, 1, 0) - (1 + 2 * k) * r * down + r * n;
    scene.balls.push_back(b);
  }
  World world(scene);
  std::vector<Vec3> start;
  for (const Ball& b : world.balls())
    start.push_back(b.position);
  std::size_t most = 0;
  for (int k = 0; k < 1000; ++k)
  {
    world.step();
    most = std::max(most, world.lastEvents().size());
  }
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_LT((world.balls()[i].position - start[i]).norm(), 1e-9) << i;
  EXPECT_LE(most, 3u);  // one per contact
  EXPECT_EQ(world.stats().frozen_balls, 0u);
}

// Three equal balls at the bottom of the bowl (z = a (x^2 + y^2)), each pressed toward the
// axis by gravity along the floor and held off it by the other two: a jam of resting
// contacts. Placed a hair apart on a circle, they close in, touch, and rest where
// frictionless contacts hold them, the equilateral triangle of side 2 r around the
// axis: each centre 2 r / sqrt(3) from it. Then they sleep.
TEST(RestingContact, JamOfThreeInTheBowl)
{
  const double L = 4, h = 0.5, a = 4 * h / (L * L), r = 0.1;
  const double rho = 2 * r / std::sqrt(3.0);
  Scene scene;
  scene.floor = bowl(L, h);
  scene.restitution = 0.5;
  // the centre of a ball resting with its foot at horizontal distance f from the axis is
  // at f - r 2 a f / sqrt(1 + 4 a^2 f^2) from it: the foot for a centre a hair beyond rho
  const double centre = rho * (1 + 1e-7);
  double f = centre;
  for (int k = 0; k < 60; ++k)
    f = centre + r * 2 * a * f / std::sqrt(1 + 4 * a * a * f * f);
  const double z = a * f * f + r / std::sqrt(1 + 4 * a * a * f * f);
  for (int k = 0; k < 3; ++k)
  {
    const double phi = 2 * M_PI * k / 3 + 0.3;
    BallDef b;
    b.radius = r;
    b.position = Vec3(centre * std::cos(phi), centre * std::sin(phi), z);
    scene.balls.push_back(b);
  }
  World world(scene);
  const double rise = largestEnergyRise(world, 300);
  EXPECT_LT(rise, 1e-9 * std::abs(world.energy().total()) + 1e-12);
  for (const Ball& b : world.balls())
  {
    EXPECT_NEAR(std::hypot(b.position.x(), b.position.y()), rho, 1e-9) << b.id;
    EXPECT_LT(b.velocity.norm(), 1e-9) << b.id;
    EXPECT_TRUE(b.asleep()) << b.id;
  }
  const auto& b = world.balls();
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR((b[i].position - b[(i + 1) % 3].position).norm(), 2 * r, 1e-9) << i;
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_GT(world.stats().resting_contacts, 0u);
  // asleep: no events
  const std::uint64_t events = world.stats().events;
  world.step();
  EXPECT_EQ(world.stats().events, events);
}

// Two balls in a channel barely wider than both: many impacts per step, all kept.
TEST(Squeeze, TwoBallsBetweenCloseWalls)
{
  const double r = 0.1, gap = 0.004;
  const double width = 4 * r + 3 * gap;
  Scene scene = flatScene(0, width, -1, 1);
  scene.walls = {{Vec3(0, -1, 0), Vec3(0, 2, 0), Vec3(0, 0, 0.5), {}},
                 {Vec3(width, -1, 0), Vec3(0, 2, 0), Vec3(0, 0, 0.5), {}}};
  scene.balls = {ball(r + gap, 0, 1.3, 0), ball(3 * r + 2 * gap, 0, -0.7, 0, r, 2)};
  World world(scene);
  const double e0 = world.energy().kinetic;
  for (int k = 0; k < 1000; ++k)
  {
    world.step();
    const auto& b = world.balls();
    ASSERT_GE(b[0].position.x(), r - 1e-9);
    ASSERT_LE(b[1].position.x(), width - r + 1e-9);
    ASSERT_GE(b[1].position.x() - b[0].position.x(), 2 * r - 1e-9);
  }
  EXPECT_GT(world.stats().events, 1000u);
  EXPECT_NEAR(world.energy().kinetic, e0, 1e-12 * e0);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
}

namespace
{
Scene gas(std::uint64_t seed)
{
  Scene scene = flatScene(-2, 2, -2, 2);
  addBox(scene, -2, 2, -2, 2);
  scene.random_balls = randomBalls(300, seed, {0.04, 0.08}, {0.5, 2}, {0, 3});
  return scene;
}
}  // namespace

TEST(Determinism, SameSceneSameBits)
{
  World a(gas(11)), b(gas(11)), c(gas(12));
  EXPECT_EQ(a.stateHash(), b.stateHash());
  EXPECT_NE(a.stateHash(), c.stateHash());
  for (int k = 0; k < 300; ++k)
  {
    a.step();
    b.step();
  }
  EXPECT_GT(a.stats().events, 100u);
  EXPECT_EQ(a.stateHash(), b.stateHash());
  EXPECT_EQ(a.stats().events, b.stats().events);
  // the hash sees a change of one bit in one velocity
  World d(gas(11));
  for (int k = 0; k < 300; ++k)
    d.step();
  EXPECT_EQ(d.stateHash(), a.stateHash());
  d.reset();
  World fresh(gas(11));
  EXPECT_EQ(d.stateHash(), fresh.stateHash());
  // a copy taken between steps goes on as the original does
  World e(gas(11));
  for (int k = 0; k < 13; ++k)
    e.step();
  World f = e;
  for (int k = 0; k < 287; ++k)
  {
    e.step();
    f.step();
  }
  EXPECT_EQ(e.stateHash(), a.stateHash());
  EXPECT_EQ(f.stateHash(), a.stateHash());
}

// A copy of a settling pile taken between steps (resting contacts solved every step: the
// copy starts without the original's work space for them) goes on as the original does.
TEST(Determinism, ACopyOfASettlingPileGoesOnAsTheOriginal)
{
  World a(bowlPile(5));
  for (int k = 0; k < 40; ++k)
    a.step();
  ASSERT_GT(a.stats().resting_contacts, 0u);
  World b = a;
  World c(bowlPile(1));
  for (int k = 0; k < 40; ++k)
    c.step();
  c = a;  // (assigned over a world with a work space of its own)
  for (int k = 0; k < 200; ++k)
  {
    a.step();
    b.step();
    c.step();
  }
  EXPECT_GT(a.stats().resting_contacts, 1000u);
  EXPECT_EQ(b.stateHash(), a.stateHash());
  EXPECT_EQ(c.stateHash(), a.stateHash());
  EXPECT_EQ(b.stats().events, a.stats().events);
}

// Not recording the events changes nothing else: the same bits and the same counts, in
// a gas of many events, and a pile in a bowl (resting contacts); turned on
// again, the list is the step's events.
TEST(Determinism, EventsNotRecordedSameBits)
{
  for (const Scene& scene : {gas(11), bowlPile(5)})
  {
    World a(scene), b(scene);
    b.recordEvents(false);
    std::uint64_t listed = 0;
    for (int k = 0; k < 300; ++k)
    {
      a.step();
      b.step();
      listed += a.lastEvents().size();
      EXPECT_TRUE(b.lastEvents().empty());
    }
    EXPECT_GT(a.stats().events, 100u);
    EXPECT_EQ(listed, a.stats().events);
    EXPECT_EQ(a.stateHash(), b.stateHash());
    EXPECT_EQ(a.stats().events, b.stats().events);
    EXPECT_EQ(a.stats().resting_events, b.stats().resting_events);
    EXPECT_EQ(a.stats().resting_contacts, b.stats().resting_contacts);
    b.recordEvents(true);
    // (a few steps: the settled pile may go a step without an impact)
    for (int k = 0; k == 0 || (k < 20 && a.lastEvents().empty()); ++k)
    {
      a.step();
      b.step();
    }
    EXPECT_FALSE(b.lastEvents().empty());
    ASSERT_EQ(b.lastEvents().size(), a.lastEvents().size());
    for (std::size_t k = 0; k < a.lastEvents().size(); ++k)
    {
      EXPECT_EQ(a.lastEvents()[k].time, b.lastEvents()[k].time);
      EXPECT_EQ(a.lastEvents()[k].ball, b.lastEvents()[k].ball);
      EXPECT_EQ(a.lastEvents()[k].other, b.lastEvents()[k].other);
    }
    EXPECT_EQ(a.stateHash(), b.stateHash());
  }
}

// The step keeps the balls' records in its own (cell) order; balls() lists them in id
// order all the same, lookups by id find the right ball, and the records' order does not
// change a run: a copy whose records an edit put back in id order steps to the same bits.
TEST(Determinism, BallsInIdOrderWhateverTheRecordsOrder)
{
  World a(gas(11));
  for (int k = 0; k < 40; ++k)  // (the records are put in cell order every few steps)
    a.step();
  const BallList balls = a.balls();
  ASSERT_GT(balls.size(), 50u);
  double kinetic = 0;
  Vec3 momentum = Vec3::Zero();
  for (std::size_t k = 0; k < balls.size(); ++k)
  {
    if (k > 0)
    {
      EXPECT_LT(balls[k - 1].id, balls[k].id);
    }
    EXPECT_EQ(a.findBall(balls[k].id), &balls[k]);
    EXPECT_EQ(a.indexOf(balls[k].id), k);
    kinetic += 0.5 * balls[k].mass * balls[k].velocity.squaredNorm();
    momentum += balls[k].mass * balls[k].velocity;
  }
  EXPECT_EQ(a.indexOf(balls.back().id + 1), balls.size());
  EXPECT_EQ(a.findBall(balls.back().id + 1), nullptr);
  EXPECT_EQ(a.energy().kinetic, kinetic);  // summed in id order, bit for bit
  EXPECT_EQ(a.momentum(), momentum);
  // an impulse reaches its ball and no other
  const std::vector<Ball> before = balls.copy();
  const int id = before[17].id;
  ASSERT_TRUE(a.applyImpulse(id, Vec3(0.25, 0, 0)).ok);
  const std::vector<Ball> after = a.balls().copy();
  for (std::size_t k = 0; k < after.size(); ++k)
  {
    EXPECT_EQ(after[k].id, before[k].id);
    EXPECT_EQ(after[k].position, before[k].position);
    if (after[k].id == id)
    {
      EXPECT_NEAR((after[k].velocity - before[k].velocity).x(), 0.25 / before[k].mass, 1e-15);
    }
    else
    {
      EXPECT_EQ(after[k].velocity, before[k].velocity);
    }
  }
  // a zero impulse changes no velocity (on the level floor) but puts the copy's records
  // in id order; both go on alike
  World b(gas(11));
  for (int k = 0; k < 40; ++k)
    b.step();
  World c = b;
  ASSERT_TRUE(c.applyImpulse(c.balls()[0].id, Vec3::Zero()).ok);
  EXPECT_EQ(c.stateHash(), b.stateHash());
  for (int k = 0; k < 200; ++k)
  {
    b.step();
    c.step();
  }
  EXPECT_GT(b.stats().events, 500u);
  EXPECT_EQ(c.stateHash(), b.stateHash());
  // removing a ball keeps the others' order and records
  const std::vector<Ball> kept = b.balls().copy();
  ASSERT_TRUE(b.removeBall(kept[30].id));
  ASSERT_EQ(b.balls().size(), kept.size() - 1);
  for (std::size_t k = 0; k < b.balls().size(); ++k)
  {
    const Ball& expected = kept[k < 30 ? k : k + 1];
    EXPECT_EQ(b.balls()[k].id, expected.id);
    EXPECT_EQ(b.balls()[k].position, expected.position);
  }
}

TEST(Editing, RefusedAddChangesNothing)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(0, 0, 1, 0)};
  World world(scene);
  const std::uint64_t before = world.stateHash();

  struct Case
  {
    BallDef def;
    const char* key;
  };
  BallDef nan_ball = ball(0.5, 0.5, 0, 0);
  nan_ball.velocity.x() = std::nan("");
  BallDef zero_radius = ball(0.5, 0.5, 0, 0);
  zero_radius.radius = 0;
  BallDef neg_mass = ball(0.5, 0.5, 0, 0);
  neg_mass.mass = -1;
  BallDef huge = ball(0.5, 0.5, 0, 0);
  huge.radius = 1e300;
  const Case cases[] = {
      {nan_ball, "velocity"},         {zero_radius, "radius"},          {neg_mass, "mass"},
      {huge, "radius"},               {ball(0.15, 0, 0, 0), "position"},  // overlaps ball 1
      {ball(1.95, 0, 0, 0), "position"},                                  // overlaps a wall
      {ball(5, 0, 0, 0), "position"},                                     // off the floor
  };
  for (const Case& c : cases)
  {
    const AddResult result = world.addBall(c.def);
    EXPECT_FALSE(result.ok) << c.key;
    EXPECT_EQ(result.error.rfind(c.key, 0), 0u) << result.error;
    EXPECT_EQ(world.stateHash(), before) << c.key;
  }
  const AddResult bad_wall = world.addWall({Vec3(0, -1, 0), Vec3(0, 2, 0), Vec3(0, 4, 0), {}});
  EXPECT_FALSE(bad_wall.ok);
  EXPECT_NE(bad_wall.error.find("parallel"), std::string::npos) << bad_wall.error;
  const AddResult through = world.addWall({Vec3(0, -1, 0), Vec3(0, 2, 0), Vec3(0, 0, 0.5), {}});
  EXPECT_FALSE(through.ok);
  EXPECT_EQ(world.walls().size(), 4u);
  EXPECT_FALSE(world.removeBall(42));
  EXPECT_FALSE(world.removeWall(42));
  EXPECT_EQ(world.stateHash(), before);
}

// Removing or adding a ball between steps takes effect in the very next step.
TEST(Editing, EditsBetweenStepsTakeEffectAtOnce)
{
  Scene scene = flatScene(-5, 5, -5, 5);
  scene.balls = {ball(-3, 0, 1, 0), ball(0, 0, 0, 0), ball(0, 2, 0, 0.5), ball(-2, -3, 0.5, 0)};
  World world(scene);
  const double dt = world.dt();
  for (int k = 0; k < 20; ++k)
    world.step();
  // ball 2 was in ball 1's way (they would meet at 2.8 s); without it ball 1 runs on
  ASSERT_TRUE(world.removeBall(2));
  for (int k = 0; k < 300; ++k)
    world.step();
  EXPECT_NEAR(world.findBall(1)->position.x(), -3 + 320 * dt, 1e-9);
  EXPECT_NEAR(world.findBall(1)->velocity.x(), 1, 1e-12);
  EXPECT_NEAR(world.findBall(3)->position.y(), 2 + 320 * dt * 0.5, 1e-9);
  EXPECT_NEAR(world.findBall(4)->position.x(), -2 + 320 * dt * 0.5, 1e-9);
  // a ball put in its way 0.6 s ahead takes all of its speed when they meet
  const AddResult added = world.addBall(ball(1.0, 0, 0, 0));
  ASSERT_TRUE(added.ok) << added.error;
  for (int k = 0; k < 100; ++k)
    world.step();
  EXPECT_NEAR(world.findBall(1)->velocity.norm(), 0, 1e-12);
  EXPECT_NEAR(world.findBall(added.id)->velocity.x(), 1, 1e-12);
  EXPECT_NEAR(world.findBall(added.id)->position.x(), 1.0 + 0.4, 1e-9);
  EXPECT_NEAR(world.findBall(1)->position.x(), 1.0 - 0.2, 1e-9);
  EXPECT_NEAR(world.energy().kinetic, 0.5 * (1 + 0.25 + 0.25), 1e-12);
}

// Rolling without slip on a flat floor: a ball that has rolled a distance s in a straight
// line has turned by s / r about up x v and spins at |v| / r; for turns per step from a
// small part of a radian to several radians.
TEST(Rolling, TurnsByDistanceOverRadius)
{
  struct Case
  {
    double speed;
    double radius;
  };
  const Vec3 dir = Vec3(3, 4, 0) / 5;
  const Vec3 axis = Vec3::UnitZ().cross(dir);
  for (const Case c : {Case{0.7, 0.2}, Case{20, 0.2}, Case{19.9, 0.2}, Case{20.1, 0.2}, Case{60, 0.05}})
  {
    Scene scene = flatScene(-100, 100, -100, 100);
    scene.balls = {ball(-90 * dir.x(), -90 * dir.y(), c.speed * dir.x(), c.speed * dir.y(), c.radius)};
    World world(scene);
    const Vec3 start = world.balls()[0].position;
    const int steps = 250;
    for (int k = 0; k < steps; ++k)
      world.step();
    const Ball& b = world.balls()[0];
    const double s = c.speed * steps * world.dt();
    EXPECT_NEAR((b.position - start).norm(), s, 1e-12 * s) << c.speed;
    const Quat expected(Eigen::AngleAxisd(s / c.radius, axis));
    EXPECT_LT(b.orientation.angularDistance(expected), 1e-10) << c.speed;
    EXPECT_NEAR(b.orientation.norm(), 1, 1e-15) << c.speed;
    EXPECT_TRUE(world.angularVelocity(0).isApprox(axis * (c.speed / c.radius), 1e-12)) << c.speed;
  }
}

// A ball that bounces inside a step turns by the step's whole move, from where the step
// started it to where it ends, whatever its path did in between: here off one wall, then
// off the other, in the same step, in a corner (e = 1). Its end and its turn are closed
// forms: each wall reflects the part of the path beyond it.
TEST(Rolling, ABallThatBouncesInAStepTurnsByTheStepsWholeMove)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  const double r = 0.1, speed = 5;
  scene.balls = {ball(1.87, 1.88, speed, speed, r)};
  World world(scene);
  const Vec3 start = world.balls()[0].position;
  world.step();
  ASSERT_EQ(world.stats().events, 2u);  // the wall at y = 2 (at x = 0.4), then x = 2 (0.6)
  const Ball& b = world.balls()[0];
  const double reach = 2 - r, move = speed * world.dt();
  // beyond each wall the path is reflected: reach - (start + move - reach)
  const Vec3 end(2 * reach - start.x() - move, 2 * reach - start.y() - move, r);
  EXPECT_LT((b.position - end).norm(), 1e-14);
  EXPECT_LT((b.velocity - Vec3(-speed, -speed, 0)).norm(), 1e-12);
  const Vec3 d = end - start;  // (0.01, -0.01, 0) m
  const Quat expected(Eigen::AngleAxisd(d.norm() / r, Vec3::UnitZ().cross(d).normalized()));
  EXPECT_LT(b.orientation.angularDistance(expected), 1e-12);
}

// An edit undone before the next step (a ball added and removed again) changes nothing:
// the step after it predicts afresh, in the balls' id order, and gets the same bits as a
// run without it; on a flat floor, in a pile settling on a slope (resting contacts, the
// commit's settling pass) and in a pile settling in a bowl (a curved floor).
TEST(Editing, AnEditUndoneChangesNothing)
{
  const Scene scenes[] = {gas(11), slopePile(), bowlPile(5)};
  for (const Scene& scene : scenes)
  {
    World plain(scene), edited(scene);
    for (int k = 0; k < 150; ++k)
    {
      plain.step();
      edited.step();
      if (k % 7 == 3)
      {
        ASSERT_TRUE(addAndRemoveABall(edited, -1.4, 1.4, -1.4, 1.4)) << k;
      }
    }
    EXPECT_GT(plain.stats().resting_events + plain.stats().events, 100u);
    EXPECT_EQ(edited.stateHash(), plain.stateHash());
    EXPECT_EQ(edited.stats().events, plain.stats().events);
  }
}

TEST(Editing, AddedBallSitsOnTheFloorAndMoves)
{
  Scene scene = flatScene();
  World world(scene);
  BallDef def = ball(0.5, 0.5, 1, 0, 0.2);
  def.position.z() = 0.25;  // put back on the floor: centre at one radius
  def.velocity.z() = 3;     // only the tangent part is kept
  const AddResult added = world.addBall(def);
  ASSERT_TRUE(added.ok) << added.error;
  const Ball* b = world.findBall(added.id);
  ASSERT_NE(b, nullptr);
  EXPECT_NEAR(b->position.z(), 0.2, 1e-15);
  EXPECT_NEAR(b->velocity.z(), 0, 1e-15);
  for (int k = 0; k < 10; ++k)
    world.step();
  EXPECT_NEAR(world.findBall(added.id)->position.x(), 0.6, 1e-12);
  EXPECT_TRUE(world.removeBall(added.id));
  EXPECT_EQ(world.findBall(added.id), nullptr);
}

// The step's tunables come from StepSettings: the resting speed decides whether a ball
// touching a wall and closing at 1e-10 m/s rests on it or bounces off; a cap of one
// event a step stops a ball after its first, and is counted; a cap beyond what the
// counters hold is refused.
TEST(StepSettings, TakenByTheWorldAtConstruction)
{
  Scene scene = flatScene();
  addBox(scene, -2, 2, -2, 2);
  scene.balls = {ball(1.9, 0, 1e-10, 0)};  // touching the east wall at x = 2
  for (const double floor_speed : {1e-9, 0.0})
  {
    StepSettings settings;
    settings.resting_speed_floor = floor_speed;
    World world(scene, settings);
    world.step();
    // (on a level floor a resting contact is met as an event, and is a constraint from then)
    ASSERT_EQ(world.lastEvents().size(), 1u) << floor_speed;
    EXPECT_EQ(world.lastEvents()[0].resting, floor_speed > 0) << floor_speed;
    EXPECT_EQ(world.stats().resting_contacts, floor_speed > 0 ? 1u : 0u) << floor_speed;
    EXPECT_EQ(world.balls()[0].velocity.x(), floor_speed > 0 ? 0.0 : -1e-10) << floor_speed;
  }
  Scene cradle = flatScene(-2, 3, -1, 1);
  cradle.balls = {ball(-0.305, 0, 1, 0), ball(0, 0, 0, 0), ball(0.2, 0, 0, 0)};  // impacts at t = 0.105 s
  StepSettings capped;
  capped.max_events_per_ball_step = 1;
  World world(cradle, capped);
  for (int k = 0; k < 20; ++k)
    world.step();
  EXPECT_GT(world.stats().frozen_balls, 0u);
  EXPECT_EQ(World(cradle).stats().frozen_balls, 0u);
  // (a ball's count is kept in 12 bits, up to one past the cap)
  capped.max_events_per_ball_step = 4094;
  EXPECT_NO_THROW(World(cradle, capped));
  for (const std::uint32_t too_many : {4095u, 70000u})
  {
    capped.max_events_per_ball_step = too_many;
    EXPECT_THROW(World(cradle, capped), std::invalid_argument) << too_many;
  }
  // chords of no length (or none at all) are refused too
  for (const double bad : {0.0, -0.01, std::nan("")})
  {
    StepSettings chords;
    chords.chord_sag = bad;
    EXPECT_THROW(World(cradle, chords), std::invalid_argument) << bad;
    chords = StepSettings();
    chords.chord_turn = bad;
    EXPECT_THROW(World(cradle, chords), std::invalid_argument) << bad;
  }
}
