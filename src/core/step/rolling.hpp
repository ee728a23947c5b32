// The commit stage's own arithmetic, apart from the world so that it is tested on its
// own (test/test_commit.cpp): a ball's turn as it rolls without slip. Reads and writes
// only its arguments. Not part of the public interface.
#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <tuple>
#include <vector>

namespace ball_collision_sim::core::step
{
/// sin(x) / x and cos(x) from y = x^2 (both are even in x): series where |x| <= 1/2,
/// sin and cos elsewhere; so a caller that has x^2 takes no square root. The series are
/// summed in pairs of terms (Estrin's scheme) so that they take a few dependent steps
/// rather than one per term.
inline void sincCosOfSquare(double y, double& sinc, double& c)
{
  if (!(y <= 0.25))
  {
    const double x = std::sqrt(y);
    sinc = std::sin(x) / x;
    c = std::cos(x);
    return;
  }
  // Taylor series to x^16 and x^18: the first term left out is below 3e-23 for |x| <= 1/2.
  // s[k] = (-1)^k / (2k + 1)!, c[k] = (-1)^k / (2k)!
  constexpr double s1 = -1.0 / 6, s2 = 1.0 / 120, s3 = -1.0 / 5040, s4 = 1.0 / 362880, s5 = -1.0 / 39916800,
                   s6 = 1.0 / 6227020800, s7 = -1.0 / 1307674368000, s8 = 1.0 / 355687428096000;
  constexpr double c1 = -1.0 / 2, c2 = 1.0 / 24, c3 = -1.0 / 720, c4 = 1.0 / 40320, c5 = -1.0 / 3628800,
                   c6 = 1.0 / 479001600, c7 = -1.0 / 87178291200, c8 = 1.0 / 20922789888000,
                   c9 = -1.0 / 6402373705728000;
  const double x2 = y, x4 = x2 * x2, x8 = x4 * x4;
  sinc = ((1 + s1 * x2) + x4 * (s2 + s3 * x2)) + x8 * (((s4 + s5 * x2) + x4 * (s6 + s7 * x2)) + x8 * s8);
  c = ((1 + c1 * x2) + x4 * (c2 + c3 * x2)) + x8 * (((c4 + c5 * x2) + x4 * (c6 + c7 * x2)) + x8 * (c8 + c9 * x2));
}

/// `orientation` after the ball of `radius` rolls without slip by `d` on a floor with unit
/// normal `normal`: turned by |n x d| / r about n x d (|n x d| is the move's length along
/// the floor). The result is a unit quaternion again to round-off.
inline Quat rolled(const Quat& orientation, const Vec3& normal, const Vec3& d, double radius)
{
  const double half_inv_radius = 0.5 / radius;
  const Vec3 axis = normal.cross(d);
  const double axis_squared = axis.squaredNorm();
  if (!(axis_squared > 0))
    return orientation;
  // the half angle x = |n x d| / 2r; sin(x) / |n x d| = sinc(x) / 2r
  double sinc_half = 1, cos_half = 1;
  sincCosOfSquare(axis_squared * (half_inv_radius * half_inv_radius), sinc_half, cos_half);
  const Vec3 k = (sinc_half * half_inv_radius) * axis;
  Quat q = Quat(cos_half, k.x(), k.y(), k.z()) * orientation;
  // back to unit length: the product of unit quaternions is off by round-off only, so one
  // Newton step of 1/sqrt does
  q.coeffs() *= 1.5 - 0.5 * q.coeffs().squaredNorm();
  return q;
}

}  // namespace ball_collision_sim::core::step
