// Friction, spin and the motion kinds against their closed forms: a ball struck without
// spin slides, then rolls at v0 / (1 + k) and stops where the laws say; a stop shot; a
// follow shot; rolling and sliding along a tilted plane's fall line; spin dying out in
// place; two decelerating balls meeting when the quartic says; a rack coming to rest with
// its energy never rising; and friction 0 giving the frictionless bits.
#include "fixtures.hpp"

#include "ball_collision_sim/core/friction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;

/// A level floor [x0, x1] x [-1, 1] with friction, no walls.
Scene table(const FrictionDef& f, double x0 = -2, double x1 = 14)
{
  Scene scene = flatScene(x0, x1, -1, 1);
  scene.friction = f;
  return scene;
}

BallDef struck(double x, double vx, const Vec3& spin, double k, double radius = 0.1)
{
  BallDef b = ball(x, 0, vx, 0, radius);
  b.angular_velocity = spin;
  b.inertia = k;
  return b;
}

/// Runs until the step that holds time t has been taken; returns every transition.
std::vector<MotionTransition> runUntil(World& world, double t)
{
  std::vector<MotionTransition> all;
  while (world.time() < t - 1e-9)
  {
    world.step();
    all.insert(all.end(), world.lastTransitions().begin(), world.lastTransitions().end());
  }
  return all;
}
}  // namespace

// Struck at its centre (no spin): it slides while friction turns it up, for
// t1 = k v0 / ((1 + k) mu_s g) (2 v0 / (7 mu_s g) for a solid ball), then rolls from
// v0 / (1 + k) (5/7 v0 solid, 3/5 v0 hollow), decelerating at mu_r g until it stops.
class SlideThenRoll : public ::testing::TestWithParam<double>
{
};

TEST_P(SlideThenRoll, MatchesTheClosedForm)
{
  const double k = GetParam();
  const double mu_s = 0.2, mu_r = 0.01, v0 = 2.0, r = 0.1, x0 = -1.5;
  Scene scene = table(friction(mu_s, mu_r));
  scene.balls = {struck(x0, v0, Vec3::Zero(), k, r)};
  World world(scene);
  ASSERT_EQ(world.motionKind(0), MotionKind::kSliding);

  const double t1 = k * v0 / ((1 + k) * mu_s * kG);
  const double v1 = v0 / (1 + k);
  const double x1 = x0 + v0 * t1 - 0.5 * mu_s * kG * t1 * t1;
  const double t2 = t1 + v1 / (mu_r * kG);
  const double x2 = x1 + v1 * v1 / (2 * mu_r * kG);

  // while it slides: v = v0 - mu_s g t, w = (mu_s g / (k r)) t about +y
  const auto sliding = runUntil(world, 0.1);
  EXPECT_TRUE(sliding.empty());
  const Ball& b = world.balls()[0];
  EXPECT_NEAR(b.position.x(), x0 + v0 * 0.1 - 0.5 * mu_s * kG * 0.01, 1e-14);
  EXPECT_NEAR(b.velocity.x(), v0 - mu_s * kG * 0.1, 1e-14);
  EXPECT_NEAR(world.angularVelocity(0).y(), mu_s * kG / (k * r) * 0.1, 1e-12);

  // then rolls: the transition at t1, to round-off
  const auto rolling = runUntil(world, t1 + 0.5);
  ASSERT_EQ(rolling.size(), 1u);
  EXPECT_EQ(rolling[0].from, MotionKind::kSliding);
  EXPECT_EQ(rolling[0].to, MotionKind::kRolling);
  EXPECT_NEAR(rolling[0].time, t1, 1e-14);
  const double t = world.time();
  EXPECT_NEAR(b.velocity.x(), v1 - mu_r * kG * (t - t1), 1e-13);
  EXPECT_NEAR(b.position.x(), x1 + v1 * (t - t1) - 0.5 * mu_r * kG * (t - t1) * (t - t1), 1e-13);
  EXPECT_EQ(world.motionKind(0), MotionKind::kRolling);
  // rolling: w = n x v / r exactly
  EXPECT_NEAR(world.angularVelocity(0).y(), b.velocity.x() / r, 1e-12);

  // and stops at t2, x2
  const auto stopping = runUntil(world, t2 + 0.05);
  ASSERT_EQ(stopping.size(), 1u);
  EXPECT_EQ(stopping[0].to, MotionKind::kStationary);
  EXPECT_NEAR(stopping[0].time, t2, 1e-10);
  EXPECT_NEAR(b.position.x(), x2, 1e-11);
  EXPECT_EQ(b.velocity, Vec3::Zero());
  EXPECT_EQ(world.angularVelocity(0), Vec3::Zero());
  EXPECT_EQ(world.motionKind(0), MotionKind::kStationary);
  const Vec3 rest = b.position;
  runUntil(world, world.time() + 1.0);
  EXPECT_EQ(b.position, rest);
}

// solid (5/7), hollow (3/5), and a number k = 1/2 (2/3)
INSTANTIATE_TEST_SUITE_P(Inertia, SlideThenRoll, ::testing::Values(kSolidInertia, kHollowInertia, 0.5));

// Backspin v0 / (k r): the slip and the velocity reach zero together at v0 / (mu_s g),
// v0^2 / (2 mu_s g) on: the ball stops dead there.
TEST(StopShot, StopsDead)
{
  const double mu_s = 0.2, v0 = 2.0, r = 0.1, k = kSolidInertia, x0 = -1.5;
  Scene scene = table(friction(mu_s, 0.01));
  scene.balls = {struck(x0, v0, Vec3(0, -v0 / (k * r), 0), k, r)};
  World world(scene);
  const auto transitions = runUntil(world, 2.0);
  ASSERT_EQ(transitions.size(), 1u);
  EXPECT_EQ(transitions[0].from, MotionKind::kSliding);
  EXPECT_EQ(transitions[0].to, MotionKind::kStationary);
  EXPECT_NEAR(transitions[0].time, v0 / (mu_s * kG), 1e-14);
  EXPECT_NEAR(world.balls()[0].position.x(), x0 + v0 * v0 / (2 * mu_s * kG), 1e-14);
  EXPECT_EQ(world.balls()[0].velocity, Vec3::Zero());
  EXPECT_EQ(world.angularVelocity(0), Vec3::Zero());
}

// A rolling cue ball hits an object ball head on (e = 1, no ball-ball friction): the cue
// ball stops with its topspin and is pulled on to 2/7 of its speed; the object ball
// leaves without spin and rolls at 5/7. No rolling resistance, so the speeds stay.
TEST(FollowShot, TwoSeventhsAndFiveSevenths)
{
  const double v0 = 1.5, r = 0.1;
  Scene scene = table(friction(0.2, 0.0));
  scene.balls = {struck(-1.0, v0, Vec3(0, v0 / r, 0), kSolidInertia, r), struck(0.0, 0.0, Vec3::Zero(), kSolidInertia, r)};
  World world(scene);
  ASSERT_EQ(world.motionKind(0), MotionKind::kRolling);
  ASSERT_EQ(world.motionKind(1), MotionKind::kStationary);
  int impacts = 0;
  for (int s = 0; s < 200; ++s)
  {
    world.step();
    impacts += static_cast<int>(world.lastEvents().size());
  }
  EXPECT_EQ(impacts, 1);
  EXPECT_NEAR(world.balls()[0].velocity.x(), 2.0 / 7 * v0, 1e-14);
  EXPECT_NEAR(world.balls()[1].velocity.x(), 5.0 / 7 * v0, 1e-14);
  EXPECT_EQ(world.motionKind(0), MotionKind::kRolling);
  EXPECT_EQ(world.motionKind(1), MotionKind::kRolling);
  EXPECT_NEAR(world.momentum().x(), 1.0 * v0, 1e-14);  // friction with the floor keeps it here
}

namespace
{
/// A plane tilted by `degrees` about y, falling toward +x, with friction; 20 m long.
Scene tilted(double degrees, const FrictionDef& f)
{
  const double a = degrees * M_PI / 180;
  Scene scene;
  FloorDef floor;
  floor.point = Vec3(-10 * std::cos(a), -1, 10 * std::sin(a));
  floor.u = Vec3(20 * std::cos(a), 0, -20 * std::sin(a));
  floor.v = Vec3(0, 2, 0);
  scene.floor = floor;
  scene.friction = f;
  return scene;
}

/// The centre of a ball of radius r resting on the middle of tilted().
Vec3 onTilted(double degrees, double r)
{
  const double a = degrees * M_PI / 180;
  return r * Vec3(std::sin(a), 0, std::cos(a));
}

/// Distance travelled down the fall line of tilted() from the plane's middle.
double downhill(const Ball& b, double degrees)
{
  const double a = degrees * M_PI / 180;
  return b.position.x() * std::cos(a) - b.position.z() * std::sin(a);
}
}  // namespace

// From rest on 10 degrees, mu_s = 0.2 holds rolling: a = g sin / (1 + k) - mu_r g cos.
TEST(TiltedPlane, RollsDownTheFallLine)
{
  const double deg = 10, a = deg * M_PI / 180, mu_r = 0.01;
  Scene scene = tilted(deg, friction(0.2, mu_r));
  BallDef b = ball(0, 0, 0, 0);
  b.position = onTilted(deg, b.radius);
  scene.balls = {b};
  World world(scene);
  const double s0 = downhill(world.balls()[0], deg);
  runUntil(world, 1.0);
  const double acc = kG * std::sin(a) / (1 + kSolidInertia) - mu_r * kG * std::cos(a);
  EXPECT_EQ(world.motionKind(0), MotionKind::kRolling);
  EXPECT_NEAR(downhill(world.balls()[0], deg) - s0, 0.5 * acc, 1e-13);
  EXPECT_NEAR(world.balls()[0].velocity.norm(), acc, 1e-13);
}

// On 20 degrees mu_s = 0.05 cannot hold rolling (k tan / (1 + k) = 0.104): it slides
// down at g sin - mu_s g cos while friction spins it up.
TEST(TiltedPlane, SlidesWhereFrictionCannotHoldRolling)
{
  const double deg = 20, a = deg * M_PI / 180, mu_s = 0.05;
  Scene scene = tilted(deg, friction(mu_s, 0.01));
  BallDef b = ball(0, 0, 0, 0);
  b.position = onTilted(deg, b.radius);
  scene.balls = {b};
  World world(scene);
  const double s0 = downhill(world.balls()[0], deg);
  const auto transitions = runUntil(world, 1.0);
  EXPECT_TRUE(transitions.empty());
  EXPECT_EQ(world.motionKind(0), MotionKind::kSliding);
  const double acc = kG * std::sin(a) - mu_s * kG * std::cos(a);
  EXPECT_NEAR(downhill(world.balls()[0], deg) - s0, 0.5 * acc, 1e-13);
  EXPECT_NEAR(world.angularVelocity(0).norm(), mu_s * kG * std::cos(a) / (kSolidInertia * 0.1), 1e-12);
}

// Without sliding friction (mu_s = 0) nothing acts on the slip but gravity, which turns it:
// a ball thrown uphill (and a little across) without spin slides on a parabola (rolling
// resistance acts on rolling balls only), also past where the slip's part along its
// direction at a step's start is gone (near 1 / g_t, where the slip is about 5 mm/s
// across, not zero).
TEST(TiltedPlane, WithoutSlidingFrictionABallSlidesOnItsParabola)
{
  const double deg = 10, a = deg * M_PI / 180, g_t = kG * std::sin(a);
  Scene scene = tilted(deg, friction(0.0, 0.01));
  BallDef b = ball(0, 0, 0, 0);
  b.position = onTilted(deg, b.radius);
  const Vec3 down(std::cos(a), 0, -std::sin(a));
  const Vec3 v0 = -1.0 * down + Vec3(0, 0.005, 0);
  b.velocity = v0;
  b.angular_velocity = Vec3::Zero();
  scene.balls = {b};
  World world(scene);
  const Vec3 p0 = world.balls()[0].position;
  const double e0 = world.energy().total();
  const auto transitions = runUntil(world, 1.0);
  EXPECT_TRUE(transitions.empty());
  EXPECT_EQ(world.motionKind(0), MotionKind::kSliding);
  const double t = world.time();
  const Vec3 expected = p0 + t * v0 + (0.5 * g_t * t * t) * down;
  EXPECT_LT((world.balls()[0].position - expected).norm(), 1e-12);
  EXPECT_LT((world.balls()[0].velocity - (v0 + (g_t * t) * down)).norm(), 1e-12);
  EXPECT_EQ(world.angularVelocity(0), Vec3::Zero());
  EXPECT_NEAR(world.energy().total(), e0, 1e-12 * std::abs(e0));
}

// Thrown uphill without spin: it slides until the slip is gone, rolls up, stops and rolls
// back down, each piece a closed form.
TEST(TiltedPlane, ThrownUphillSlidesRollsUpAndComesBack)
{
  const double deg = 10, a = deg * M_PI / 180, mu_s = 0.2, mu_r = 0.01, k = kSolidInertia, v0 = 2.0;
  const double gs = kG * std::sin(a), gc = kG * std::cos(a);
  Scene scene = tilted(deg, friction(mu_s, mu_r));
  BallDef b = ball(0, 0, 0, 0);
  b.position = onTilted(deg, b.radius);
  b.velocity = -v0 * Vec3(std::cos(a), 0, -std::sin(a));  // up the fall line
  b.angular_velocity = Vec3::Zero();
  scene.balls = {b};
  World world(scene);
  const double s0 = downhill(world.balls()[0], deg);
  // sliding: s'' = gs + mu_s gc (both against the uphill motion), slip falls at
  // mu_s gc (1 + k) / k + gs
  const double t1 = v0 / (mu_s * gc * (1 + k) / k + gs);
  const double a1 = gs + mu_s * gc;
  const double v1 = -v0 + a1 * t1;
  const double s1 = -v0 * t1 + 0.5 * a1 * t1 * t1;
  // rolling up: s'' = gs / (1 + k) + mu_r gc, until v = 0
  const double a2 = gs / (1 + k) + mu_r * gc;
  const double t2 = t1 - v1 / a2;
  const double s2 = s1 - v1 * v1 / (2 * a2);
  // rolling down: s'' = gs / (1 + k) - mu_r gc
  const double a3 = gs / (1 + k) - mu_r * gc;
  const double t = 3.0;
  const auto transitions = runUntil(world, t);
  ASSERT_GE(transitions.size(), 1u);
  EXPECT_NEAR(transitions[0].time, t1, 1e-14);
  EXPECT_EQ(transitions[0].to, MotionKind::kRolling);
  EXPECT_NEAR(downhill(world.balls()[0], deg) - s0, s2 + 0.5 * a3 * (t - t2) * (t - t2), 1e-12);
  EXPECT_NEAR(world.balls()[0].velocity.norm(), a3 * (t - t2), 1e-12);
}

// Spinning in place about the normal: w.n falls at mu_sp g / (k r) to 0; it never moves.
TEST(Spin, DiesOutInPlace)
{
  const double mu_sp = 0.044, r = 0.028575, w0 = 30;
  Scene scene = table(friction(0.2, 0.01, mu_sp));
  scene.balls = {struck(0, 0, Vec3(0, 0, w0), kSolidInertia, r)};
  World world(scene);
  ASSERT_EQ(world.motionKind(0), MotionKind::kSpinning);
  const Vec3 p = world.balls()[0].position;
  const double rate = mu_sp * kG / (kSolidInertia * r);
  runUntil(world, 0.5);
  EXPECT_NEAR(world.angularVelocity(0).z(), w0 - rate * 0.5, 1e-12);
  const auto transitions = runUntil(world, 1.0);
  ASSERT_EQ(transitions.size(), 1u);
  EXPECT_EQ(transitions[0].from, MotionKind::kSpinning);
  EXPECT_EQ(transitions[0].to, MotionKind::kStationary);
  EXPECT_NEAR(transitions[0].time, w0 / rate, 1e-14);
  EXPECT_EQ(world.angularVelocity(0), Vec3::Zero());
  EXPECT_EQ(world.balls()[0].position, p);
}

// Two sliding balls decelerating across each other: their distance squared less the reach
// squared is a quartic in t; the impact comes at its first root.
TEST(Decelerating, BallsMeetAtTheQuarticsRoot)
{
  const double mu_s = 0.2, r = 0.1;
  Scene scene = table(friction(mu_s, 0.01));
  const Vec3 pa(0, 0, r), pb(0.55, -0.45, r), va(3, 0, 0), vb(0, 2.5, 0);
  scene.balls = {struck(0, 3, Vec3::Zero(), kSolidInertia, r), struck(0, 0, Vec3::Zero(), kSolidInertia, r)};
  scene.balls[1].position = pb;
  scene.balls[1].velocity = vb;
  World world(scene);
  // each slides with a = -mu_s g v/|v| until 2 |v| / (7 mu_s g)
  const auto at = [&](const Vec3& p, const Vec3& v, long double t) {
    const Vec3 dir = v.normalized();
    return std::array<long double, 2>{p.x() + (v.x() * t - 0.5L * mu_s * kG * dir.x() * t * t),
                                      p.y() + (v.y() * t - 0.5L * mu_s * kG * dir.y() * t * t)};
  };
  const auto f = [&](long double t) {
    const auto a = at(pa, va, t), b = at(pb, vb, t);
    const long double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy - 4.0L * r * r;
  };
  const long double t_end = 2 * 2.5 / (7 * mu_s * kG);
  // the first time the quartic goes negative, on a fine grid, then halving
  long double lo = 0, hi = -1;
  for (int k = 1; k <= 100000 && hi < 0; ++k)
  {
    const long double t = t_end * k / 100000;
    if (f(t) < 0)
      hi = t;
    else
      lo = t;
  }
  ASSERT_GT(hi, 0);  // they meet while both slide
  for (int k = 0; k < 200; ++k)
  {
    const long double mid = 0.5L * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  double hit = -1;
  for (int s = 0; s < 50 && hit < 0; ++s)
  {
    world.step();
    for (const CollisionEvent& e : world.lastEvents())
      hit = e.time;
  }
  EXPECT_NEAR(hit, static_cast<double>(lo), 1e-13);
}

namespace
{
/// A pool table with a rack of 15 and a cue ball struck into it (pooltool's defaults).
Scene rack(double restitution)
{
  const double r = 0.028575, m = 0.170097;
  Scene scene = flatScene(-0.635, 0.635, -1.27, 1.27);
  addBox(scene, -0.635, 0.635, -1.27, 1.27, 0.05);
  scene.restitution = restitution;
  FrictionDef f = friction(0.2, 0.01, 0.044);
  scene.friction = f;
  int n = 0;
  for (int row = 0; row < 5; ++row)
    for (int c = 0; c <= row; ++c, ++n)
      scene.balls.push_back(ball((c - 0.5 * row) * 2.0001 * r, 0.6 + row * std::sqrt(3.0) * 1.0001 * r, 0, 0, r, m));
  BallDef cue = ball(0.01, -0.6, 0, 8, r, m);
  cue.angular_velocity = Vec3::Zero();
  scene.balls.push_back(cue);
  return scene;
}
}  // namespace

// The break at e = 0.9: every ball comes to rest; the energy (with the spins') never
// rises in a step, no ball overlaps another, none leaves the table.
TEST(Rack, ComesToRestWithEnergyNeverRising)
{
  World world(rack(0.9));
  double e = world.energy().total();
  const double e0 = e;
  double worst_rise = 0, deepest = 0;
  int steps = 0;
  for (; steps < 6000; ++steps)
  {
    world.step();
    const double now = world.energy().total();
    worst_rise = std::max(worst_rise, now - e);
    e = now;
    deepest = std::max(deepest, deepestOverlap(world.balls()));
    bool still = true;
    for (std::size_t k = 0; k < world.balls().size(); ++k)
      still = still && world.motionKind(k) == MotionKind::kStationary;
    if (still)
      break;
  }
  EXPECT_LT(steps, 6000) << "still moving after 60 s";
  EXPECT_GT(steps, 100);                   // the break takes seconds to die down
  EXPECT_GT(world.stats().events, 30u);    // the cue ball breaks the rack up
  EXPECT_GT(world.stats().transitions, 30u);
  EXPECT_LE(worst_rise, 1e-12 * std::abs(e0));
  EXPECT_LT(deepest, 1e-9);
  EXPECT_EQ(world.lostBalls(), 0);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_EQ(world.energy().kinetic, 0.0);
  EXPECT_EQ(world.energy().rotational, 0.0);
}

namespace
{
bool sameBits(const Vec3& a, const Vec3& b)
{
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

void expectSameMotion(Scene scene, int steps)
{
  World plain(scene);
  scene.friction = FrictionDef{};
  World zero(scene);
  for (int s = 0; s < steps; ++s)
  {
    plain.step();
    zero.step();
  }
  ASSERT_EQ(plain.balls().size(), zero.balls().size());
  int differ = 0;
  for (std::size_t k = 0; k < plain.balls().size(); ++k)
    differ += !sameBits(plain.balls()[k].position, zero.balls()[k].position) ||
              !sameBits(plain.balls()[k].velocity, zero.balls()[k].velocity);
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(plain.stats().events, zero.stats().events);
  EXPECT_GT(plain.stats().events, 0u);
}
}  // namespace

// Friction 0 moves every ball as no friction block does, to the bit: on a level table
// with walls, and on a 10 degree slope against a wall where balls rest on each other.
TEST(ZeroFriction, SameBitsAsNone)
{
  Scene level = flatScene(-2, 2, -2, 2);
  addBox(level, -2, 2, -2, 2);
  level.random_balls = randomBalls(200, 7, {0.05, 0.1}, {0.5, 2}, {0.5, 3});
  expectSameMotion(level, 300);
  expectSameMotion(slopeWithWall(60, 10, 0.5, 3), 300);
}

// The sliding-to-rolling transition of the law itself, on both sides of the tolerance.
TEST(FrictionLaw, SlipOfRoundOffIsRolling)
{
  const FrictionLaw law(friction(0.2, 0.01), Vec3::UnitZ(), Vec3(0, 0, -kG), Vec3::Zero(), 1e-12, 1e-9);
  Vec3 v(1, 0, 0), w(0, 10 * (1 + 1e-14), 0);
  EXPECT_EQ(law.start(0.4, 0.1, v, w).kind, MotionKind::kRolling);
  EXPECT_EQ(w, Vec3::UnitZ().cross(v) / 0.1);  // rolling's spin, exactly
  Vec3 v2(1, 0, 0), w2(0, 10 * (1 + 1e-9), 0);
  const FrictionPhase phase = law.start(0.4, 0.1, v2, w2);
  EXPECT_EQ(phase.kind, MotionKind::kSliding);
  EXPECT_EQ(phase.ends, kSlipStops);
}

namespace
{
/// Impacts only: no floor friction, so velocities and spins stay as the impact left them.
Scene impactsOnly(double ball_ball, double wall)
{
  Scene scene = flatScene(-2, 2, -1, 1);
  addBox(scene, -2, 2, -1, 1);
  FrictionDef f;
  f.ball_ball = ball_ball;
  f.wall = wall;
  scene.friction = f;
  return scene;
}
}  // namespace

// Head on, e = 1, a ball with side spin w about z meets a ball at rest: the touching points
// slip by w r across the normal; the tangential impulse that stops it is w r m / 7 (solid,
// equal masses), below mu Jn = mu m v here: "throw". Above it, mu Jn exactly.
TEST(ImpactFriction, BallBallThrowStopsTheSlipOrReachesCoulomb)
{
  const double v = 1.0, r = 0.1, m = 1.0, mu = 0.3;
  for (const double w : {2.0, 40.0})
  {
    Scene scene = impactsOnly(mu, 0.0);
    scene.balls = {struck(-1.0, v, Vec3(0, 0, w), kSolidInertia, r), struck(0.0, 0.0, Vec3::Zero(), kSolidInertia, r)};
    World world(scene);
    for (int s = 0; s < 100; ++s)
      world.step();
    ASSERT_EQ(world.stats().events, 1u);
    const double jt = std::min(mu * m * v, w * r * m / 7);
    EXPECT_NEAR(world.balls()[0].velocity.y(), -jt / m, 1e-15) << w;
    EXPECT_NEAR(world.balls()[1].velocity.y(), jt / m, 1e-15) << w;
    EXPECT_NEAR(world.balls()[1].velocity.x(), v, 1e-15);
    EXPECT_NEAR(world.momentum().y(), 0.0, 1e-15);
    EXPECT_NEAR(world.angularVelocity(0).z(), w - jt / (kSolidInertia * m * r), 1e-12) << w;
    EXPECT_NEAR(world.angularVelocity(1).z(), -jt / (kSolidInertia * m * r), 1e-12) << w;
    // the touching points' slip after: w_a r + w_b r + 2 v_y... never reversed
    const double slip_after = (world.angularVelocity(0).z() + world.angularVelocity(1).z()) * r +
                              (world.balls()[0].velocity.y() - world.balls()[1].velocity.y());
    EXPECT_GE(slip_after, -1e-15) << w;
  }
}

// A ball with side spin meets a wall square on (e = 1): the wall's tangential impulse
// min(mu (1 + e) m v, w r m / (1 + 1/k)) turns its path and its spin; without wall
// friction the spin passes through unchanged.
TEST(ImpactFriction, WallTurnsASpinningBall)
{
  const double v = 1.0, r = 0.1, m = 1.0, w = 5.0;
  for (const double mu : {0.0, 0.05, 0.5})
  {
    Scene scene = impactsOnly(0.0, mu);
    scene.balls = {struck(1.5, v, Vec3(0, 0, w), kSolidInertia, r)};
    World world(scene);
    for (int s = 0; s < 60; ++s)
      world.step();
    ASSERT_EQ(world.stats().events, 1u);
    const double jt = std::min(mu * 2 * m * v, w * r * m / (1 + 1 / kSolidInertia));
    // the touching point (at +r x) slips by w r along +y: the impulse is along -y
    EXPECT_NEAR(world.balls()[0].velocity.x(), -v, 1e-15) << mu;
    EXPECT_NEAR(world.balls()[0].velocity.y(), -jt / m, 1e-15) << mu;
    EXPECT_NEAR(world.angularVelocity(0).z(), w - jt / (kSolidInertia * m * r), 1e-12) << mu;
  }
}

// A ball rolling square into a wall (e = 1) meets it with its touching point slipping
// down at v (its topspin's r w): the wall's friction across the floor's line acts upward,
// where the floor takes none of it, so that only the spin turns: w_y' = v / r - min(v k
// m, mu (1 + e) m v) / (k m r). From mu = k / (1 + e) on, the topspin stops; the velocity
// only bounces.
TEST(ImpactFriction, WallTakesARollingBallsTopspin)
{
  const double v = 1.0, r = 0.1, m = 1.0;
  for (const double k : {kSolidInertia, kHollowInertia})
    for (const double mu : {0.0, 0.05, 0.15, 0.5})
    {
      Scene scene = impactsOnly(0.0, mu);
      scene.balls = {struck(1.5, v, Vec3(0, v / r, 0), k, r)};
      World world(scene);
      for (int s = 0; s < 60; ++s)
        world.step();
      ASSERT_EQ(world.stats().events, 1u);
      const double jz = std::min(v * k * m, mu * 2 * m * v);
      EXPECT_NEAR(world.balls()[0].velocity.x(), -v, 1e-15) << mu;
      EXPECT_NEAR(world.balls()[0].velocity.y(), 0.0, 1e-15) << mu;
      EXPECT_NEAR(world.angularVelocity(0).y(), v / r - jz / (k * m * r), 1e-12) << "k " << k << " mu " << mu;
      EXPECT_NEAR(world.angularVelocity(0).x(), 0.0, 1e-12);
      EXPECT_NEAR(world.angularVelocity(0).z(), 0.0, 1e-12);
    }
}

// A ball rolling into an equal one at rest, head on (e = 1): its touching point slips
// down past the other's at v. Friction between them acts across the floor's line, where
// the floor takes it all, with the impulse min(v k m / 2, mu m v) (each ball's touching
// point moves by J / (k m) under it): it takes that from the rolling ball's topspin and
// gives the struck one as much backspin; the velocities are exchanged as without it.
TEST(ImpactFriction, BallBallFrictionTurnsTopspinAcrossTheFloorLine)
{
  const double v = 1.0, r = 0.1, m = 1.0, k = kSolidInertia;
  for (const double mu : {0.05, 0.5})
  {
    Scene scene = impactsOnly(mu, 0.0);
    scene.balls = {struck(-1.0, v, Vec3(0, v / r, 0), k, r), struck(0.0, 0.0, Vec3::Zero(), k, r)};
    World world(scene);
    for (int s = 0; s < 100; ++s)
      world.step();
    ASSERT_EQ(world.stats().events, 1u);
    const double jz = std::min(v * k * m / 2, mu * m * v);
    EXPECT_NEAR(world.balls()[0].velocity.norm(), 0.0, 1e-15) << mu;
    EXPECT_NEAR(world.balls()[1].velocity.x(), v, 1e-15) << mu;
    EXPECT_NEAR(world.balls()[1].velocity.y(), 0.0, 1e-15) << mu;
    EXPECT_NEAR(world.angularVelocity(0).y(), v / r - jz / (k * m * r), 1e-12) << mu;
    EXPECT_NEAR(world.angularVelocity(1).y(), -jz / (k * m * r), 1e-12) << mu;
  }
}

// A table of balls at e = 0.9 with every friction on, impacts' too: the energy never rises
// in a step and every ball comes to rest.
TEST(ImpactFriction, TableComesToRestWithEnergyNeverRising)
{
  Scene scene = flatScene(-1, 1, -1, 1);
  addBox(scene, -1, 1, -1, 1);
  scene.restitution = 0.9;
  scene.random_balls = randomBalls(80, 5, {0.03, 0.06}, {0.1, 0.3}, {0.5, 3});
  FrictionDef f = friction(0.2, 0.01, 0.044);
  f.ball_ball = 0.05;
  f.wall = 0.2;
  scene.friction = f;
  World world(scene);
  double e = world.energy().total(), rise = 0;
  bool still = false;
  int steps = 0;
  for (; steps < 3000 && !still; ++steps)
  {
    world.step();
    rise = std::max(rise, world.energy().total() - e);
    e = world.energy().total();
    still = true;
    for (std::size_t k = 0; k < world.balls().size(); ++k)
      still = still && world.motionKind(k) == MotionKind::kStationary;
  }
  EXPECT_TRUE(still) << "moving after " << steps << " steps";
  EXPECT_LE(rise, 1e-12);
  EXPECT_GT(world.stats().events, 80u);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
}

// A pile in the bowl with friction (e = 0.5) comes to rest and sleeps; no ball reaches
// the event cap, none overlaps, and the energy rises by no more than round-off of it.
TEST(CurvedFloor, PileWithFrictionComesToRestAndSleeps)
{
  Scene scene = bowlPile(5);
  scene.friction = friction(0.2, 0.01, 0.044);
  World world(scene);
  const double e0 = world.energy().total();
  double e = e0, rise = 0, deepest = 0;
  for (int k = 0; k < 3000; ++k)
  {
    world.step();
    rise = std::max(rise, world.energy().total() - e);
    e = world.energy().total();
    deepest = std::max(deepest, deepestOverlap(world.balls()));
  }
  EXPECT_EQ(world.stats().sleeping_balls, world.balls().size());
  EXPECT_EQ(world.energy().kinetic, 0.0);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_LT(deepest, 1e-9);
  EXPECT_LE(rise, 1e-9 * std::abs(e0));
}
