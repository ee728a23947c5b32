#include "ball_collision_sim/core/wall.hpp"

#include <algorithm>
#include <limits>

namespace ball_collision_sim::core
{
const char* toString(WallFeature feature)
{
  switch (feature)
  {
    case WallFeature::kFace:
      return "face";
    case WallFeature::kEdge:
      return "edge";
    case WallFeature::kCorner:
      return "corner";
  }
  return "?";
}

Wall::Wall(int wall_id, const WallDef& wall_def, double default_restitution)
    : id(wall_id), def(wall_def), restitution(wall_def.restitution.value_or(default_restitution))
{
  const Vec3 n = def.u.cross(def.v);
  normal = n.normalized();
  // Dual basis of (u, v) in the wall's plane: <dual_u, u> = 1, <dual_u, v> = 0, ...
  dual_u = def.v.cross(n) / n.squaredNorm();
  dual_v = n.cross(def.u) / n.squaredNorm();
  corners = {def.point, def.point + def.u, def.point + def.u + def.v, def.point + def.v};
  box_min = box_max = corners[0];
  for (const Vec3& c : corners)
  {
    box_min = box_min.cwiseMin(c);
    box_max = box_max.cwiseMax(c);
  }
}

Vec3 Wall::closestPoint(const Vec3& q, WallFeature* feature) const
{
  const Vec3 d = q - def.point;
  const double s = d.dot(dual_u);
  const double t = d.dot(dual_v);
  if (s >= 0 && s <= 1 && t >= 0 && t <= 1)
  {
    if (feature)
      *feature = WallFeature::kFace;
    return def.point + s * def.u + t * def.v;
  }
  // Outside the face: the nearest point lies on the boundary.
  double best = std::numeric_limits<double>::infinity();
  Vec3 best_point = corners[0];
  WallFeature best_feature = WallFeature::kCorner;
  for (int k = 0; k < 4; ++k)
  {
    const Vec3& a = corners[k];
    const Vec3 e = corners[(k + 1) % 4] - a;
    const double along = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec3 p = a + along * e;
    const double dist = (q - p).squaredNorm();
    if (dist < best)
    {
      best = dist;
      best_point = p;
      best_feature = (along > 0 && along < 1) ? WallFeature::kEdge : WallFeature::kCorner;
    }
  }
  if (feature)
    *feature = best_feature;
  return best_point;
}
}  // namespace ball_collision_sim::core
