// A ball's motion on a curved floor, integrated (FloorFlow): its foot point and velocity
// under a law along the floor and the floor's push that keeps it on it.
#include "ball_collision_sim/core/floor_flow.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
Vec3 FloorFlow::centre(const Vec2& foot, Vec3* normal) const
{
  const Vec3 n = floor_.normal(foot);
  if (normal)
    *normal = n;
  return floor_.point(foot) + radius_ * n;
}

void FloorFlow::rates(const State& s, const Law& law, Vec2& foot_rate, Vec3& acceleration) const
{
  Vec3 p, su, sv, suu, suv, svv;
  floor_.derivatives(s.foot, p, su, sv, suu, suv, svv);
  Vec3 n = su.cross(sv).normalized();
  if (n.dot(floor_.up()) < 0)
    n = -n;
  // first and second fundamental forms
  Mat2 first, second;
  first << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
  second << suu.dot(n), suv.dot(n), suv.dot(n), svv.dot(n);
  const Vec3& v = s.velocity;
  const Vec2 b(su.dot(v), sv.dot(v));
  foot_rate = (first - radius_ * second).inverse() * b;
  // the push along n: c^T II foot_rate, c = I^-1 b the velocity's coordinates
  const double push = (first.inverse() * b).dot(second * foot_rate);
  const double g_n = -gravity_.dot(n);
  const Vec3 g_t = gravity_ + g_n * n;
  acceleration = law.share * g_t + push * n;
  if (law.drag > 0)
  {
    const Vec3 along = v - v.dot(n) * n;
    const double speed = along.norm();
    if (speed > 0)
      acceleration -= (law.drag * std::max(0.0, g_n) / speed) * along;
  }
}

Vec3 FloorFlow::advance(State& state, double duration, int substeps, const Law& law, Vec3& normal) const
{
  const double h = duration / substeps;
  for (int k = 0; k < substeps; ++k)
  {
    Vec2 f1, f2, f3, f4;
    Vec3 a1, a2, a3, a4;
    const State s0 = state;
    rates(s0, law, f1, a1);
    rates({s0.foot + (0.5 * h) * f1, s0.velocity + (0.5 * h) * a1}, law, f2, a2);
    rates({s0.foot + (0.5 * h) * f2, s0.velocity + (0.5 * h) * a2}, law, f3, a3);
    rates({s0.foot + h * f3, s0.velocity + h * a3}, law, f4, a4);
    state.foot = s0.foot + (h / 6) * (f1 + 2 * f2 + 2 * f3 + f4);
    state.velocity = s0.velocity + (h / 6) * (a1 + 2 * a2 + 2 * a3 + a4);
  }
  const Vec3 c = centre(state.foot, &normal);
  state.velocity -= state.velocity.dot(normal) * normal;
  return c;
}

int FloorFlow::substepsFor(double duration, double speed, double curvature, double gravity, double turn)
{
  const double swing = duration * (speed * curvature + std::sqrt(gravity * curvature));
  return std::max(1, static_cast<int>(std::ceil(swing / turn)));
}
}  // namespace ball_collision_sim::core
