#include "ball_collision_sim/core/step_settings.hpp"
#include "ball_collision_sim/core/time_of_impact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace ball_collision_sim::core;
/// The step's own slop for touching objects (StepSettings::closing_slop).
const double kSlop = StepSettings().closing_slop;

TEST(SphereSweep, HeadOnMeetsAtGapOverClosingSpeed)
{
  // centres 1 m apart, radii sum 0.3, closing at 0.5 m per unit t: t = 0.7 / 0.5
  const auto t = sphereSweep(Vec3(-1, 0, 0), Vec3(0.5, 0, 0), 0.3, 10, kSlop);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 1.4, 1e-15);
}

TEST(SphereSweep, NoImpactWhenSeparatingPassingByOrTooLate)
{
  EXPECT_FALSE(sphereSweep(Vec3(-1, 0, 0), Vec3(-0.5, 0, 0), 0.3, 10, kSlop));  // separating
  EXPECT_FALSE(sphereSweep(Vec3(-1, 0.31, 0), Vec3(1, 0, 0), 0.3, 10, kSlop));  // passes by
  EXPECT_FALSE(sphereSweep(Vec3(-1, 0, 0), Vec3(0.5, 0, 0), 0.3, 1.39, kSlop));  // after t_max
  EXPECT_FALSE(sphereSweep(Vec3(-1, 0, 0), Vec3(0, 0, 0), 0.3, 10, kSlop));     // no relative motion
}

TEST(SphereSweep, TouchingAndClosingIsAnImpactNow)
{
  EXPECT_EQ(*sphereSweep(Vec3(-0.3, 0, 0), Vec3(1, 0, 0), 0.3, 1, kSlop), 0.0);
  EXPECT_FALSE(sphereSweep(Vec3(-0.3, 0, 0), Vec3(-1, 0, 0), 0.3, 1, kSlop));
  // sliding past each other while touching is not an impact
  EXPECT_FALSE(sphereSweep(Vec3(-0.3, 0, 0), Vec3(0, 1, 0), 0.3, 1, kSlop));
}

TEST(SphereSweep, GrazingImpactsTouchAtTheContactDistance)
{
  // offsets ever closer to the sum of radii: the root found must put the centres at
  // exactly that distance, to round-off
  const double R = 0.2;
  for (int k = 1; k <= 14; ++k)
  {
    const double h = R * (1 - std::pow(10.0, -k));
    const auto t = sphereSweep(Vec3(-1, h, 0), Vec3(1.3, 0, 0), R, 10, kSlop);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR((Vec3(-1, h, 0) + *t * Vec3(1.3, 0, 0)).norm(), R, 1e-15) << k;
    // the time itself is as well conditioned as the graze allows: the distance changes
    // at the rate sqrt(R^2 - h^2) / R there
    const double along = std::sqrt((R - h) * (R + h));
    EXPECT_NEAR(*t, (1 - along) / 1.3, 1e-13 + 1e-15 * R / along) << k;
  }
}

TEST(SphereSweep, RandomCasesTouchAtTheRootAndNeverBefore)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int found = 0;
  for (int k = 0; k < 5000; ++k)
  {
    const Vec3 d(u(rng), u(rng), u(rng)), e(u(rng), u(rng), u(rng));
    const double reach = 0.5 * std::abs(u(rng));
    const auto t = sphereSweep(d, e, reach, 1.0, kSlop);
    // the closed form: the earliest t in [0, 1] with |d + t e| <= reach
    double first = -1;
    if (d.norm() <= reach && e.dot(d) < 0)
      first = 0;  // already touching and closing
    else if (d.norm() > reach)
    {
      const double a = e.dot(e), hb = e.dot(d), c = d.dot(d) - reach * reach, disc = hb * hb - a * c;
      if (hb < 0 && disc >= 0)
      {
        const double r = (-hb - std::sqrt(disc)) / a;
        if (r <= 1)
          first = r;
      }
    }
    if (first < 0)
    {
      EXPECT_FALSE(t) << k;
      continue;
    }
    ++found;
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, first, 1e-9) << k;
    if (first > 0)
    {
      EXPECT_NEAR((d + *t * e).norm(), reach, 1e-12) << k;
    }
  }
  EXPECT_GT(found, 100);
}

namespace
{
Wall unitWall()
{
  // the square [0, 1] x [0, 1] in the plane z = 0
  return Wall(0, WallDef{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), {}}, 1.0);
}
}  // namespace

TEST(SweepWall, FaceFromEitherSide)
{
  const Wall w = unitWall();
  auto hit = sweepWall(w, Vec3(0.5, 0.5, 2), Vec3(0, 0, -1), 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kFace);
  EXPECT_NEAR(hit->t, 1.75, 1e-15);
  EXPECT_TRUE(hit->normal.isApprox(Vec3(0, 0, 1)));
  hit = sweepWall(w, Vec3(0.5, 0.5, -2), Vec3(0, 0, 1), 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1.75, 1e-15);
  EXPECT_TRUE(hit->normal.isApprox(Vec3(0, 0, -1)));
}

TEST(SweepWall, EdgeWhenPassingBesideTheFace)
{
  const Wall w = unitWall();
  // moving down at x = 1.1: misses the face, touches the edge x = 1 (a cylinder of
  // radius 0.25): contact when the centre is at height sqrt(0.25^2 - 0.1^2)
  const auto hit = sweepWall(w, Vec3(1.1, 0.5, 2), Vec3(0, 0, -1), 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kEdge);
  const double z = std::sqrt(0.25 * 0.25 - 0.1 * 0.1);
  EXPECT_NEAR(hit->t, 2 - z, 1e-14);
  EXPECT_TRUE(hit->normal.isApprox(Vec3(0.1, 0, z) / 0.25, 1e-12));
}

TEST(SweepWall, CornerWhenPassingBesideTwoEdges)
{
  const Wall w = unitWall();
  const auto hit = sweepWall(w, Vec3(1.1, 1.1, 2), Vec3(0, 0, -1), 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kCorner);
  const double z = std::sqrt(0.25 * 0.25 - 0.02);
  EXPECT_NEAR(hit->t, 2 - z, 1e-14);
  EXPECT_FALSE(sweepWall(w, Vec3(1.2, 1.2, 2), Vec3(0, 0, -1), 0.25, 10, kSlop));  // sqrt(0.08) > 0.25
}

TEST(SweepWall, NoTunnellingAtAnySpeed)
{
  const Wall w = unitWall();
  // 1e6 m per unit t through a wall of zero thickness
  const auto hit = sweepWall(w, Vec3(0.5, 0.5, 3), Vec3(0, 0, -1e6), 0.01, 1, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, (3 - 0.01) / 1e6, 1e-20);
}

// A ball that comes within r of the wall's plane just beside the face, and then moves on
// over the face with a slow drift into it (a ball that leaned on the wall's edge, going
// back along the wall under a blocked direction a hair off the face's normal): the edge's
// cylinder is only grazed, by round-off, so the face must be met where the ball comes over
// it. No path may end deeper in the wall than round-off without an impact before.
TEST(SweepWall, GrazingAnEdgeIntoTheFaceIsMet)
{
  const Wall w = unitWall();
  const double r = 0.25;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int met = 0;
  for (int k = 0; k < 2000; ++k)
  {
    // where the plane is crossed, beside the face by `beside` (down to 1e-12) along x
    const double beside = std::pow(10.0, -12 + 11 * unit(rng));
    const double drift = std::pow(10.0, -10 + 7 * unit(rng));  // down, per unit t
    const double speed = 0.5 + unit(rng);                     // along -x
    const bool accelerated = k % 2 == 1;
    const double t_cross = 0.2;
    const Vec3 e(-speed, 0.0, -drift);
    const Vec3 c = accelerated ? Vec3(0.0, 0.0, -drift * unit(rng)) : Vec3::Zero();
    const double z_cross = r;
    const Vec3 p(1 + beside + speed * t_cross, 0.5, z_cross + drift * t_cross - c.z() * t_cross * t_cross);
    const auto hit = sweepWall(w, p, e, c, r, 1.0, kSlop);
    const double until = hit ? hit->t : 1.0;
    if (hit)
    {
      // met touching, from its own side
      const Vec3 q = p + hit->t * e + (hit->t * hit->t) * c;
      EXPECT_NEAR((q - w.closestPoint(q)).norm(), r, 1e-9);
      EXPECT_GT(q.z(), 0.0);
      EXPECT_GT(hit->normal.z(), 0.0);
    }
    // the path up to the impact (or its end) stays out of the wall but for round-off
    double deepest = 0;
    for (int s = 0; s <= 400; ++s)
    {
      const double t = until * s / 400.0;
      const Vec3 q = p + t * e + (t * t) * c;
      deepest = std::max(deepest, r - (q - w.closestPoint(q)).norm());
    }
    EXPECT_LT(deepest, 1e-12) << "beside " << beside << " drift " << drift << " accelerated " << accelerated;
    met += hit ? 1 : 0;
  }
  EXPECT_GT(met, 1900);
  // A ball that passes beside the edge with room to spare, crosses the plane beside the
  // face and comes over the face from behind meets nothing; straight, and falling past
  // the edge under acceleration.
  EXPECT_FALSE(sweepWall(w, Vec3(1.1, 0.5, 0.05), Vec3(-3, 0, -3), Vec3::Zero(), 0.02, 0.04, kSlop));
  EXPECT_FALSE(sweepWall(w, Vec3(1.1, 0.5, 0.1), Vec3(-1, 0, 0), Vec3(0, 0, -100), 0.02, 0.3, kSlop));
}

// Random parallelograms in any orientation, and paths (straight and accelerated) that
// pass them nearest at a set depth: through the face, past an edge or a corner, along
// the plane just beyond the radius or just within it, away from it. Where sweepWall()
// reports an impact the ball touches the wall there and was clear of it before; where
// it reports none the path stays clear all along. (Paths that stay beyond the plane's
// reach, and impacts well inside the face, are decided without the edges and corners.)
TEST(SweepWall, RandomPathsMeetTheWallWhereTheyFirstTouchIt)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto direction = [&] {
    Vec3 d;
    do
      d = Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    while (d.norm() < 0.1);
    return Vec3(d.normalized());
  };
  const double depths[] = {-0.5, -1e-6, 1e-6, 0.5, 1.0};  // (of the radius: beyond it, > 0)
  int met = 0, missed = 0;
  for (int k = 0; k < 20000; ++k)
  {
    const Vec3 u = (0.3 + 2 * unit(rng)) * direction();
    Vec3 v = direction();
    v = (0.3 + 2 * unit(rng)) * Vec3(v - v.dot(u.normalized()) * u.normalized()).normalized();
    const Wall w(0, WallDef{Vec3(unit(rng), unit(rng), unit(rng)), u, v, {}}, 1.0);
    const double r = 0.01 + 0.3 * unit(rng);
    // the point nearest the wall's plane at t = 1/2: over the face, or past an edge or corner
    const double a = -0.3 + 1.6 * unit(rng), b = -0.3 + 1.6 * unit(rng);
    const double depth = depths[k % 5];
    const double side = unit(rng) < 0.5 ? -1.0 : 1.0;
    const Vec3 nearest = w.def.point + a * u + b * v + side * r * (1 + depth) * w.normal;
    // moving along the plane (nearest to it at t = 1/2) or across it, at speeds of 0.1 to 10
    const double speed = std::pow(10.0, -1 + 2 * unit(rng));
    Vec3 e = speed * direction();
    if (k % 3 != 2)
      e -= e.dot(w.normal) * w.normal;
    const Vec3 c = k % 4 == 3 ? Vec3(speed * speed * unit(rng) * direction()) : Vec3::Zero();
    const Vec3 p = nearest - 0.5 * e - 0.25 * c;
    const auto at = [&](double t) { return Vec3(p + t * e + (t * t) * c); };
    if (w.distance(p) < r * (1 + 1e-3))
      continue;  // (a start in or at the wall is a case of its own, above)
    const auto hit = sweepWall(w, p, e, c, r, 1.0, kSlop);
    const double until = hit ? hit->t : 1.0;
    if (hit)
    {
      EXPECT_NEAR(w.distance(at(hit->t)), r, 1e-9 * (1 + speed)) << "case " << k;
      ++met;
    }
    else
      ++missed;
    double deepest = -1;
    for (int s = 0; s <= 1000; ++s)
      deepest = std::max(deepest, r - w.distance(at(until * s / 1000.0)));
    EXPECT_LT(deepest, 1e-9 * (1 + speed)) << "case " << k << (hit ? " met" : " missed");
  }
  // (both kinds of answer are asked for)
  EXPECT_GT(met, 1000);
  EXPECT_GT(missed, 1000);
}

// A ball thrown up from below a shelf, past its edge, lands on top of it: it crosses the
// plane beside the face and comes back down to it from the other side, at the later
// root of z(t) = r.
TEST(SweepWall, ThrownPastAShelfsEdgeLandsOnTop)
{
  const Wall shelf = unitWall();  // (z = 0, x and y in [0, 1])
  const double r = 0.1;
  const Vec3 p(1.6, 0.5, -0.5), c(0, 0, -2);  // z = -0.5 + 4 t - 2 t^2
  const double t_land = (4 + std::sqrt(16 - 8 * (0.5 + r))) / 4;
  const Vec3 e(-(1.6 - 0.5) / t_land, 0, 4);  // over the shelf's middle as it comes down
  const auto hit = sweepWall(shelf, p, e, c, r, 3.0, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kFace);
  EXPECT_NEAR(hit->t, t_land, 1e-12);
  EXPECT_EQ(hit->normal, Vec3(0, 0, 1));
  // the same path turned over (thrown down from above past the edge, coming up from
  // below) meets the shelf's underside
  const auto under = sweepWall(shelf, Vec3(p.x(), p.y(), -p.z()), Vec3(e.x(), e.y(), -e.z()), -c, r, 3.0, kSlop);
  ASSERT_TRUE(under);
  EXPECT_NEAR(under->t, t_land, 1e-12);
  EXPECT_EQ(under->normal, Vec3(0, 0, -1));
}

TEST(FirstRoot, FindsTheEarliestRootOfAQuarticToTheLastBit)
{
  // -(t - 0.3)(t - 0.5)(t - 2)(t + 1) = -t^4 + 1.8 t^3 + 1.05 t^2 - 1.45 t + 0.3
  const std::array<double, 5> f{0.3, -1.45, 1.05, 1.8, -1.0};
  const auto t = firstRoot(f, 10.0);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 0.3, 1e-15);
  EXPECT_FALSE(firstRoot(f, 0.29));  // before it
  // none: t^2 + 1; a double root (a graze) is found, as well as it is conditioned
  EXPECT_FALSE(firstRoot({1.0, 0.0, 1.0, 0.0, 0.0}, 10.0));
  const auto graze = firstRoot({0.16, -0.8, 1.0, 0.0, 0.0}, 10.0);  // (t - 0.4)^2
  ASSERT_TRUE(graze);
  EXPECT_NEAR(*graze, 0.4, 1e-7);
  // the earliest of four roots in the interval, whatever the others
  const auto four = firstRoot({0.0105, -0.176, 0.86, -1.6, 1.0}, 1.0);  // roots 0.1, 0.3, 0.5, 0.7
  ASSERT_TRUE(four);
  EXPECT_NEAR(four.value(), 0.1, 1e-12);
}

TEST(SphereSweepAccelerated, MeetsAtTheClosedFormTimeUnderConstantAcceleration)
{
  // from rest 1 m apart, closing at 1 m/s^2 (c = a / 2): 1 - t^2 / 2 = 0.3
  const auto t = sphereSweepAccelerated(Vec3(-1, 0, 0), Vec3::Zero(), Vec3(0.5, 0, 0), 0.3, 10, kSlop);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, std::sqrt(1.4), 1e-15);
  // 0.5 apart, moving apart at 1, pulled back at 2 (c = -1): 0.5 + t - t^2 = 0.3
  const auto back = sphereSweepAccelerated(Vec3(0.5, 0, 0), Vec3(1, 0, 0), Vec3(-1, 0, 0), 0.3, 10, kSlop);
  ASSERT_TRUE(back);
  EXPECT_NEAR(*back, (1 + std::sqrt(1.8)) / 2, 1e-15);
  // touching and pulled in: an impact now; touching, thrown off and pulled back: later
  EXPECT_EQ(*sphereSweepAccelerated(Vec3(0.3, 0, 0), Vec3::Zero(), Vec3(-1, 0, 0), 0.3, 1, kSlop), 0.0);
  const auto returns = sphereSweepAccelerated(Vec3(0.3, 0, 0), Vec3(1, 0, 0), Vec3(-1, 0, 0), 0.3, 10, kSlop);
  ASSERT_TRUE(returns);
  EXPECT_NEAR(*returns, 1.0, 1e-15);
  // touching, closing in at first and pulled apart before the end: an impact now
  EXPECT_EQ(*sphereSweepAccelerated(Vec3(0.3, 0, 0), Vec3(-1, 0, 0), Vec3(1.2, 0, 0), 0.3, 1, kSlop), 0.0);
  // without acceleration it is sphereSweep, to the bit
  EXPECT_EQ(*sphereSweepAccelerated(Vec3(-1, 0.1, 0), Vec3(0.7, 0, 0), Vec3::Zero(), 0.3, 10, kSlop),
            *sphereSweep(Vec3(-1, 0.1, 0), Vec3(0.7, 0, 0), 0.3, 10, kSlop));
}

TEST(SphereSweepAccelerated, RandomCasesTouchAtTheRootAndNeverBefore)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int found = 0;
  for (int k = 0; k < 10000; ++k)
  {
    const Vec3 d(u(rng), u(rng), u(rng)), e(2 * u(rng), 2 * u(rng), 2 * u(rng)), c(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const double reach = 0.5 * std::abs(u(rng));
    if (d.norm() <= reach)
      continue;
    const auto at = [&](double t) { return (d + t * e + (t * t) * c).norm(); };
    const auto t = sphereSweepAccelerated(d, e, c, reach, 1.0, kSlop);
    // sampled: the distance stays above reach before the root, and reaches it there
    double first = -1;
    for (int s = 0; s <= 4000 && first < 0; ++s)
      if (at(s / 4000.0) < reach)
        first = s / 4000.0;
    if (!t)
    {
      EXPECT_LT(first, 0) << k;  // (a graze between samples may be missed by the samples)
      continue;
    }
    ++found;
    EXPECT_NEAR(at(*t), reach, 1e-12) << k;
    EXPECT_LE(*t, 1.0);
    if (first >= 0)
    {
      EXPECT_LE(*t, first) << k;
    }
    for (int s = 0; s < 200; ++s)
      EXPECT_GE(at(*t * s / 200.0), reach - 1e-12) << k;
  }
  EXPECT_GT(found, 200);  // (most random motions pass wide)
}

TEST(SweepWall, UnderConstantAccelerationAtTheClosedFormTimes)
{
  const Wall w = unitWall();
  const Vec3 down(0, 0, -1);  // c: falling from rest at 2 m/s^2
  // the face: 2 - t^2 = 0.25
  auto hit = sweepWall(w, Vec3(0.5, 0.5, 2), Vec3::Zero(), down, 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kFace);
  EXPECT_NEAR(hit->t, std::sqrt(1.75), 1e-15);
  // an edge: 2 - t^2 = sqrt(0.25^2 - 0.1^2)
  hit = sweepWall(w, Vec3(1.1, 0.5, 2), Vec3::Zero(), down, 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kEdge);
  EXPECT_NEAR(hit->t, std::sqrt(2 - std::sqrt(0.0525)), 1e-14);
  // a corner: 2 - t^2 = sqrt(0.25^2 - 0.02)
  hit = sweepWall(w, Vec3(1.1, 1.1, 2), Vec3::Zero(), down, 0.25, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kCorner);
  EXPECT_NEAR(hit->t, std::sqrt(2 - std::sqrt(0.0425)), 1e-14);
  // thrown up beside the wall: a parabola that clears its edge and comes down on its
  // face, where 0.5 + t - t^2 / 2 = 0.1
  hit = sweepWall(w, Vec3(-0.5, 0.5, 0.5), Vec3(0.3, 0, 1), Vec3(0, 0, -0.5), 0.1, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1 + std::sqrt(1.8), 1e-14);
  EXPECT_EQ(hit->feature, WallFeature::kFace);
  // touching the face, moving in and pulled out again before the end: an impact now
  hit = sweepWall(w, Vec3(0.5, 0.5, 0.25), Vec3(0, 0, -1), Vec3(0, 0, 1.2), 0.25, 1, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 0.0);
  // beside the face and within r of its plane (z = 0.05 < r = 0.1, x < 0): thrown up
  // and over toward the face, it leaves reach of the plane and comes back down on the
  // face, where 0.05 + t - t^2 = 0.1: the larger root, (1 + sqrt(0.8)) / 2
  hit = sweepWall(w, Vec3(-0.3, 0.5, 0.05), Vec3(0.5, 0, 1), Vec3(0, 0, -1), 0.1, 10, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kFace);
  EXPECT_NEAR(hit->t, (1 + std::sqrt(0.8)) / 2, 1e-14);
  // beside the edge y = z = 0 (x = -0.3 < 0, clear of its corner) and within r = 0.5
  // of its line: thrown away from the line and along it, the ball leaves reach of the
  // line and comes back to it over the edge, where the height 0.3 + 0.6 t - t^2 / 2
  // falls to 0.4 (0.3^2 + 0.4^2 = r^2): t = 1, at x = 0.7. (Taking the line's reach as
  // a contact already, a sweep sees the ball touching the line and moving off it, and
  // finds its return to where it started, t = 1.2, 0.1 deep.)
  hit = sweepWall(w, Vec3(-0.3, -0.3, 0.3), Vec3(1, 0, 0.6), Vec3(0, 0, -0.5), 0.5, 2, kSlop);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->feature, WallFeature::kEdge);
  EXPECT_NEAR(hit->t, 1.0, 1e-12);
  EXPECT_NEAR((hit->normal - Vec3(0, -0.6, 0.8)).norm(), 0.0, 1e-12);
  for (int k = 0; k <= 100; ++k)
  {
    // clear of the wall all the way there
    const double t = hit->t * k / 100;
    const Vec3 q = Vec3(-0.3, -0.3, 0.3) + t * Vec3(1, 0, 0.6) + (t * t) * Vec3(0, 0, -0.5);
    EXPECT_GE(w.distance(q), 0.5 - 1e-12) << "t = " << t;
  }
  // without acceleration it is the straight sweep, to the bit
  EXPECT_EQ(sweepWall(w, Vec3(1.1, 0.5, 2), Vec3(0, 0, -1), Vec3::Zero(), 0.25, 10, kSlop)->t,
            sweepWall(w, Vec3(1.1, 0.5, 2), Vec3(0, 0, -1), 0.25, 10, kSlop)->t);
}
