#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <limits>

namespace ball_collision_sim::core
{
/// The planar motion dq/dt = a - c q / |q| (a constant vector, c > 0 a constant rate),
/// solved exactly: a puck sliding across an incline under Coulomb friction. On a tilted
/// plane it is the slip of a sliding ball (a = g_t, c = mu_s g_n (1 + 1/k)) and the
/// velocity of a rolling one under rolling resistance (a = g_t / (1 + k), c = mu_r g_n):
/// q turns toward a as it goes.
///
/// With phi the angle from a to q, G = |a|, lambda = c / G and rho = tan(phi / 2) /
/// tan(phi0 / 2), which falls from 1 as time goes on, the components along a and across
/// it are
///   q_x = (A rho^(lambda - 1) - B rho^(lambda + 1)) / 2,   q_y = q_y0 rho^lambda,
/// A = |q0| + q_x0, B = |q0| - q_x0 (so A B = q_y0^2), and time and the integral of q are
/// sums of I(e, rho) = (1 - rho^e) / e (ln(1 / rho) at e = 0):
///   t = (A I(lambda - 1) + B I(lambda + 1)) / (2 G),
///   Q_x = (A^2 I(2 lambda - 2) - B^2 I(2 lambda + 2)) / (4 G),
///   Q_y = q_y0 (A I(2 lambda - 1) + B I(2 lambda + 1)) / (2 G).
/// A time is turned into rho by Newton's method on ln(1 / rho), kept bracketed. Where
/// lambda > 1, q reaches 0 at t(rho = 0), endTime(); where lambda <= 1 it never does.
/// The formulas hold along a's line too (q_y0 = 0: A or B is 0), where q does not turn.
class TurningDrag
{
public:
  TurningDrag() = default;
  /// q0 and a in one plane, a != 0, c > 0, q0 != 0 (else nothing is set, and at() is not
  /// to be asked).
  TurningDrag(const Vec3& q0, const Vec3& a, double c);

  /// q0 has a part across a, so that q turns (false for a default one, and along a's
  /// line, where the accelerations are constant and at() holds all the same).
  bool turns() const { return qy0_ > 0; }
  /// When |q| reaches 0 [s]: infinite where it never does (lambda <= 1).
  double endTime() const { return end_; }
  /// q(t) and its integral from 0 to t; past endTime() q is 0 and the integral stays.
  void at(double t, Vec3& q, Vec3& integral) const;

private:
  /// ln(1 / rho) at time t, t in (0, endTime()).
  double logAt(double t) const;
  /// t at ln(1 / rho) = y, and dt/dy.
  double timeAt(double y) const;
  double rateAt(double y) const;

  Vec3 ex_ = Vec3::Zero();  ///< a / |a|
  Vec3 ey_ = Vec3::Zero();  ///< q0's part across a, unit (zero where there is none)
  double g_ = 0.0;          ///< |a|
  double lambda_ = 0.0;     ///< c / |a|
  double a_ = 0.0, b_ = 0.0, qy0_ = 0.0;
  double end_ = std::numeric_limits<double>::infinity();
};
}  // namespace ball_collision_sim::core
