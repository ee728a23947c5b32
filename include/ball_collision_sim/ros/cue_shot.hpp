#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <string>

namespace ball_collision_sim::bridge
{
/// The cue in rviz (InteractivePlay) as arithmetic, free of ROS so that it is tested
/// alone: what a cue's pose does to the ball it is aimed at.
///
/// The cue's frame: its origin `position` is a point on the cue's line, and its x axis
/// (the unit d = orientation * (1, 0, 0)) points along the cue from its butt toward its
/// tip, that is toward the ball. Seated (as the node puts it), the origin is the point of
/// the line nearest the ball's centre c; pulled back by s, it is s behind that point.
struct CuePose
{
  core::Vec3 position = core::Vec3::Zero();                         ///< [m], in the world's frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< need not be normalised
};

/// Ball speed per metre of pull-back [1/s]: a cue pulled back s gives the ball the speed
/// kCueSpeedPerPull * s (10 m/s per metre: 0.3 m is a firm shot, 0.6 m a break).
constexpr double kCueSpeedPerPull = 10.0;
/// The most speed a cue gives [m/s] (reached at 1 m of pull-back).
constexpr double kCueMaxSpeed = 10.0;
/// Least pull-back that strikes [m]: less is a twitch of the mouse (or round-off).
constexpr double kCueMinPull = 1e-3;

/// What a cue's pose does to a ball of centre c, radius r and mass m.
///   d      = orientation * (1, 0, 0), normalised: the cue's direction (toward the ball)
///   pull   s = (c - position) . d: how far the origin sits behind the point nearest c
///   offset o = position + s d - c: from c to the cue line's point nearest c (o . d = 0)
///   impulse J = m min(kCueSpeedPerPull s, kCueMaxSpeed) d, for s >= kCueMinPull; else none
/// J is along the cue (a chalked tip's friction keeps it there), and o x J is also the
/// torque about c of J at the point where the line meets the ball's surface: the strike's
/// spin change is o x J / (k m r^2) (core::World::strike()).
struct CueShot
{
  core::Vec3 direction = core::Vec3::UnitX();  ///< d, unit
  double pull = 0.0;                           ///< s [m]; below kCueMinPull: no strike
  core::Vec3 offset = core::Vec3::Zero();      ///< o [m]
  core::Vec3 impulse = core::Vec3::Zero();     ///< J [N s]; zero below kCueMinPull
  /// why the cue cannot strike from this pose ("orientation: ...", "offset: the cue's
  /// line passes ... from the centre ..."), or ""
  std::string error;
};

CueShot cueShot(const CuePose& cue, const core::Vec3& centre, double radius, double mass);

/// The cue seated on a ball of centre c: direction d (unit), offset o (o . d = 0), no
/// pull; its y axis level across d where `up` allows (the floor's normal), so that the
/// aim turns about `up`.
CuePose seatedCue(const core::Vec3& centre, const core::Vec3& direction, const core::Vec3& offset,
                  const core::Vec3& up);
}  // namespace ball_collision_sim::bridge
