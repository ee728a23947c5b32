#include "fixtures.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
struct HeadOn
{
  double m1, m2, r1, r2;
};

class HeadOnCollision : public ::testing::TestWithParam<HeadOn>
{
};

}  // namespace

// Two balls meet head-on; the velocities after must be the elastic closed form of the
// seed's equations (16)-(19), u1' = ((m1 - m2) u1 + 2 m2 u2) / (m1 + m2) and its mirror,
// at the analytic time of impact, and positions after follow from both.
TEST_P(HeadOnCollision, MatchesClosedForm)
{
  const HeadOn c = GetParam();
  Scene scene = flatScene(-3, 3, -1, 1);
  scene.gravity = Vec3(0, 0, -9.81);
  const double u1 = 1.3, u2 = -0.4, x1 = -1.0, x2 = 0.5;
  scene.balls = {ball(x1, 0, u1, 0, c.r1, c.m1), ball(x2, 0, u2, 0, c.r2, c.m2)};
  // centres at heights r1 and r2: they touch when the horizontal gap is sqrt(R^2 - dz^2)
  const double R = c.r1 + c.r2, dz = c.r2 - c.r1;
  const double t_hit = (x2 - x1 - std::sqrt(R * R - dz * dz)) / (u1 - u2);
  const double v1 = ((c.m1 - c.m2) * u1 + 2 * c.m2 * u2) / (c.m1 + c.m2);
  const double v2 = ((c.m2 - c.m1) * u2 + 2 * c.m1 * u1) / (c.m1 + c.m2);

  World world(scene);
  std::vector<CollisionEvent> events;
  const double T = 1.5;
  while (world.time() < T - 1e-12)
  {
    world.step();
    events.insert(events.end(), world.lastEvents().begin(), world.lastEvents().end());
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0].time, t_hit, 1e-12);
  EXPECT_EQ(events[0].ball, 1);  // ids start at 1
  EXPECT_EQ(events[0].other, 2);
  const auto& b = world.balls();
  EXPECT_NEAR(b[0].velocity.x(), v1, 1e-12);
  EXPECT_NEAR(b[1].velocity.x(), v2, 1e-12);
  EXPECT_NEAR(b[0].velocity.y(), 0, 1e-15);
  EXPECT_NEAR(b[0].position.x(), x1 + u1 * t_hit + v1 * (T - t_hit), 1e-12);
  EXPECT_NEAR(b[1].position.x(), x2 + u2 * t_hit + v2 * (T - t_hit), 1e-12);
  EXPECT_NEAR(c.m1 * b[0].velocity.x() + c.m2 * b[1].velocity.x(), c.m1 * u1 + c.m2 * u2, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(MassRatios, HeadOnCollision,
                         ::testing::Values(HeadOn{1, 1, 0.1, 0.1}, HeadOn{3, 1, 0.1, 0.1},
                                           HeadOn{1, 7, 0.1, 0.1}, HeadOn{1.0 / 7, 1, 0.1, 0.15}));

TEST(ObliqueCollision, ConservesMomentumAndEnergyAlongTheLineOfCentres)
{
  Scene scene = flatScene(-3, 3, -1, 1);
  const double m1 = 1, m2 = 2, r = 0.1, off = 0.1;
  scene.balls = {ball(-1, off, 2, 0, r, m1), ball(0, 0, 0, 0, r, m2)};
  World world(scene);
  const Vec3 p0 = world.momentum();
  const double e0 = world.energy().kinetic;
  for (int k = 0; k < 100; ++k)
    world.step();
  ASSERT_EQ(world.stats().events, 1u);
  EXPECT_LT((world.momentum() - p0).norm(), 1e-14);
  EXPECT_NEAR(world.energy().kinetic, e0, 1e-14 * e0);
  // closed form: the normal at contact and the impulse along it
  const Vec3 n = Vec3(std::sqrt(4 * r * r - off * off), -off, 0) / (2 * r);
  const double J = 2 * m1 * m2 / (m1 + m2) * Vec3(2, 0, 0).dot(n);
  EXPECT_TRUE(world.balls()[1].velocity.isApprox(J / m2 * n, 1e-13));
  EXPECT_TRUE(world.balls()[0].velocity.isApprox(Vec3(2, 0, 0) - J / m1 * n, 1e-13));
}

TEST(Restitution, ScalesTheClosingSpeed)
{
  for (double e : {0.0, 0.5, 0.9})
  {
    Scene scene = flatScene(-3, 3, -1, 1);
    scene.restitution = e;
    scene.balls = {ball(-1, 0, 2, 0), ball(0, 0, 0, 0, 0.1, 3)};
    World world(scene);
    for (int k = 0; k < 100; ++k)
      world.step();
    const auto& b = world.balls();
    EXPECT_NEAR(b[1].velocity.x() - b[0].velocity.x(), e * 2, 1e-12) << "e = " << e;
    EXPECT_NEAR(b[0].velocity.x() + 3 * b[1].velocity.x(), 2, 1e-12) << "e = " << e;
  }
}

TEST(CollisionImpulse, ConservesEnergyWithDifferentTangentDirections)
{
  // On a curved floor each ball is pushed along its own tangent part of the normal.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k)
  {
    const Vec3 t1(u(rng), u(rng), u(rng)), t2(u(rng), u(rng), u(rng));
    Vec3 v1(u(rng), u(rng), u(rng)), v2(u(rng), u(rng), u(rng));
    const double m1 = 0.1 + std::abs(u(rng)), m2 = 0.1 + std::abs(u(rng));
    const double closing = v1.dot(t1) - v2.dot(t2);
    if (closing <= 0)
      continue;
    const double before = m1 * v1.squaredNorm() + m2 * v2.squaredNorm();
    const double J = collisionImpulse(closing, 1 / m1, t1, 1 / m2, t2, 1.0);
    v1 -= J / m1 * t1;
    v2 += J / m2 * t2;
    EXPECT_NEAR(m1 * v1.squaredNorm() + m2 * v2.squaredNorm(), before, 1e-12 * before);
    EXPECT_NEAR(v1.dot(t1) - v2.dot(t2), -closing, 1e-12);  // e = 1 reverses the closing speed
  }
}
