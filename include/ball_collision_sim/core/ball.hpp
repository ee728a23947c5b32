#pragma once

#include "ball_collision_sim/core/types.hpp"

namespace ball_collision_sim::core
{
/// A ball. Physical fields carry units; `uv` is its foot point on the floor.
struct Ball
{
  int id = 0;
  double radius = 0.1;                    ///< [m]
  double mass = 1.0;                      ///< [kg]
  Vec3 position = Vec3::Zero();           ///< centre [m]
  Vec3 velocity = Vec3::Zero();           ///< [m/s]
  Quat orientation = Quat::Identity();    ///< turns as the ball rolls
  Vec3 angular_velocity = Vec3::Zero();   ///< of rolling without slip [rad/s]
  Vec2 uv = Vec2(0.5, 0.5);               ///< foot point parameters on the floor
};
}  // namespace ball_collision_sim::core
