#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <array>
#include <cstdint>

namespace ball_collision_sim::core
{
/// Which part of a wall a ball touches.
enum class WallFeature : std::uint8_t
{
  kFace,
  kEdge,
  kCorner,
};

const char* toString(WallFeature feature);

/// A finite, two-sided parallelogram wall point + s u + t v, s, t in [0, 1].
struct Wall
{
  Wall(int wall_id, const WallDef& def, double default_restitution);

  int id;
  WallDef def;
  double restitution;             ///< 0..1
  Vec3 normal;                    ///< unit, u x v / |u x v|
  Vec3 dual_u;                    ///< <q - point, dual_u> = s of q's projection
  Vec3 dual_v;                    ///< <q - point, dual_v> = t of q's projection
  std::array<Vec3, 4> corners;    ///< point, point + u, point + u + v, point + v
  Vec3 box_min;                   ///< axis-aligned bounds [m]
  Vec3 box_max;

  /// The wall's point nearest to q, and which feature it lies on.
  Vec3 closestPoint(const Vec3& q, WallFeature* feature = nullptr) const;
  /// Distance from q to the wall [m].
  double distance(const Vec3& q) const { return (q - closestPoint(q)).norm(); }
};
}  // namespace ball_collision_sim::core
