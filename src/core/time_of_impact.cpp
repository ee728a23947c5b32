#include "ball_collision_sim/core/time_of_impact.hpp"

#include <cmath>

namespace ball_collision_sim::core
{
namespace
{
/// The face: the plane at distance r on the ball's side, then the contact point must
/// project inside the parallelogram.
std::optional<WallHit> sweepFace(const Wall& wall, const Vec3& p, const Vec3& e, double r, double t_max,
                                 double slop)
{
  const double s0 = (p - wall.def.point).dot(wall.normal);
  const double en = e.dot(wall.normal);
  double side = s0 > 0 ? 1.0 : -1.0;
  if (s0 == 0)
    side = en > 0 ? -1.0 : 1.0;
  const double d0 = side * s0;
  const double rate = side * en;
  double t = 0;
  if (d0 <= r)
  {
    if (!(-rate * t_max > slop * r))
      return std::nullopt;
  }
  else
  {
    if (rate >= 0)
      return std::nullopt;
    t = (d0 - r) / -rate;
    if (!(t <= t_max))
      return std::nullopt;
  }
  const Vec3 q = p + t * e - wall.def.point;
  const double s = q.dot(wall.dual_u);
  const double w = q.dot(wall.dual_v);
  if (s < 0 || s > 1 || w < 0 || w > 1)
    return std::nullopt;
  return WallHit{t, WallFeature::kFace, side * wall.normal};
}

/// Edge k: the cylinder of radius r around the segment, then the contact must lie
/// within the segment.
std::optional<WallHit> sweepEdge(const Wall& wall, int k, const Vec3& p, const Vec3& e, double r, double t_max,
                                 double slop)
{
  const Vec3& a = wall.corners[k];
  const Vec3 edge = wall.corners[(k + 1) % 4] - a;
  const double len2 = edge.squaredNorm();
  const Vec3 d = p - a;
  const Vec3 d_perp = d - (d.dot(edge) / len2) * edge;
  const Vec3 e_perp = e - (e.dot(edge) / len2) * edge;
  const auto t = sphereSweep(d_perp, e_perp, r, t_max, slop);
  if (!t)
    return std::nullopt;
  const double along = (d + *t * e).dot(edge) / len2;
  if (along < 0 || along > 1)
    return std::nullopt;
  return WallHit{*t, WallFeature::kEdge, (d_perp + *t * e_perp).normalized()};
}
}  // namespace

std::optional<WallHit> sweepWall(const Wall& wall, const Vec3& p, const Vec3& e, double r, double t_max,
                                 double slop)
{
  // The first time the distance to the (convex) parallelogram reaches r is the earliest
  // valid contact over its features; ties go to the face, then edges, then corners.
  std::optional<WallHit> best = sweepFace(wall, p, e, r, t_max, slop);
  for (int k = 0; k < 4; ++k)
  {
    const auto hit = sweepEdge(wall, k, p, e, r, best ? best->t : t_max, slop);
    if (hit && (!best || hit->t < best->t))
      best = hit;
  }
  for (int k = 0; k < 4; ++k)
  {
    const Vec3 d = p - wall.corners[k];
    const auto t = sphereSweep(d, e, r, best ? best->t : t_max, slop);
    if (t && (!best || *t < best->t))
      best = WallHit{*t, WallFeature::kCorner, (d + *t * e).normalized()};
  }
  return best;
}
}  // namespace ball_collision_sim::core
