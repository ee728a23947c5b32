#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ball_collision_sim::core
{
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
/// Unaligned, so that it packs into structs without padding.
using Quat = Eigen::Quaternion<double, Eigen::DontAlign>;

/// Largest length accepted anywhere in a scene [m]; beyond it squares overflow precision.
constexpr double kMaxLength = 1e6;
/// Smallest radius and wall or floor edge accepted [m]: below it the rolling rate |v| / r
/// overflows and edge products underflow to zero.
constexpr double kMinLength = 1e-6;
/// Largest speed accepted [m/s].
constexpr double kMaxSpeed = 1e7;
/// Largest angular speed accepted [rad/s]: kMaxSpeed over the smallest radius.
constexpr double kMaxSpin = kMaxSpeed / kMinLength;
/// Largest friction coefficient accepted: far above any real surface's (rubber on
/// concrete is about 1); a typo such as 20 for 0.2 is refused.
constexpr double kMaxFriction = 10.0;
/// Largest mass accepted [kg].
constexpr double kMaxMass = 1e12;
/// Smallest mass accepted [kg]: below it 1 / m overflows.
constexpr double kMinMass = 1e-12;
/// Two objects closer than this are in contact; deeper overlap is an error at input [m].
constexpr double kContactTolerance = 1e-9;
}  // namespace ball_collision_sim::core
