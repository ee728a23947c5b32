#include "ball_collision_sim/core/time_of_impact.hpp"

#include "bracketed_root.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ball_collision_sim::core
{

namespace
{
/// The screen that drops pairs too far apart to meet within the step compares lengths
/// of a few rounded operations; it drops a pair only when its bound beats the reach by
/// this part of it [1], well above their round-off, so no pair that meets is dropped.
constexpr double kScreenMargin = 1e-9;
/// A straight ball that meets a wall's face this part of its scale (radius, distance,
/// travel) inside the face's edges meets no edge or corner first: far above the edge
/// tests' round-off, so that skipping them cannot change what they would find [1].
constexpr double kInsideMargin = 1e-6;

/// p(t) for the coefficients a[0..n], by Horner's rule.
double evaluate(const std::array<double, 5>& a, int n, double t)
{
  double v = a[static_cast<std::size_t>(n)];
  for (int k = n - 1; k >= 0; --k)
    v = v * t + a[static_cast<std::size_t>(k)];
  return v;
}

/// The point of [lo, hi] where p (degree n) changes sign, f_lo = p(lo) and f_hi = p(hi)
/// of opposite signs (f_lo != 0): the last double at which p keeps the sign it has at
/// lo, or a point where it is zero.
double refineRoot(const std::array<double, 5>& a, int n, double lo, double hi, double f_lo, double f_hi)
{
  const bool positive = f_lo > 0;
  return bracketedRoot([&](double t) { return evaluate(a, n, t); },
                       [&](double v) { return v == 0 ? 0 : (v > 0) == positive ? 1 : -1; }, lo, hi, f_lo, f_hi);
}

/// The roots of a quadratic a[0] + a[1] t + a[2] t^2 (a[2] != 0) in (lo, hi), in order,
/// by the formula that keeps the smaller one free of cancellation: close enough to split
/// a polynomial into its monotone pieces (the roots themselves are refined).
int quadraticRootsIn(const std::array<double, 5>& a, double lo, double hi, std::array<double, 4>& out)
{
  const double disc = a[1] * a[1] - 4 * a[2] * a[0];
  if (disc < 0)
    return 0;
  const double q = -0.5 * (a[1] + std::copysign(std::sqrt(disc), a[1]));
  double r1 = q / a[2], r2 = q != 0 ? a[0] / q : r1;
  if (r2 < r1)
    std::swap(r1, r2);
  int found = 0;
  for (const double r : {r1, r2})
    if (r > lo && r < hi && (found == 0 || r > out[0]))
      out[static_cast<std::size_t>(found++)] = r;
  return found;
}

/// The roots of p (degree at most n) in the open interval (lo, hi), in order, the first
/// `most` of them: between the derivative's roots p is monotone, so each piece holds at
/// most one. Where `split` (the derivative of the polynomial asked about), a quadratic's
/// roots come from the formula.
int rootsIn(const std::array<double, 5>& a, int n, double lo, double hi, std::array<double, 4>& out, int most,
            bool split)
{
  while (n > 0 && a[static_cast<std::size_t>(n)] == 0)
    --n;
  if (n == 0)
    return 0;
  if (n == 1)
  {
    const double t = -a[0] / a[1];
    if (!(t > lo && t < hi))
      return 0;
    out[0] = t;
    return 1;
  }
  if (n == 2 && split)
    return quadraticRootsIn(a, lo, hi, out);
  std::array<double, 5> da{};
  for (int k = 1; k <= n; ++k)
    da[static_cast<std::size_t>(k - 1)] = k * a[static_cast<std::size_t>(k)];
  std::array<double, 4> critical{};
  const int m = rootsIn(da, n - 1, lo, hi, critical, 4, true);
  int found = 0;
  double from = lo, f_from = evaluate(a, n, lo);
  for (int k = 0; k <= m && found < most; ++k)
  {
    const double to = k < m ? critical[static_cast<std::size_t>(k)] : hi;
    const double f_to = evaluate(a, n, to);
    if (f_to == 0 && to < hi)
      out[static_cast<std::size_t>(found++)] = to;
    else if (f_from != 0 && (f_from > 0) != (f_to > 0) && f_to != 0)
      out[static_cast<std::size_t>(found++)] = refineRoot(a, n, from, to, f_from, f_to);
    from = to;
    f_from = f_to;
  }
  return found;
}
}  // namespace

namespace
{
/// Whether a motion whose distance changes by rate t + acc t^2 (rate <= 0) comes closer
/// than `slop` at some t in [0, t_max]: its deepest approach, at t_max or, where the
/// acceleration turns it back, at -rate / (2 acc).
bool closesIn(double rate, double acc, double t_max, double slop)
{
  const double t = acc > 0 ? std::min(t_max, -rate / (2 * acc)) : t_max;
  return -(rate * t + acc * t * t) > slop;
}
}  // namespace

std::optional<double> firstRoot(const std::array<double, 5>& a, double t_max)
{
  if (!(a[0] > 0) || !(t_max > 0))
    return std::nullopt;
  std::array<double, 4> roots{};
  if (rootsIn(a, 4, 0.0, t_max, roots, 1, false) > 0)
    return roots[0];
  if (const double f_end = evaluate(a, 4, t_max); f_end <= 0)
    return refineRoot(a, 4, 0.0, t_max, a[0], f_end);
  return std::nullopt;
}

namespace
{
/// The first t in (0, t_max) at which a[0] + a[1] t + ... + a[4] t^4 falls through zero
/// from above and `accept(t)` holds; none where there is no such t.
template <class Accept>
std::optional<double> firstInwardRoot(const std::array<double, 5>& a, double t_max, const Accept& accept)
{
  std::array<double, 4> roots{};
  const int found = rootsIn(a, 4, 0.0, t_max, roots, 4, false);
  double from = 0.0;
  for (int k = 0; k < found; ++k)
  {
    const double t = roots[static_cast<std::size_t>(k)];
    // (falling through zero: positive on the way there)
    if (evaluate(a, 4, 0.5 * (from + t)) > 0 && accept(t))
      return t;
    from = t;
  }
  return std::nullopt;
}

/// |d + t e + t^2 c|^2 - reach^2, by powers of t.
std::array<double, 5> distanceQuartic(const Vec3& d, const Vec3& e, const Vec3& c, double reach)
{
  return {d.squaredNorm() - reach * reach, 2 * d.dot(e), e.squaredNorm() + 2 * d.dot(c), 2 * e.dot(c), c.squaredNorm()};
}
}  // namespace

std::optional<double> sphereSweepAccelerated(const Vec3& d, const Vec3& e, const Vec3& c, double reach, double t_max,
                                             double slop)
{
  if (c == Vec3::Zero())
    return sphereSweep(d, e, reach, t_max, slop);
  const std::array<double, 5> f = distanceQuartic(d, e, c, reach);
  if (f[0] > 0)
  {
    // (|d + t e + t^2 c| >= |d| - t |e| - t^2 |c|: most pairs cannot meet at all)
    if (std::sqrt(f[0] + reach * reach) - t_max * (e.norm() + t_max * c.norm()) > (1 + kScreenMargin) * reach)
      return std::nullopt;
    return firstRoot(f, t_max);
  }
  // Touching (or overlapping by round-off) and moving apart: an impact later, where the
  // acceleration brings it back (the distance squared less its value now is
  // t (f1 + f2 t + f3 t^2 + f4 t^3)) ...
  if (f[1] > 0)
    return firstRoot({f[1], f[2], f[3], f[4], 0.0}, t_max);
  // ... else an impact now if the motion closes in by more than round-off.
  return closesIn(d.dot(e), d.dot(c), t_max, slop * reach * d.norm()) ? std::optional<double>(0.0) : std::nullopt;
}

namespace
{
/// d + t e + t^2 c; with c zero, d + t e itself (the same bits as a straight motion's).
Vec3 pointAt(const Vec3& d, const Vec3& e, const Vec3& c, double t)
{
  return c == Vec3::Zero() ? Vec3(d + t * e) : Vec3(d + t * e + (t * t) * c);
}

/// Whether the point p projects outside the wall's parallelogram.
bool beside(const Wall& wall, const Vec3& p)
{
  const Vec3 q = p - wall.def.point;
  const double u = q.dot(wall.dual_u), v = q.dot(wall.dual_v);
  return u < 0 || u > 1 || v < 0 || v > 1;
}

/// The first t in [from, t_max) at which the projection of p + t e + t^2 c onto the
/// wall's plane enters its parallelogram (from itself where it is inside there): the
/// start of the first piece, between the times its two coordinates cross 0 or 1, whose
/// middle lies inside.
std::optional<double> entersFace(const Wall& wall, const Vec3& p, const Vec3& e, const Vec3& c, double from,
                                 double t_max)
{
  const Vec3 q = p - wall.def.point;
  std::array<double, 10> cuts{};
  std::size_t count = 0;
  cuts[count++] = from;
  for (const Vec3* dual : {&wall.dual_u, &wall.dual_v})
    for (const double level : {0.0, 1.0})
    {
      std::array<double, 4> roots{};
      const int found = rootsIn({q.dot(*dual) - level, e.dot(*dual), c.dot(*dual), 0.0, 0.0}, 2, from, t_max, roots, 2,
                                false);
      for (int k = 0; k < found; ++k)
        cuts[count++] = roots[static_cast<std::size_t>(k)];
    }
  std::sort(cuts.begin() + 1, cuts.begin() + static_cast<std::ptrdiff_t>(count));
  cuts[count++] = t_max;
  for (std::size_t k = 0; k + 1 < count; ++k)
    if (cuts[k + 1] > cuts[k] && !beside(wall, pointAt(p, e, c, 0.5 * (cuts[k] + cuts[k + 1]))))
      return cuts[k];
  return std::nullopt;
}

/// A ball's path against a wall's face, in the signed distance from the face's plane on
/// the ball's side: d(t) = d0 + rate t + acc t^2.
struct FaceSweep
{
  const Wall& wall;
  const Vec3& p;
  const Vec3& e;
  const Vec3& c;
  double r, t_max, slop;
  double side, d0, rate, acc;

  FaceSweep(const Wall& wall, const Vec3& p, const Vec3& e, const Vec3& c, double r, double t_max, double slop)
      : wall(wall), p(p), e(e), c(c), r(r), t_max(t_max), slop(slop)
  {
    const double s0 = (p - wall.def.point).dot(wall.normal);
    const double en = e.dot(wall.normal), cn = c.dot(wall.normal);
    side = s0 > 0 ? 1.0 : -1.0;
    if (s0 == 0)
      side = en > 0 || (en == 0 && cn > 0) ? -1.0 : 1.0;
    d0 = side * s0;
    rate = side * en;
    acc = side * cn;
  }
  std::optional<WallHit> hit(std::optional<double> t) const
  {
    return t ? std::optional<WallHit>(WallHit{*t, WallFeature::kFace, side * wall.normal}) : std::nullopt;
  }
  /// Within r of the plane at `from`: met now where the motion goes deeper than
  /// round-off, or where it moves off and comes back to this depth.
  std::optional<double> fromWithin(double from) const
  {
    const double rate_from = rate + 2 * acc * from;
    if (rate_from > 0)
    {
      const auto back = firstRoot({rate_from, acc, 0.0, 0.0, 0.0}, t_max - from);
      return back ? std::optional<double>(std::min(from + *back, t_max)) : std::nullopt;
    }
    return closesIn(rate_from, acc, t_max - from, slop * r) ? std::optional<double>(from) : std::nullopt;
  }
  /// Within r of the plane beside the face: where the contact point comes over the face
  /// while still within r, and on the side it came from, the face is met there. (An edge
  /// is met first, exactly; but a ball grazing an edge may miss it by round-off, and then
  /// go on into the face. One that passed the edge and the plane comes over the face from
  /// behind: no impact.)
  std::optional<double> entering(double from) const
  {
    const auto in = entersFace(wall, p, e, c, from, t_max);
    if (!in)
      return std::nullopt;
    const double d_in = d0 + *in * (rate + acc * *in);
    if (!(d_in >= 0 && d_in <= r))
      return std::nullopt;
    const auto t = fromWithin(*in);
    return t && (*t == *in || !beside(wall, pointAt(p, e, c, *t))) ? t : std::nullopt;
  }
  /// Beside the face and within r of its plane: it may come over the face (entering()),
  /// or leave beyond r and come back over the face, where (d0 - r) + rate t + acc t^2,
  /// <= 0 now, falls to 0 again: its larger root, where it opens downward. (Straight, it
  /// never comes back.)
  std::optional<double> fromBeside() const
  {
    std::optional<double> t = entering(0.0);
    const double disc = rate * rate - 4 * acc * (d0 - r);
    if (acc < 0 && disc > 0)
    {
      const double back = (-rate - std::sqrt(disc)) / (2 * acc);
      if (back > 0 && back <= t_max && !beside(wall, pointAt(p, e, c, back)) && (!t || back < *t))
        t = back;
    }
    return t;
  }
  /// Whether the ball stays farther than r from the plane on its side over [0, t_max] (it
  /// never nears the plane), by more than
  /// the round-off of any feature's test: then it meets none of them (they lie in the
  /// plane, and a point's distance to each is at least its distance to the plane).
  bool clearOfPlane() const
  {
    const double d1 = d0 + t_max * (rate + t_max * acc);
    double lo = std::min(d0, d1);
    if (acc != 0)
    {
      const double t = -rate / (2 * acc);  // (where the distance turns)
      if (t > 0 && t < t_max)
        lo = std::min(lo, d0 + t * (rate + t * acc));
    }
    // (d0 >= 0: the ball starts on the side d counts from, so it stays clear above it)
    return lo > r + kScreenMargin * (r + d0 + t_max * (std::abs(rate) + t_max * std::abs(acc)));
  }
  /// Whether a straight ball that meets the face at t from beyond r of its plane does so
  /// well inside the parallelogram (past round-off of the edges' and corners' tests):
  /// then no edge or corner comes first, as each is farther than the face until t, and
  /// farther than r at t.
  bool wellInside(double t) const
  {
    const Vec3 q = p + t * e - wall.def.point;
    const double u = q.dot(wall.dual_u), v = q.dot(wall.dual_v);
    // (the distance in the plane to the edges u = 0 and u = 1 is u / |dual_u| and
    // (1 - u) / |dual_u|; the same in v)
    const double margin = kInsideMargin * (r + (p - wall.def.point).norm() + t * e.norm());
    return std::min(u, 1 - u) > margin * wall.dual_u.norm() && std::min(v, 1 - v) > margin * wall.dual_v.norm();
  }
  /// The same path seen from the plane's other side.
  FaceSweep flipped() const
  {
    FaceSweep f = *this;
    f.side = -side;
    f.d0 = -d0;
    f.rate = -rate;
    f.acc = -acc;
    return f;
  }
  /// From the other side: accelerated back toward its own side, a ball can pass the
  /// plane beside the face, go beyond r on the far side and come back to the face from
  /// there, where d, rising, reaches -r again: the larger root of (d0 + r) + rate t +
  /// acc t^2 (both are positive: d0 + r > 0, and it moves toward the plane, rate < 0).
  /// Over the face then, it meets it there; beside it, where it comes over it within r.
  std::optional<WallHit> fromFarSide() const
  {
    if (!(acc > 0 && rate < 0))
      return std::nullopt;
    const double disc = rate * rate - 4 * acc * (d0 + r);
    if (!(disc > 0))
      return std::nullopt;
    const double back = (0.5 * (std::sqrt(disc) - rate)) / acc;
    if (!(back <= t_max))
      return std::nullopt;
    const FaceSweep far = flipped();
    return far.hit(beside(wall, pointAt(p, e, c, back)) ? far.entering(back) : std::optional<double>(back));
  }
};

/// The earlier of two hits (a where they tie).
std::optional<WallHit> earlier(const std::optional<WallHit>& a, const std::optional<WallHit>& b)
{
  return b && (!a || b->t < a->t) ? b : a;
}

/// The face: where the ball comes within r of the plane (the signed distance from it is
/// linear in t, or quadratic under acceleration) with the contact point inside the
/// parallelogram: on the side it starts on, or, under acceleration, on the other.
std::optional<WallHit> sweepFace(const FaceSweep& f)
{
  const Wall& wall = f.wall;
  const Vec3 &p = f.p, &e = f.e, &c = f.c;
  const double r = f.r, t_max = f.t_max;
  if (f.d0 > r)
  {
    std::optional<double> t =
        f.acc == 0 ? (f.rate < 0 && (f.d0 - r) / -f.rate <= t_max ? std::optional<double>((f.d0 - r) / -f.rate)
                                                                   : std::nullopt)
                   : firstRoot({f.d0 - r, f.rate, f.acc, 0.0, 0.0}, t_max);
    if (t && beside(wall, pointAt(p, e, c, *t)))
      t = f.entering(*t);
    return earlier(f.hit(t), f.fromFarSide());
  }
  if (beside(wall, p))
    return earlier(f.hit(f.fromBeside()), f.fromFarSide());
  const auto t = f.fromWithin(0.0);
  return t && !beside(wall, pointAt(p, e, c, *t)) ? f.hit(t) : std::nullopt;
}

/// Edge k: the cylinder of radius r around the segment, then the contact must lie
/// within the segment.
std::optional<WallHit> sweepEdge(const Wall& wall, int k, const Vec3& p, const Vec3& e, const Vec3& c, double r,
                                 double t_max, double slop)
{
  const Vec3& a = wall.corners[k];
  const Vec3 edge = wall.corners[(k + 1) % 4] - a;
  const double len2 = edge.squaredNorm();
  const auto across = [&](const Vec3& w) { return Vec3(w - (w.dot(edge) / len2) * edge); };
  const Vec3 d = p - a;
  const Vec3 d_perp = across(d), e_perp = across(e), c_perp = across(c);
  const auto within = [&](double t) {
    const double along = pointAt(d, e, c, t).dot(edge) / len2;
    return along >= 0 && along <= 1;
  };
  const auto hit = [&](double t) { return WallHit{t, WallFeature::kEdge, pointAt(d_perp, e_perp, c_perp, t).normalized()}; };
  const double start = d_perp.squaredNorm() - r * r;
  if (!(start > 0) && within(0.0))
  {
    // touching the edge now: as two touching spheres
    const auto t = sphereSweepAccelerated(d_perp, e_perp, c_perp, r, t_max, slop);
    return t && within(*t) ? std::optional<WallHit>(hit(*t)) : std::nullopt;
  }
  const auto t = start > 0 ? sphereSweepAccelerated(d_perp, e_perp, c_perp, r, t_max, slop) : std::nullopt;
  if (t && within(*t))
    return hit(*t);
  if (c_perp == Vec3::Zero() || (start > 0 && !t))
    return std::nullopt;
  // Under acceleration the ball can come within r of the edge's line beside the segment
  // (or start there, beside it, leaning on a corner) and then leave and come in again
  // along the segment: the edge is met where the distance falls through r within it.
  if (const auto in = firstInwardRoot(distanceQuartic(d_perp, e_perp, c_perp, r), t_max, within))
    return hit(*in);
  return std::nullopt;
}
}  // namespace

std::optional<WallHit> sweepWall(const Wall& wall, const Vec3& p, const Vec3& e, const Vec3& c, double r,
                                 double t_max, double slop)
{
  const FaceSweep face(wall, p, e, c, r, t_max, slop);
  if (face.clearOfPlane())
    return std::nullopt;
  // The first time the distance to the (convex) parallelogram reaches r is the earliest
  // valid contact over its features; ties go to the face, then edges, then corners.
  std::optional<WallHit> best = sweepFace(face);
  if (best && c == Vec3::Zero() && face.d0 > r && face.wellInside(best->t))
    return best;
  for (int k = 0; k < 4; ++k)
  {
    const auto hit = sweepEdge(wall, k, p, e, c, r, best ? best->t : t_max, slop);
    if (hit && (!best || hit->t < best->t))
      best = hit;
  }
  for (int k = 0; k < 4; ++k)
  {
    const Vec3 d = p - wall.corners[k];
    const auto t = sphereSweepAccelerated(d, e, c, r, best ? best->t : t_max, slop);
    if (t && (!best || *t < best->t))
      best = WallHit{*t, WallFeature::kCorner, pointAt(d, e, c, *t).normalized()};
  }
  return best;
}

std::optional<WallHit> sweepWall(const Wall& wall, const Vec3& p, const Vec3& e, double r, double t_max, double slop)
{
  return sweepWall(wall, p, e, Vec3::Zero(), r, t_max, slop);
}
}  // namespace ball_collision_sim::core
