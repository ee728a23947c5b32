// What balls move on, asked as the step asks it: on a plane and on the bowl (a curved
// floor), against closed forms.
#include "fixtures.hpp"

#include "ball_collision_sim/core/ground.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

TEST(Ground, OnASlopedPlane)
{
  FloorDef f;
  f.point = Vec3(-2, -2, 0);
  f.u = Vec3(4, 0, -1);  // falls 1 m in 4 m along +x
  f.v = Vec3(0, 4, 0);
  const Vec3 g(0, 0, -9.81);
  const Ground ground(f, g, StepSettings());
  const Vec3 n = f.u.cross(f.v).normalized();
  EXPECT_FALSE(ground.straight());
  EXPECT_FALSE(ground.bends());
  EXPECT_EQ(ground.up(), Vec3(0, 0, 1));  // against gravity; the normals face that way
  EXPECT_GT(n.dot(ground.up()), 0);
  const Vec2 guess(0.5, 0.5);
  // a centre put back on the plane: r above it along the normal, moved along the normal
  const Vec3 q(0.3, -0.7, 2.0);
  const Vec3 c = ground.land(q, 0.25, guess);
  EXPECT_NEAR((c - f.point).dot(n), 0.25, 1e-15);
  EXPECT_LT((c - q).cross(n).norm(), 1e-15);
  EXPECT_EQ(ground.normalAt(q, guess), n);
  // along the floor; gravity along it is g sin(atan(1/4))
  const Vec3 w(1, 2, 3);
  EXPECT_NEAR(ground.along(w, n).dot(n), 0, 1e-15);
  EXPECT_NEAR(ground.gravityAlong(n), 9.81 * std::sin(std::atan(0.25)), 1e-14);
  // a step's end is put on the plane; the foot parameters of a centre outside it
  const Ground::End end = ground.end(q, 0.25, guess);
  EXPECT_EQ(end.centre, c);
  EXPECT_EQ(end.normal, n);
  // (the plane spans x in [-2, 2]: a centre at x = 2.5 is beside it)
  EXPECT_EQ(ground.whyOff(c, 0.25, guess, {}), "");
  EXPECT_EQ(ground.whyOff(Vec3(2.5, 0, 0), 0.25, guess, {}).rfind("left the floor (its foot point at u = ", 0), 0u);
  // a plane square to gravity: straight lines
  f.u = Vec3(4, 0, 0);
  EXPECT_TRUE(Ground(f, g, StepSettings()).straight());
}

TEST(Ground, OnTheBowl)
{
  // z = a (x^2 + y^2), a = 4 h / L^2
  const double a = 4 * 0.5 / 16;
  const Vec3 g(0, 0, -9.81);
  const Ground ground(bowl(4, 0.5), g, StepSettings());
  EXPECT_TRUE(ground.bends());
  EXPECT_FALSE(ground.straight());
  Vec2 guess(0.5, 0.5);
  const Vec3 q(0.8, -0.6, 0.5);
  const Vec3 c = ground.landKeepingFoot(q, 0.1, guess);
  // the foot point kept is on the paraboloid, and the centre one radius above it along
  // the normal there, which is (-2 a x, -2 a y, 1) normalised
  const Floor& floor = *ground.floor();
  const Vec3 foot = floor.point(guess);
  EXPECT_NEAR(foot.z(), a * (foot.x() * foot.x() + foot.y() * foot.y()), 1e-12);
  const Vec3 n = Vec3(-2 * a * foot.x(), -2 * a * foot.y(), 1).normalized();
  EXPECT_LT((c - (foot + 0.1 * n)).norm(), 1e-12);
  EXPECT_LT((ground.normalAt(c, guess) - n).norm(), 1e-12);
  EXPECT_LT((ground.normalUnder(guess) - n).norm(), 1e-12);
  // gravity along the floor there: g sin(slope), tan(slope) = 2 a rho
  const double rho = std::hypot(foot.x(), foot.y());
  EXPECT_NEAR(ground.gravityAlong(n), 9.81 * std::sin(std::atan(2 * a * rho)), 1e-12);
  // a step's end on a curved floor stays where its chord ends; its foot and normal found
  const Ground::End end = ground.end(c, 0.1, guess);
  EXPECT_EQ(end.centre, c);
  EXPECT_LT((end.normal - n).norm(), 1e-12);
  EXPECT_LT((end.foot - guess).norm(), 1e-12);
  // on a curved floor the kept foot point says whether the ball is on it
  EXPECT_EQ(ground.whyOff(c, 0.1, guess, {}), "");
  EXPECT_NE(ground.whyOff(c, 0.1, Vec2(1.01, 0.5), {}), "");
  // a ball that has not moved since its foot point was found (asleep): the same end,
  // bit for bit, without the search; the normal only when asked for
  const Ground::End still = ground.stillEnd(c, 0.1, end.foot, true);
  const Ground::End again = ground.end(c, 0.1, end.foot);
  EXPECT_EQ(still.centre, again.centre);
  EXPECT_EQ(still.foot, again.foot);
  EXPECT_EQ(still.normal, again.normal);
  EXPECT_EQ(ground.stillEnd(c, 0.1, end.foot, false).normal, Vec3::Zero());
  EXPECT_EQ(ground.stillEnd(c, 0.1, end.foot, false).centre, c);
}

TEST(Ground, WithoutAFloor)
{
  const Ground ground(std::nullopt, Vec3(0, 0, -2), StepSettings());
  EXPECT_FALSE(ground.floor().has_value());
  EXPECT_EQ(ground.up(), Vec3(0, 0, 1));
  const Vec3 q(1, 2, 3);
  EXPECT_EQ(ground.land(q, 0.5, Vec2(0.5, 0.5)), q);
  EXPECT_EQ(ground.along(q, ground.up()), q);
  EXPECT_EQ(ground.gravityAlong(ground.up()), 2.0);
  EXPECT_FALSE(ground.straight());
  EXPECT_TRUE(Ground(std::nullopt, Vec3::Zero(), StepSettings()).straight());
  // without walls nothing bounds a ball; with them, the box they span (a ball may reach
  // one radius beyond it)
  EXPECT_FALSE(ground.bounded({}));
  EXPECT_EQ(ground.whyOff(Vec3(1e9, 0, 0), 0.5, Vec2::Zero(), {}), "");
  const Ground::Bounds box{true, Vec3(0, 0, 0), Vec3(2, 2, 2)};
  EXPECT_TRUE(ground.bounded(box));
  EXPECT_EQ(ground.whyOff(Vec3(2.4, 1, 1), 0.5, Vec2::Zero(), box), "");
  EXPECT_EQ(ground.whyOff(Vec3(2.6, 1, 1), 0.5, Vec2::Zero(), box), "left the walls' bounds");
  EXPECT_EQ(ground.whyOff(Vec3(1, 1, -0.6), 0.5, Vec2::Zero(), box), "left the walls' bounds");
}

TEST(Ground, VelocityAlongTheWayAndTurnsThatKeepTheSpeed)
{
  FloorDef f;
  f.point = Vec3(-2, -2, 0);
  f.u = Vec3(4, 0, -1);
  f.v = Vec3(0, 4, 0);
  const Vec3 g(0, 0, -9.81);
  const Ground slope(f, g, StepSettings());
  const Vec3 n = f.u.cross(f.v).normalized();
  const Vec3 gt = g - g.dot(n) * n;
  // on the exact path p0 + v0 t + g_t t^2 / 2 the velocity is v0 + g_t t, whose speed
  // is also the one the energy gives there
  const Vec3 p0 = slope.land(Vec3(0, 0, 1), 0.1, Vec2(0.5, 0.5));
  const Vec3 v0 = Vec3(0.3, 1.2, 0) - Vec3(0.3, 1.2, 0).dot(n) * n;
  const double t = 0.37;
  const Vec3 p = p0 + t * v0 + (0.5 * t * t) * gt;
  const Vec3 v = slope.velocityAt(v0, t, p0, p, n);
  EXPECT_LT((v - (v0 + t * gt)).norm(), 1e-14);
  // where the chord was cut short of that point, the speed is the one its energy gives there
  const Vec3 short_of = p0 + 0.5 * (p - p0);
  const double energy_speed = std::sqrt(v0.squaredNorm() + 2 * g.dot(short_of - p0));
  EXPECT_NEAR(slope.velocityAt(v0, t, p0, short_of, n).norm(), energy_speed, 1e-14);
  // a turn keeps the speed where gravity pulls along the floor ...
  const Vec3 before(1, 2, 0), after(0.5, -0.25, 0);
  EXPECT_NEAR(slope.turned(before, after).norm(), before.norm(), 1e-15);
  EXPECT_LT(slope.turned(before, after).normalized().cross(after.normalized()).norm(), 1e-15);
  EXPECT_EQ(slope.turned(before, Vec3::Zero()), Vec3::Zero());
  // ... and on a level plane a ball keeps its velocity along the floor, wherever the
  // chord took it, and a turn is what it is
  f.u = Vec3(4, 0, 0);
  const Ground level(f, g, StepSettings());
  const Vec3 up(0, 0, 1);
  EXPECT_EQ(level.velocityAt(Vec3(1, 2, 0), t, p0, p0 + Vec3(5, 0, 0), up), Vec3(1, 2, 0));
  EXPECT_EQ(level.turned(before, after), after);
}
