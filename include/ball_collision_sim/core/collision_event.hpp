#pragma once

#include "ball_collision_sim/core/types.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <cstdint>

namespace ball_collision_sim::core
{
/// One handled collision.
struct CollisionEvent
{
  enum class Kind : std::uint8_t
  {
    kBallBall,
    kBallWall,
    kBallFloor,  ///< a ball in flight lands on the floor (a bounce, or its last landing)
  };
  double time = 0.0;                  ///< exact time of impact [s]
  Vec3 point = Vec3::Zero();          ///< contact point [m]
  Vec3 normal = Vec3::UnitX();        ///< unit, from the ball toward the other object
  double impulse = 0.0;               ///< magnitude of the exchanged impulse [N s]
  double approach_speed = 0.0;        ///< normal closing speed before [m/s]
  int ball = -1;                      ///< id of the (first) ball
  int other = -1;                     ///< id of the second ball or of the wall; 0 for the floor
  Kind kind = Kind::kBallBall;
  WallFeature feature = WallFeature::kFace;  ///< ball-wall only
  /// true for a resting contact: the closing speed was below what gravity adds in a
  /// step or two, so the motion was stopped along the normal instead of bounced.
  bool resting = false;
};
}  // namespace ball_collision_sim::core
