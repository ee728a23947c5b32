#pragma once

#include "ball_collision_sim/core/types.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <array>
#include <cmath>
#include <optional>

namespace ball_collision_sim::core
{
/// Earliest t in [0, t_max] at which |d + t e| = reach while the distance shrinks:
/// the smaller root of <e,e> t^2 + 2 <e,d> t + <d,d> - reach^2 = 0, in the stable form
/// t = c / (-h + sqrt(h^2 - a c)), h = <e, d>. Already touching and closing by more
/// than slop * reach over [0, t_max]: t = 0 (StepSettings::closing_slop).
/// Ball-ball: d = p1 - p2, e = ds1 - ds2, reach = r1 + r2.
inline std::optional<double> sphereSweep(const Vec3& d, const Vec3& e, double reach, double t_max, double slop)
{
  const double c = d.squaredNorm() - reach * reach;
  const double h = e.dot(d);  // half the linear coefficient: one convention throughout
  if (c <= 0)
  {
    // Touching (or overlapping by round-off): an impact now, if closing at all.
    if (-h * t_max > slop * reach * d.norm())
      return 0.0;
    return std::nullopt;
  }
  if (h >= 0)
    return std::nullopt;  // not approaching
  const double a = e.squaredNorm();
  const double disc = h * h - a * c;
  if (disc < 0)
    return std::nullopt;  // passes by
  // q > 0 because h < 0; c / q is the smaller root without cancellation.
  const double t = c / (-h + std::sqrt(disc));
  if (!(t <= t_max))
    return std::nullopt;
  return t;
}

/// The earliest t in [0, t_max] at which the polynomial a[0] + a[1] t + ... + a[4] t^4
/// (a[0] > 0) reaches zero, or none where it stays above. The polynomial is monotone
/// between the roots of its derivative, found the same way, so the first piece whose
/// ends differ in sign holds the root, which false position finds to the last bit: the
/// t returned is the last double at which the polynomial is still positive (or the
/// root itself where it is exactly zero there).
std::optional<double> firstRoot(const std::array<double, 5>& a, double t_max);

/// As sphereSweep(), for a relative motion under constant acceleration,
/// |d + t e + t^2 c| = reach: the distance squared less reach^2 is a quartic in t.
/// Touching already: an impact now where the motion's deepest approach over [0, t_max]
/// passes slop * reach, or later where it first moves apart and comes back. With c = 0
/// it is sphereSweep() itself.
std::optional<double> sphereSweepAccelerated(const Vec3& d, const Vec3& e, const Vec3& c, double reach, double t_max,
                                             double slop);

/// The earliest t in [0, t_max] at which the point d + t e + t^2 c comes within `radius`
/// of the origin (a pocket's circle, all three in its plane): 0 where it is within already.
inline std::optional<double> circleEntry(const Vec3& d, const Vec3& e, const Vec3& c, double radius, double t_max)
{
  if (d.squaredNorm() <= radius * radius)
    return 0.0;
  return sphereSweepAccelerated(d, e, c, radius, t_max, 0.0);
}

/// First contact of a ball with a wall.
struct WallHit
{
  double t = 0.0;                         ///< in units of the motion parameter
  WallFeature feature = WallFeature::kFace;
  Vec3 normal = Vec3::UnitZ();            ///< unit, from the wall toward the ball's centre
};

/// Earliest t in [0, t_max] at which a ball of radius r at p moving by e per unit t
/// touches the wall's face, one of its four edges or one of its four corners (already
/// touching: as sphereSweep() with `slop`).
std::optional<WallHit> sweepWall(const Wall& wall, const Vec3& p, const Vec3& e, double r, double t_max,
                                 double slop);
/// The same for a ball moving by p + t e + t^2 c (constant acceleration).
std::optional<WallHit> sweepWall(const Wall& wall, const Vec3& p, const Vec3& e, const Vec3& c, double r,
                                 double t_max, double slop);
}  // namespace ball_collision_sim::core
