#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <cstdint>

namespace ball_collision_sim::core
{
/// A ball. Physical fields carry units. Its angular velocity is that of rolling without
/// slip on the floor under it (World::angularVelocity()).
struct Ball
{
  int id = 0;
  /// At rest in a group that leans on walls or the floor's slope: the step leaves it
  /// where it is, without motion or events, until an impact or an edit wakes it.
  bool asleep = false;
  /// In flight: no floor holds it; its centre moves on x0 + v t + g t^2 / 2 and its spin
  /// is constant until it lands (a world without a floor has no flight: every ball moves
  /// so there).
  bool flying = false;
  /// Steps in a row it has been all but still while leaning on something (to sleep).
  std::uint16_t quiet_steps = 0;
  double radius = 0.1;                    ///< [m]
  double mass = 1.0;                      ///< [kg]
  Vec3 position = Vec3::Zero();           ///< centre [m]
  Vec3 velocity = Vec3::Zero();           ///< [m/s]
  Quat orientation = Quat::Identity();    ///< turns as the ball rolls
};
}  // namespace ball_collision_sim::core
