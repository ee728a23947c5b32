// The commit stage's own arithmetic (src/core/step/rolling.hpp) on its own: the turn of
// a ball rolling without slip against the closed form of a rotation by |d| / r, the
// series it takes sin and cos from.
#include "core/step/rolling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace ball_collision_sim::core;

namespace
{
constexpr double kPi = 3.14159265358979323846;

Vec3 randomUnit(std::mt19937_64& rng)
{
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v.normalized();
}

Quat randomOrientation(std::mt19937_64& rng)
{
  std::normal_distribution<double> g;
  Quat q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q;
}

/// The rotation angle between two orientations (0 when they are the same turn; q and -q
/// are).
double angleBetween(const Quat& p, const Quat& q) { return 2 * std::asin(std::min(1.0, (p * q.conjugate()).vec().norm())); }
}  // namespace

TEST(SincCosOfSquare, MatchesSinAndCosOnBothSidesOfTheSeriesLimit)
{
  // The series hold for x^2 <= 1/4; past it sin and cos are called. Both sides of the
  // limit, and near zero, where sin(x) / x must not be computed as such.
  double sinc = 0, c = 0;
  step::sincCosOfSquare(0.0, sinc, c);
  EXPECT_EQ(sinc, 1.0);
  EXPECT_EQ(c, 1.0);
  for (int k = 1; k <= 4000; ++k)
  {
    const double y = k * 1e-3;  // x^2 from 1e-3 to 4: x up to 2
    const double x = std::sqrt(y);
    step::sincCosOfSquare(y, sinc, c);
    ASSERT_NEAR(sinc, std::sin(x) / x, 6e-16) << "x^2 = " << y;
    ASSERT_NEAR(c, std::cos(x), 6e-16) << "x^2 = " << y;
  }
  for (const double y : {1e-300, 1e-30, 1e-16, 1e-8})
  {
    step::sincCosOfSquare(y, sinc, c);
    EXPECT_NEAR(sinc, 1 - y / 6, 1e-16) << y;
    EXPECT_NEAR(c, 1 - y / 2, 1e-16) << y;
  }
}

TEST(Rolled, TurnsByTheMoveOverTheRadiusAboutTheFloorNormalCrossTheMove)
{
  // Against the closed form: a turn by |n x d| / r about n x d, after the orientation it
  // had; on floors turned every way, moves of 1e-9 to 6 radii (both ways of computing
  // the half angle), some with a part along the normal, which does not roll the ball.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 20000; ++trial)
  {
    const Vec3 n = randomUnit(rng);
    const double radius = 0.01 + 2 * unit(rng);
    const double length = radius * std::pow(10.0, -9 + 9.8 * unit(rng));
    const Vec3 tangent = randomUnit(rng).cross(n).normalized();
    const Vec3 d = length * tangent + (trial % 3 == 0 ? 0.3 * length * unit(rng) : 0.0) * n;
    const Quat q0 = randomOrientation(rng);
    const Quat q = step::rolled(q0, n, d, radius);
    const Vec3 axis = n.cross(d);
    const Quat expected = Quat(Eigen::AngleAxisd(axis.norm() / radius, axis.normalized())) * q0;
    ASSERT_LT(angleBetween(q, expected), 1e-14) << "trial " << trial << ", |d| / r = " << length / radius;
    ASSERT_NEAR(q.norm(), 1.0, 4.5e-16) << "trial " << trial;
  }
}

TEST(Rolled, TurnsTheWayAWheelDoesWithoutSlip)
{
  // A ball rolled a quarter of its girth forward brings the point that was in front of it
  // down to the floor; half its girth, the point on the floor to the top; a whole girth,
  // back as it was. A ball that turned the other way (or slid) would bring the front up.
  const double r = 0.25;
  const Vec3 n = Vec3(0.2, -0.1, 1).normalized();
  const Vec3 forward = n.cross(Vec3::UnitX()).normalized();
  const Quat q0 = Quat::Identity();
  const Quat quarter = step::rolled(q0, n, (kPi * r / 2) * forward, r);
  EXPECT_LT((quarter * forward - (-n)).norm(), 1e-14);
  const Quat half = step::rolled(q0, n, (kPi * r) * forward, r);
  EXPECT_LT((half * (-n) - n).norm(), 1e-14);
  const Quat whole = step::rolled(q0, n, (2 * kPi * r) * forward, r);
  EXPECT_LT(angleBetween(whole, q0), 1e-14);
}

TEST(Rolled, AMillionSmallRollsAddUpToTheirSumAndStayUnit)
{
  // A ball rolled once round its girth in 10^6 steps of one step's size: back where it
  // began, the round-off of the steps adding up, not growing; unit length kept throughout.
  const double r = 0.1;
  const Vec3 n = Vec3::UnitZ();
  const Vec3 d = (2 * kPi * r / 1e6) * Vec3(1, 2, 0).normalized();
  Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 1, 1).normalized()));
  const Quat start = q;
  double worst_norm = 0;
  for (int k = 0; k < 1000000; ++k)
  {
    q = step::rolled(q, n, d, r);
    worst_norm = std::max(worst_norm, std::abs(q.norm() - 1));
  }
  EXPECT_LT(worst_norm, 4.5e-16);
  EXPECT_LT(angleBetween(q, start), 1e-9);
}

TEST(Rolled, NoMoveAlongTheFloorLeavesTheOrientationAsItWas)
{
  // No move, or one straight along the normal: the very same orientation; along a normal
  // whose cross product with the move is round-off (of |d|), a turn of that round-off
  // over the radius.
  const Quat q0(0.5, 0.5, -0.5, 0.5);
  for (const Vec3& d : {Vec3(Vec3::Zero()), Vec3(0, 0, 2.5), Vec3(0, 0, -1e-3)})
  {
    const Quat q = step::rolled(q0, Vec3::UnitZ(), d, 0.3);
    EXPECT_EQ(q.coeffs(), q0.coeffs()) << d.transpose();
  }
  const Vec3 n(0, 0.6, 0.8);
  for (const double along : {2.5, -1e-3, 1e3})
    EXPECT_LT(angleBetween(step::rolled(q0, n, along * n, 0.3), q0),
              1e-15 + 8 * std::numeric_limits<double>::epsilon() * std::abs(along) / 0.3)
        << along;
}
