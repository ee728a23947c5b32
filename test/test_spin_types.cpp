// The two spin types of the step (src/core/step/spin_model.hpp), each alone against what
// it must give: without friction a ball's spin is rolling's (n x v / r, k = 2/5) and an
// off-centre strike turns nothing; with friction each ball keeps its own spin and phase
// (a sliding ball's phase on a plane, closed form; a strike's spin offset x J / (k m r^2));
// and on a curved floor a friction phase's chord takes its phase's velocity (a rolling
// ball's v^2 = v0^2 + 2 g.dp / (1 + k)), not the free ball's.
#include "fixtures.hpp"

#include "core/step/spin_model.hpp"
#include "core/step/step_types.hpp"
#include "core/step/stages.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;

FrictionDef sliding(double mu)
{
  FrictionDef f;
  f.sliding = mu;
  f.rolling = 0;
  f.spinning = 0;
  return f;
}

/// A context with its motions predicted, as the step makes them before detection.
StepContext predicted(const Scene& scene)
{
  StepContext c(scene);
  step::startStep(c);
  step::predictMotions(c);
  return c;
}

void expectNear(const Vec3& a, const Vec3& b, double tolerance)
{
  EXPECT_NEAR((a - b).norm(), 0.0, tolerance) << a.transpose() << " vs " << b.transpose();
}
}  // namespace

TEST(SpinTypes, WithoutFrictionABallTurnsByRollingAndKeepsNoSpin)
{
  Scene scene = flatScene(-5, 5, -5, 5);
  scene.balls = {ball(0, 0, 1, 0.5, 0.1, 2.0)};
  StepContext c = predicted(scene);
  EXPECT_EQ(c.spin_, &StepState::SpinModel::of(false));
  EXPECT_TRUE(c.spins_.empty());
  EXPECT_TRUE(c.spin_motions_.empty());
  EXPECT_FALSE(c.motionsEnd());  // (no phase ends on a plane without friction)
  EXPECT_EQ(c.motions_[0].type, MotionType::kLine);

  World world(scene);
  const int id = world.balls()[0].id;
  expectNear(world.angularVelocity(0), Vec3(0, 0, 1).cross(Vec3(1, 0.5, 0)) / 0.1, 1e-14);
  EXPECT_EQ(world.inertia(0), kSolidInertia);
  // an off-centre strike changes the velocity by J / m and turns the ball only by rolling
  const AddResult r = world.strike(id, Vec3(0.4, 0, 0), Vec3(0, 0, 0.05));
  ASSERT_TRUE(r.ok) << r.error;
  expectNear(world.balls()[0].velocity, Vec3(1.2, 0.5, 0), 1e-15);
  expectNear(world.angularVelocity(0), Vec3(0, 0, 1).cross(Vec3(1.2, 0.5, 0)) / 0.1, 1e-14);
}

TEST(SpinTypes, WithFrictionEachBallKeepsItsSpinAndPhase)
{
  const double mu = 0.2, v = 2, r = 0.1, m = 2.0;
  Scene scene = flatScene(-5, 5, -5, 5);
  scene.friction = sliding(mu);
  BallDef b = ball(0, 0, v, 0, r, m);
  b.angular_velocity = Vec3::Zero();  // sliding without spin
  scene.balls = {b};
  StepContext c = predicted(scene);
  EXPECT_EQ(c.spin_, &StepState::SpinModel::of(true));
  ASSERT_EQ(c.spins_.size(), 1u);
  ASSERT_EQ(c.spin_motions_.size(), 1u);
  EXPECT_TRUE(c.motionsEnd());
  // the phase: a parabola on the plane, decelerated by mu g, spun up at 5 mu g / (2 r)
  EXPECT_EQ(c.motions_[0].type, MotionType::kPhase);
  const Vec3 p = c.positionAt(0, 1.0);
  const Vec3 n(0, 0, 1);
  expectNear(c.onFloorVelocity(0, 1.0, p, n), Vec3(v - mu * kG * scene.dt, 0, 0), 1e-14);
  expectNear(p - c.balls_[0].position, Vec3(v * scene.dt - 0.5 * mu * kG * scene.dt * scene.dt, 0, 0), 1e-15);
  expectNear(c.spinAt(0, 1.0), Vec3(0, 5 * mu * kG * scene.dt / (2 * r), 0), 1e-13);
  // its slip ends at 2 v / (7 mu g), where it rolls
  EXPECT_NEAR(c.spin_motions_[0].x_end * scene.dt, 2 * v / (7 * mu * kG), 1e-14);

  World world(scene);
  const int id = world.balls()[0].id;
  const Vec3 j(0, 0.3, 0), offset(0.05, 0, 0.02);
  ASSERT_TRUE(world.strike(id, j, offset).ok);
  expectNear(world.angularVelocity(0), offset.cross(j) / (kSolidInertia * m * r * r), 1e-13);
}

TEST(SpinTypes, OnACurvedFloorAPhasesChordTakesItsPhasesVelocity)
{
  // rolling down the 3 m bowl (z = 0.4 (x^2 + y^2) / 3) from x = 0.8 toward its bottom
  Scene scene;
  scene.floor = bowl(3, 0.3);
  scene.friction = sliding(0.5);  // (enough to hold rolling on this slope)
  BallDef b = ball(0.8, 0, -1, 0, 0.05);
  b.position.z() = 0.4 * 0.64 / 3 + 0.06;  // (put on the floor below)
  scene.balls = {b};
  StepContext c = predicted(scene);
  ASSERT_EQ(c.spin_motions_[0].kind, MotionKind::kRolling);
  EXPECT_EQ(c.motions_[0].type, MotionType::kPhaseChord);
  const Vec3 p0 = c.startPosition(0), v0 = c.startVelocity(0);
  const Vec3 p = c.positionAt(0, 1.0);
  const Vec3 n = c.floorNormalAt(0, p);
  const Vec3 v = c.onFloorVelocity(0, 1.0, p, n);
  const double rolling2 = v0.squaredNorm() + 2 * scene.gravity.dot(p - p0) / (1 + kSolidInertia);
  const double free2 = v0.squaredNorm() + 2 * scene.gravity.dot(p - p0);
  EXPECT_NEAR(v.squaredNorm(), rolling2, 1e-13);
  EXPECT_GT(std::abs(free2 - rolling2), 1e-4);  // (a free chord's speed would be told apart)

  // the same ball without friction moves on the free chord
  scene.friction.reset();
  StepContext f = predicted(scene);
  EXPECT_EQ(f.motions_[0].type, MotionType::kLine);
  const Vec3 fp = f.positionAt(0, 1.0);
  const Vec3 fv = f.onFloorVelocity(0, 1.0, fp, f.floorNormalAt(0, fp));
  EXPECT_NEAR(fv.squaredNorm(), f.startVelocity(0).squaredNorm() + 2 * scene.gravity.dot(fp - f.startPosition(0)), 1e-13);
}
