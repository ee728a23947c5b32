// A root of a function of one variable, kept bracketed: shared by the step (where a
// ball's energy runs out along its chord) and the times of impact (a quartic's root).
#pragma once

#include <limits>

namespace ball_collision_sim::core
{
/// The last point of [lo, hi] on lo's side of a change of sign of f, given f(lo) = f_lo
/// on that side and f(hi) = f_hi on the other. side(v) tells where a value lies: +1 on
/// lo's side, -1 on hi's, 0 at a root, taken at once. False position with the Illinois
/// rule (a stalled end's value halved), and a halving besides wherever a pass gains less
/// than that; for at most `passes` passes and while the bracket is wider than `width`,
/// or, with none given, until its ends are neighbouring doubles.
template <class F, class Side>
double bracketedRoot(F&& f, Side&& side, double lo, double hi, double f_lo, double f_hi,
                     int passes = std::numeric_limits<int>::max(), double width = 0.0)
{
  int last = 0;  // the end moved last: +1 lo, -1 hi
  for (int k = 0; k < passes && hi - lo > width; ++k)
  {
    const double before = hi - lo;
    double t = lo + before * (f_lo / (f_lo - f_hi));
    if (!(t > lo && t < hi))
      t = 0.5 * (lo + hi);
    if (!(t > lo && t < hi))
      return lo;  // neighbouring doubles
    const double v = f(t);
    const int s = side(v);
    if (s == 0)
      return t;
    if (s > 0)
    {
      lo = t;
      f_lo = v;
      if (last > 0)
        f_hi *= 0.5;
      last = 1;
    }
    else
    {
      hi = t;
      f_hi = v;
      if (last < 0)
        f_lo *= 0.5;
      last = -1;
    }
    if (hi - lo > 0.5 * before && hi - lo > width)
    {
      // one end stuck: halve the bracket as well
      const double half = 0.5 * (lo + hi);
      if (!(half > lo && half < hi))
        return lo;
      const double w = f(half);
      const int sh = side(w);
      if (sh == 0)
        return half;
      (sh > 0 ? lo : hi) = half;
      (sh > 0 ? f_lo : f_hi) = w;
      last = 0;
    }
  }
  return lo;
}
}  // namespace ball_collision_sim::core
