#pragma once

#include "ball_collision_sim/core/types.hpp"

namespace ball_collision_sim::core
{
/// A ball. Physical fields carry units. Its angular velocity is that of rolling without
/// slip on the floor under it (World::angularVelocity()).
struct Ball
{
  int id = 0;
  double radius = 0.1;                    ///< [m]
  double mass = 1.0;                      ///< [kg]
  Vec3 position = Vec3::Zero();           ///< centre [m]
  Vec3 velocity = Vec3::Zero();           ///< [m/s]
  Quat orientation = Quat::Identity();    ///< turns as the ball rolls
};
}  // namespace ball_collision_sim::core
