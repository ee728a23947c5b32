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
  /// What holds the ball up between steps.
  enum class Support : std::uint8_t
  {
    /// On the floor: it rolls, slides, spins or stands on it (or, in a world without a
    /// floor, moves in the plane).
    kFloor,
    /// At rest in a group that leans on walls or the floor's slope: the step leaves it
    /// where it is, without motion or events, until an impact or an edit wakes it.
    kAsleep,
    /// In flight: no floor holds it; its centre moves on x0 + v t + g t^2 / 2 and its spin
    /// is constant until it lands (a world without a floor has no flight).
    kAir,
  };
  Support support = Support::kFloor;
  bool asleep() const { return support == Support::kAsleep; }
  bool flying() const { return support == Support::kAir; }
  /// Steps in a row it has been all but still while leaning on something (to sleep).
  std::uint16_t quiet_steps = 0;
  double radius = 0.1;                    ///< [m]
  double mass = 1.0;                      ///< [kg]
  Vec3 position = Vec3::Zero();           ///< centre [m]
  Vec3 velocity = Vec3::Zero();           ///< [m/s]
  Quat orientation = Quat::Identity();    ///< turns as the ball rolls
};
}  // namespace ball_collision_sim::core
