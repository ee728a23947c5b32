// A ball's motion on a curved floor, integrated (FloorFlow): its foot point, velocity and
// spin under the friction laws along the floor and the floor's push that keeps it on it.
#include "ball_collision_sim/core/floor_flow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
namespace
{
constexpr double kNever = std::numeric_limits<double>::infinity();
/// A phase's end is taken where the rates say it comes within this time: well inside
/// the 1e-9 s its time is asked to, and far above the round-off of a step's times [s].
constexpr double kEndTime = 1e-12;
/// Steps toward a phase's end that take at most this part of the time the rates give it.
constexpr double kApproach = 0.5;
/// At most this many steps toward one end (each halves what is left: from a step of 1 s,
/// 40 reach kEndTime).
constexpr int kApproachSteps = 60;

int sign(double x)
{
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}
}  // namespace

Vec3 FloorFlow::centre(const Vec2& foot, Vec3* normal) const
{
  const Vec3 n = floor_.normal(foot);
  if (normal)
    *normal = n;
  return floor_.point(foot) + radius_ * n;
}

FloorFlow::Rates FloorFlow::rates(const State& s, const Law& law) const
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
  const Vec3 v = s.velocity - s.velocity.dot(n) * n;
  const Vec2 b(su.dot(v), sv.dot(v));
  Rates out;
  out.foot = (first - radius_ * second).inverse() * b;
  // the push along n: c^T II foot_rate, c = I^-1 b the velocity's coordinates
  const Mat2 first_inverse = first.inverse();
  const double push = (first_inverse * b).dot(second * out.foot);
  const double g_n = std::max(0.0, -gravity_.dot(n));
  const Vec3 g_t = gravity_ - gravity_.dot(n) * n;
  const double k = law.inertia, r = radius_;
  out.spin_n_rate = law.spinning * g_n / (k * r);  // (0 where there is no such friction)
  out.spin = Vec3::Zero();
  out.spin_n = 0.0;
  out.q = out.q_rate = Vec3::Zero();
  out.drag = 0.0;
  switch (law.kind)
  {
    case Kind::kFree:
      out.acceleration = g_t;
      break;
    case Kind::kRolling:
    {
      out.acceleration = g_t / (1 + k);
      const double speed = v.norm();
      const double pull = g_t.norm() / (1 + k), drag = law.rolling * g_n;
      if (speed > 0)
        out.acceleration -= (drag / speed) * v;
      else  // (from rest it moves along the pull, the drag against it, where it moves at all)
        out.acceleration *= pull > drag ? 1 - drag / pull : 0.0;
      out.spin_n = -sign(s.spin_n) * out.spin_n_rate;
      out.q = v;
      out.q_rate = out.acceleration;
      out.drag = drag;
      break;
    }
    case Kind::kSliding:
    {
      out.acceleration = g_t;
      const Vec3 u = v + r * n.cross(s.spin);
      const double slip = u.norm();
      if (slip > 0)
      {
        const double force = law.sliding * g_n;
        out.acceleration -= (force / slip) * u;
        out.spin = (force / (k * r * slip)) * n.cross(u);
      }
      // the spin along the floor carried along it as the normal turns (dn/dt = -L of the
      // foot's velocity on S), as the velocity is by the push
      const Vec2 bend = first_inverse * (second * out.foot);
      const Vec3 n_rate = -(bend.x() * su + bend.y() * sv);
      out.spin -= s.spin.dot(n_rate) * n;
      out.spin_n = -sign(s.spin_n) * out.spin_n_rate;
      // the slip's rate along the floor: the velocity's, and the spin's turned and carried
      out.q = u;
      out.q_rate = out.acceleration + r * (n_rate.cross(s.spin) + n.cross(out.spin));
      out.q_rate -= out.q_rate.dot(n) * n;
      out.drag = law.sliding * g_n * (1 + 1 / k);
      break;
    }
  }
  out.acceleration += push * n;
  out.support = push + g_n;
  return out;
}

FloorFlow::State FloorFlow::rungeKutta(const State& s, double h, const Law& law, const Rates& d1) const
{
  const auto at = [&](const Rates& d, double f) {
    return State{s.foot + f * d.foot, s.velocity + f * d.acceleration, s.spin + f * d.spin, s.spin_n + f * d.spin_n};
  };
  const Rates d2 = rates(at(d1, 0.5 * h), law);
  const Rates d3 = rates(at(d2, 0.5 * h), law);
  const Rates d4 = rates(at(d3, h), law);
  const double w = h / 6;
  return State{s.foot + w * (d1.foot + 2 * d2.foot + 2 * d3.foot + d4.foot),
               s.velocity + w * (d1.acceleration + 2 * d2.acceleration + 2 * d3.acceleration + d4.acceleration),
               s.spin + w * (d1.spin + 2 * d2.spin + 2 * d3.spin + d4.spin),
               s.spin_n + w * (d1.spin_n + 2 * d2.spin_n + 2 * d3.spin_n + d4.spin_n)};
}

double FloorFlow::timeToEnd(const State& s, const Law& law, const Rates& d, std::uint8_t& which) const
{
  which = kPhaseRuns;
  double best = kNever;
  const auto consider = [&](double left, double rate, std::uint8_t end) {
    if (left > 0 && rate > 0 && left / rate < best)
    {
      best = left / rate;
      which = end;
    }
  };
  if (law.kind == Kind::kFree)
    return kNever;
  // (the slip's end, or the ball's stop: also a rolling ball's without rolling
  // resistance, at a turning point where its speed falls to zero)
  const double size = d.q.norm();
  if (size > 0)
    consider(size, -d.q.dot(d.q_rate) / size, law.kind == Kind::kSliding ? kSlipStops : kBallStops);
  consider(std::abs(s.spin_n), d.spin_n_rate, kSpinStops);
  return best;
}

double FloorFlow::turnTime(const Rates& d, double turn) const
{
  // (only the drag turns with q, and its error with it: as turn^3 times the drag, so
  // that a drag of g takes `turn`, a weaker one more; none, none)
  if (!(d.drag > 0))
    return kNever;
  turn *= std::cbrt(gravity_.norm() / d.drag);
  const double size = d.q.norm();
  if (!(size > 0))
    return kNever;  // (from nothing it grows along its rate, and does not turn)
  const double across = (d.q_rate - (d.q_rate.dot(d.q) / (size * size)) * d.q).norm();
  if (!(across > 0))
    return kNever;
  // Where q shrinks (at `shrink`), it turns ever faster: by (across / shrink) ln(|q| /
  // (|q| - shrink t)) in t, which is `turn` at this t.
  const double shrink = -d.q.dot(d.q_rate) / size;
  if (shrink > 0)
    return (size / shrink) * -std::expm1(-turn * shrink / across);
  return turn * size / across;
}

FloorFlow::End FloorFlow::advance(State& state, double duration, int substeps, const Law& law, double turn,
                                  int step_cap) const
{
  End end;
  const double h = duration / substeps;
  double t = 0.0;
  int approach = 0, steps = 0;
  Rates d = rates(state, law);
  while (t < duration)
  {
    // (no step shorter than kEndTime, in which nothing moves by more than round-off; past
    // the cap, the substeps as they are)
    const double turning = ++steps > step_cap ? kNever : turnTime(d, turn);
    double step = std::min({h, duration - t, std::max(kEndTime, turning)});
    std::uint8_t which = kPhaseRuns;
    const double to_end = timeToEnd(state, law, d, which);
    if (to_end <= step)
    {
      // (within kEndTime of it, or the steps toward it spent: here)
      if (to_end <= kEndTime || ++approach > kApproachSteps)
      {
        end.ends = which;
        break;
      }
      step = kApproach * to_end;
    }
    const State next = rungeKutta(state, step, law, d);
    const Rates there = rates(next, law);
    if (there.support < 0 && d.support >= 0)
    {
      // (the floor lets go within the step: where, on the side past it)
      double taken = 0.0;
      state = takeOff(state, d, step, law, taken);
      t += taken;
      end.ends = kTakesOff;
      break;
    }
    state = next;
    d = there;
    t += step;
  }
  end.time = std::min(t, duration);
  end.centre = centre(state.foot, &end.normal);
  state.velocity -= state.velocity.dot(end.normal) * end.normal;
  if (law.kind == Kind::kSliding)
    state.spin -= state.spin.dot(end.normal) * end.normal;  // (along the floor, to round-off)
  return end;
}

FloorFlow::State FloorFlow::takeOff(const State& before, const Rates& rates_before, double step, const Law& law,
                                   double& time) const
{
  double lo = 0.0, hi = step;
  State past = rungeKutta(before, hi, law, rates_before);
  while (hi - lo > kEndTime)
  {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi))
      break;
    const State there = rungeKutta(before, mid, law, rates_before);
    if (rates(there, law).support < 0)
    {
      hi = mid;
      past = there;
    }
    else
      lo = mid;
  }
  time = hi;
  return past;
}

int FloorFlow::substepsFor(double duration, double speed, double curvature, double gravity, double turn)
{
  const double swing = duration * (speed * curvature + std::sqrt(gravity * curvature));
  return std::max(1, static_cast<int>(std::ceil(swing / turn)));
}
}  // namespace ball_collision_sim::core
