#include "ball_collision_sim/core/floor.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ball_collision_sim::core
{
namespace
{
/// Quadratic Bernstein weights and their first and second derivatives at t.
struct Bernstein
{
  double b[3];
  double d[3];
  double dd[3];
  explicit Bernstein(double t)
      : b{(1 - t) * (1 - t), 2 * t * (1 - t), t * t}
      , d{-2 * (1 - t), 2 - 4 * t, 2 * t}
      , dd{2, -4, 2}
  {
  }
};

constexpr double kInsideTolerance = 1e-9;
constexpr int kMaxNewtonIterations = 30;
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
    const Bernstein any(0.5);  // (second derivatives of quadratics do not depend on t)
    for (int i = 0; i < 3; ++i)
    {
      const std::array<Vec3, 3>& p = def_.control_points[i];
      rows_vv_[i] = any.dd[0] * p[0] + any.dd[1] * p[1] + any.dd[2] * p[2];
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
  // Each row of control points along v first (the curves at this v, their v-derivatives
  // and second v-derivatives), then those along u: 27 weighted sums of points and 18 of
  // rows instead of 54 of points.
  const Bernstein bu(uv.x());
  const Bernstein bv(uv.y());
  std::array<Vec3, 3> row, row_v;
  for (int i = 0; i < 3; ++i)
  {
    const std::array<Vec3, 3>& p = def_.control_points[i];
    row[i] = bv.b[0] * p[0] + bv.b[1] * p[1] + bv.b[2] * p[2];
    row_v[i] = bv.d[0] * p[0] + bv.d[1] * p[1] + bv.d[2] * p[2];
  }
  const std::array<Vec3, 3>& row_vv = rows_vv_;
  s = bu.b[0] * row[0] + bu.b[1] * row[1] + bu.b[2] * row[2];
  su = bu.d[0] * row[0] + bu.d[1] * row[1] + bu.d[2] * row[2];
  suu = bu.dd[0] * row[0] + bu.dd[1] * row[1] + bu.dd[2] * row[2];
  sv = bu.b[0] * row_v[0] + bu.b[1] * row_v[1] + bu.b[2] * row_v[2];
  suv = bu.d[0] * row_v[0] + bu.d[1] * row_v[1] + bu.d[2] * row_v[2];
  svv = bu.b[0] * row_vv[0] + bu.b[1] * row_vv[1] + bu.b[2] * row_vv[2];
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
    // Newton's method on the gradient of |S(u, v) - q|^2 / 2; where its Hessian is not
    // positive definite (far from the surface), the Gauss-Newton step instead.
    // It stops where the next step would be below 1e-15, without taking it: the
    // derivatives at hand are then those at the foot point (and a guess that is already
    // the foot, as for a ball at rest, costs one evaluation).
    Vec2 uv = guess;
    Vec3 s, su, sv, suu, suv, svv;
    bool converged = false;
    for (int it = 0; it < kMaxNewtonIterations; ++it)
    {
      derivatives(uv, s, su, sv, suu, suv, svv);
      const Vec3 r = s - q;
      const Vec2 grad(r.dot(su), r.dot(sv));
      Mat2 h;
      h << su.dot(su) + r.dot(suu), su.dot(sv) + r.dot(suv), su.dot(sv) + r.dot(suv),
          sv.dot(sv) + r.dot(svv);
      if (h.determinant() <= 0 || h(0, 0) <= 0)
        h << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
      Vec2 step = -h.inverse() * grad;
      const double len = step.norm();
      converged = len < 1e-15;
      if (converged)
        break;
      if (len > 0.5)
        step *= 0.5 / len;
      uv += step;
    }
    if (!converged)
      derivatives(uv, s, su, sv, suu, suv, svv);
    foot.uv = uv;
    foot.point = s;
    foot.normal = orient(su.cross(sv).normalized());
    foot.height = (q - s).dot(foot.normal);
  }
  foot.inside = (foot.uv.array() >= -kInsideTolerance).all() &&
                (foot.uv.array() <= 1 + kInsideTolerance).all();
  return foot;
}
}  // namespace ball_collision_sim::core
