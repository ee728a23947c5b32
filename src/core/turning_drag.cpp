// The planar motion dq/dt = a - c q / |q| in closed form (TurningDrag): a puck sliding
// across an incline, a ball's slip or rolling velocity crossing a tilted plane's fall line.
#include "ball_collision_sim/core/turning_drag.hpp"

#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
namespace
{
/// (1 - rho^e) / e with rho = exp(-y), y >= 0: the integral of x^(e - 1) from rho to 1
/// (y itself at e = 0); expm1 keeps it exact where e y is small.
double integral(double e, double y)
{
  return e == 0 ? y : -std::expm1(-e * y) / e;
}
}  // namespace

TurningDrag::TurningDrag(const Vec3& q0, const Vec3& a, double c)
{
  g_ = a.norm();
  if (!(g_ > 0) || !(c > 0))
    return;
  ex_ = a / g_;
  const double qx0 = q0.dot(ex_);
  const Vec3 across = q0 - qx0 * ex_;
  qy0_ = across.norm();
  const double s0 = std::hypot(qx0, qy0_);
  if (!(s0 > 0))
    return;
  if (qy0_ > 0)
    ey_ = across / qy0_;
  // A = s0 + q_x0 and B = s0 - q_x0, the smaller from A B = q_y0^2 (no cancellation)
  if (qx0 >= 0)
  {
    a_ = s0 + qx0;
    b_ = qy0_ * qy0_ / a_;
  }
  else
  {
    b_ = s0 - qx0;
    a_ = qy0_ * qy0_ / b_;
  }
  lambda_ = c / g_;
  if (lambda_ > 1)
    end_ = (a_ / (lambda_ - 1) + b_ / (lambda_ + 1)) / (2 * g_);
}

double TurningDrag::timeAt(double y) const
{
  return (a_ * integral(lambda_ - 1, y) + b_ * integral(lambda_ + 1, y)) / (2 * g_);
}

double TurningDrag::rateAt(double y) const
{
  return (a_ * std::exp(-(lambda_ - 1) * y) + b_ * std::exp(-(lambda_ + 1) * y)) / (2 * g_);
}

double TurningDrag::logAt(double t) const
{
  // Newton's method on ln(t(y) / t), which is all but straight where t(y) grows as an
  // exponential (lambda < 1) and where it levels off toward the end (lambda > 1), kept in
  // a bracket [lo, hi] (t(lo) < t <= t(hi)) whose halving takes any step that leaves it;
  // down to the round-off of y. A t(y) past the largest double lies beyond the root.
  double lo = 0.0, hi = t / rateAt(0.0);
  while (timeAt(hi) < t && hi < std::numeric_limits<double>::max())
  {
    lo = hi;
    hi *= 2;
  }
  double y = hi;
  for (int pass = 0; pass < 200; ++pass)
  {
    const double at_y = timeAt(y);
    const double g = std::log(at_y / t);
    if (g == 0)
      return y;
    (g < 0 ? lo : hi) = y;
    double next = y - g * at_y / rateAt(y);
    if (!(next > lo && next < hi))
      next = 0.5 * (lo + hi);
    if (std::abs(next - y) <= 4 * std::numeric_limits<double>::epsilon() * next || next == lo || next == hi)
      return next;
    y = next;
  }
  return y;
}

void TurningDrag::at(double t, Vec3& q, Vec3& integral_q) const
{
  if (!(t > 0))
  {
    q = (0.5 * (a_ - b_)) * ex_ + qy0_ * ey_;
    integral_q = Vec3::Zero();
    return;
  }
  const double l = lambda_;
  const double y = t < end_ ? logAt(t) : std::numeric_limits<double>::infinity();
  const double qx = y < std::numeric_limits<double>::infinity()
                        ? 0.5 * (a_ * std::exp(-(l - 1) * y) - b_ * std::exp(-(l + 1) * y))
                        : 0.0;
  const double qy = qy0_ * std::exp(-l * y);
  q = qx * ex_ + qy * ey_;
  const auto part = [&](double e) { return y < std::numeric_limits<double>::infinity() ? integral(e, y) : 1 / e; };
  const double big_x = (a_ * a_ * part(2 * l - 2) - b_ * b_ * part(2 * l + 2)) / (4 * g_);
  const double big_y = qy0_ * (a_ * part(2 * l - 1) + b_ * part(2 * l + 1)) / (2 * g_);
  integral_q = big_x * ex_ + big_y * ey_;
}
}  // namespace ball_collision_sim::core
