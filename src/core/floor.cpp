#include "ball_collision_sim/core/floor.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ball_collision_sim::core
{
namespace
{
/// Three points as the coefficients of t^0, t^1 and t^2 of the quadratic Bezier curve
/// they control: (1 - t)^2 p0 + 2 t (1 - t) p1 + t^2 p2.
std::array<Vec3, 3> powerBasis(const Vec3& p0, const Vec3& p1, const Vec3& p2)
{
  return {p0, 2 * (p1 - p0), (p0 - 2 * p1) + p2};
}

/// Newton's method for the foot point converges quadratically from a guess near it;
/// far from the surface its damped steps take longer, never this many in the tests.
constexpr int kMaxNewtonIterations = 30;
/// Newton's method stops where its next step in (u, v) would be shorter than this [1]:
/// a few ulps of parameters in [0, 1], where a further step only trades round-off.
constexpr double kFootStepTolerance = 1e-15;
}  // namespace

Floor::Floor(const FloorDef& def, const Vec3& gravity) : def_(def)
{
  const double g = gravity.norm();
  if (def_.type == FloorDef::Type::kPlane)
  {
    plane_normal_ = def_.u.cross(def_.v).normalized();
    Mat2 gram;
    gram << def_.u.dot(def_.u), def_.u.dot(def_.v), def_.u.dot(def_.v), def_.v.dot(def_.v);
    plane_gram_inverse_ = gram.inverse();
  }
  else
  {
    plane_normal_ = Vec3::UnitZ();
    plane_gram_inverse_ = Mat2::Identity();
    // along v within each row of control points, then along u across the rows
    std::array<std::array<Vec3, 3>, 3> rows;
    for (int i = 0; i < 3; ++i)
      rows[i] = powerBasis(def_.control_points[i][0], def_.control_points[i][1], def_.control_points[i][2]);
    for (int b = 0; b < 3; ++b)
    {
      const std::array<Vec3, 3> column = powerBasis(rows[0][b], rows[1][b], rows[2][b]);
      for (int a = 0; a < 3; ++a)
        power_[a][b] = column[a];
    }
  }
  // "Up" is against gravity; without gravity, the side of the surface's own normal at
  // its centre.
  if (g > 0)
    up_ = -gravity / g;
  else
  {
    Vec3 s, su, sv, suu, suv, svv;
    derivatives(Vec2(0.5, 0.5), s, su, sv, suu, suv, svv);
    up_ = su.cross(sv).normalized();
  }
  if (isPlane())
    plane_normal_ = orient(plane_normal_);
  else
    sampleCurvatures();
}

void Floor::sampleCurvatures()
{
  // The principal curvatures H -+ sqrt(H^2 - K) from the first and second fundamental
  // forms under the up-oriented normal, at the points of a grid over the floor: the
  // larger in magnitude, and the least's negative (a bend away from the normal).
  constexpr int kSamples = 16;
  double largest = 0.0, away = 0.0;
  for (int a = 0; a <= kSamples; ++a)
    for (int b = 0; b <= kSamples; ++b)
    {
      Vec3 s, su, sv, suu, suv, svv;
      derivatives(Vec2(static_cast<double>(a) / kSamples, static_cast<double>(b) / kSamples), s, su, sv, suu, suv, svv);
      const Vec3 n = orient(su.cross(sv).normalized());
      const double e = su.dot(su), f = su.dot(sv), g = sv.dot(sv);
      const double l = suu.dot(n), m = suv.dot(n), k = svv.dot(n);
      const double det = e * g - f * f;
      if (!(det > 0))
        continue;
      const double mean = (l * g - 2 * m * f + k * e) / (2 * det);
      const double gauss = (l * k - m * m) / det;
      const double spread = std::sqrt(std::max(0.0, mean * mean - gauss));
      largest = std::max(largest, std::abs(mean) + spread);
      away = std::max(away, spread - mean);
    }
  max_curvature_ = largest;
  away_curvature_ = away;
}

Vec3 Floor::orient(Vec3 n) const
{
  return n.dot(up_) < 0 ? Vec3(-n) : n;
}

void Floor::derivatives(const Vec2& uv, Vec3& s, Vec3& su, Vec3& sv, Vec3& suu, Vec3& suv,
                        Vec3& svv) const
{
  if (isPlane())
  {
    s = def_.point + uv.x() * def_.u + uv.y() * def_.v;
    su = def_.u;
    sv = def_.v;
    suu = suv = svv = Vec3::Zero();
    return;
  }
  // S = sum over a, b of c_ab u^a v^b: the rows c_a0 + c_a1 v + c_a2 v^2 and their
  // derivatives along v at this v, then those along u.
  const double u = uv.x(), v = uv.y();
  const auto& c = power_;
  std::array<Vec3, 3> row, row_v;
  for (int a = 0; a < 3; ++a)
  {
    row[a] = c[a][0] + v * (c[a][1] + v * c[a][2]);
    row_v[a] = c[a][1] + (2 * v) * c[a][2];
  }
  s = row[0] + u * (row[1] + u * row[2]);
  su = row[1] + (2 * u) * row[2];
  suu = 2 * row[2];
  sv = row_v[0] + u * (row_v[1] + u * row_v[2]);
  suv = row_v[1] + (2 * u) * row_v[2];
  svv = 2 * (c[0][2] + u * (c[1][2] + u * c[2][2]));
}

Vec3 Floor::point(const Vec2& uv) const
{
  Vec3 s, su, sv, suu, suv, svv;
  derivatives(uv, s, su, sv, suu, suv, svv);
  return s;
}

Vec3 Floor::normal(const Vec2& uv) const
{
  if (isPlane())
    return plane_normal_;
  Vec3 s, su, sv, suu, suv, svv;
  derivatives(uv, s, su, sv, suu, suv, svv);
  return orient(su.cross(sv).normalized());
}

FloorFoot Floor::project(const Vec3& q, const Vec2& guess) const
{
  FloorFoot foot;
  if (isPlane())
  {
    const Vec3 d = q - def_.point;
    foot.uv = plane_gram_inverse_ * Vec2(d.dot(def_.u), d.dot(def_.v));
    foot.normal = plane_normal_;
    foot.height = d.dot(plane_normal_);
    foot.point = q - foot.height * plane_normal_;
  }
  else
  {
    foot = nearestFrom(q, guess);
    // Newton's method finds the point where it starts nearest to q of the surface's
    // points square to q - S, not the nearest of all: from a guess off the floor (the
    // foot of a point far away, as a fast ball's uncut chord ends) it can end far off
    // the floor on the polynomial past its edge, with q right above the floor. Then it
    // starts again on the floor's edge nearest the guess, and the nearer foot counts.
    const Vec2 on_floor = guess.cwiseMax(0.0).cwiseMin(1.0);
    if (!inside(foot.uv) && on_floor != guess)
    {
      const FloorFoot again = nearestFrom(q, on_floor);
      if ((again.point - q).squaredNorm() < (foot.point - q).squaredNorm())
        foot = again;
    }
  }
  foot.inside = inside(foot.uv);
  return foot;
}

FloorFoot Floor::nearestFrom(const Vec3& q, const Vec2& start) const
{
  // Newton's method on the gradient of |S(u, v) - q|^2 / 2; where its Hessian is not
  // positive definite (far from the surface), the Gauss-Newton step instead.
  // It stops where the next step would be below kFootStepTolerance, without taking it: the
  // derivatives at hand are then those at the foot point (and a start that is already
  // the foot, as for a ball at rest, costs one evaluation).
  Vec2 uv = start;
  Vec3 s, su, sv, suu, suv, svv;
  bool converged = false;
  for (int it = 0; it < kMaxNewtonIterations; ++it)
  {
    derivatives(uv, s, su, sv, suu, suv, svv);
    const Vec3 r = s - q;
    const Vec2 grad(r.dot(su), r.dot(sv));
    Mat2 h;
    h << su.dot(su) + r.dot(suu), su.dot(sv) + r.dot(suv), su.dot(sv) + r.dot(suv), sv.dot(sv) + r.dot(svv);
    if (h.determinant() <= 0 || h(0, 0) <= 0)
      h << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    Vec2 step = -h.inverse() * grad;
    const double len = step.norm();
    converged = len < kFootStepTolerance;
    if (converged)
      break;
    if (len > 0.5)
      step *= 0.5 / len;
    uv += step;
  }
  if (!converged)
    derivatives(uv, s, su, sv, suu, suv, svv);
  FloorFoot foot;
  foot.uv = uv;
  foot.point = s;
  foot.normal = orient(su.cross(sv).normalized());
  foot.height = (q - s).dot(foot.normal);
  return foot;
}
}  // namespace ball_collision_sim::core
