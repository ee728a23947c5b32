#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <array>

namespace ball_collision_sim::core
{
/// The nearest point of a floor to a given point.
struct FloorFoot
{
  Vec2 uv = Vec2::Zero();        ///< surface parameters
  Vec3 point = Vec3::Zero();     ///< S(u, v) [m]
  Vec3 normal = Vec3::UnitZ();   ///< unit normal facing against gravity
  double height = 0.0;           ///< signed distance of the query point along `normal` [m]
  bool inside = true;            ///< uv within [0, 1]^2 (to a small tolerance)
};

/// A parametric floor S(u, v), (u, v) in [0, 1]^2: a plane or the "nine point"
/// biquadratic Bezier surface. A ball on it has its centre at S + r n.
class Floor
{
public:
  /// A foot point this far outside [0, 1]^2 in u or v is still on the floor: round-off
  /// of Newton's method at the floor's edge [1].
  static constexpr double kInsideTolerance = 1e-9;
  /// True when (u, v) is on the floor (within kInsideTolerance).
  static bool inside(const Vec2& uv)
  {
    return (uv.array() >= -kInsideTolerance).all() && (uv.array() <= 1 + kInsideTolerance).all();
  }

  explicit Floor(const FloorDef& def, const Vec3& gravity);

  const FloorDef& def() const { return def_; }
  bool isPlane() const { return def_.type == FloorDef::Type::kPlane; }

  /// S(u, v) [m]
  Vec3 point(const Vec2& uv) const;
  /// Unit normal at (u, v), on the side facing against gravity.
  Vec3 normal(const Vec2& uv) const;
  /// S(u, v) and its first and second partial derivatives there.
  void derivatives(const Vec2& uv, Vec3& s, Vec3& su, Vec3& sv, Vec3& suu, Vec3& suv, Vec3& svv) const;
  /// The foot point of q (nearest surface point), by Newton's method from `guess`, and,
  /// where that ends off the floor from a guess off it, from the floor's edge nearest the
  /// guess as well (the nearer of the two). The polynomial surface is used past its edges
  /// too, so `inside` tells whether the foot is on the floor proper.
  FloorFoot project(const Vec3& q, const Vec2& guess) const;
  /// The centre of a ball of radius r nearest to q: foot + r n.
  Vec3 ballCentre(const FloorFoot& foot, double radius) const { return foot.point + radius * foot.normal; }
  /// Plane only: the parameters (u, v) of the foot point of q.
  Vec2 planeParameters(const Vec3& q) const
  {
    const Vec3 d = q - def_.point;
    return plane_gram_inverse_ * Vec2(d.dot(def_.u), d.dot(def_.v));
  }
  /// The largest principal curvature over the floor, from a grid of points on it (0 for a
  /// plane) [1/m].
  double maxCurvature() const { return max_curvature_; }
  /// The largest curvature with which the floor bends away from its (up-oriented) normal,
  /// as over a crest or across a saddle, from the same grid: the least principal
  /// curvature's negative, or 0 where the floor bends toward its normal everywhere (a
  /// bowl), where no ball on it ever needs the floor to pull [1/m]. (Where x and y are
  /// affine in (u, v), as on a floor over a grid of control points, the sign of the
  /// curvature is that of the height's Hessian, whose entries are affine in each
  /// parameter: the largest bend away lies at a corner, which the grid holds.)
  double awayCurvature() const { return away_curvature_; }
  /// Plane only: its unit normal (facing against gravity) and <normal, point on it>.
  const Vec3& planeNormal() const { return plane_normal_; }
  double planeOffset() const { return plane_normal_.dot(def_.point); }
  /// The unit vector the floor's normals are oriented toward.
  const Vec3& up() const { return up_; }

private:
  Vec3 orient(Vec3 n) const;
  /// Biquadratic only: the foot point Newton's method finds from `start` (not `inside`).
  FloorFoot nearestFrom(const Vec3& q, const Vec2& start) const;

  FloorDef def_;
  Vec3 up_;
  // plane only: unit normal and the inverse Gram matrix of (U, V)
  Vec3 plane_normal_;
  Mat2 plane_gram_inverse_;
  /// biquadratic only: S(u, v) = sum of power_[a][b] u^a v^b
  std::array<std::array<Vec3, 3>, 3> power_{};
  double max_curvature_ = 0.0;
  double away_curvature_ = 0.0;
  /// Sets max_curvature_ and away_curvature_ from a grid of points on the floor.
  void sampleCurvatures();
};
}  // namespace ball_collision_sim::core
