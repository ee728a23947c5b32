// The cue's pose as a strike: plain arithmetic on Eigen, no ROS (cue_shot.hpp).
#include "ball_collision_sim/ros/cue_shot.hpp"

#include "ball_collision_sim/core/format.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::bridge
{
CueShot cueShot(const CuePose& cue, const core::Vec3& centre, double radius, double mass)
{
  CueShot shot;
  const double norm = cue.orientation.norm();
  if (!(norm > 0) || !std::isfinite(norm) || !cue.position.allFinite())
  {
    shot.error = "orientation: the cue's pose is not a finite rotation and position";
    return shot;
  }
  shot.direction = (cue.orientation.normalized() * core::Vec3::UnitX()).normalized();
  const core::Vec3& d = shot.direction;
  shot.pull = (centre - cue.position).dot(d);
  shot.offset = cue.position + shot.pull * d - centre;
  // (the ball's own check allows its radius plus the contact tolerance)
  if (shot.offset.norm() > radius + core::kContactTolerance)
  {
    shot.error = "offset: the cue's line passes " + core::formatNumber(shot.offset.norm()) +
                 " m from the ball's centre, outside its radius " + core::formatNumber(radius) + " m";
    return shot;
  }
  if (shot.pull >= kCueMinPull)
    shot.impulse = mass * std::min(kCueSpeedPerPull * shot.pull, kCueMaxSpeed) * d;
  return shot;
}

CuePose seatedCue(const core::Vec3& centre, const core::Vec3& direction, const core::Vec3& offset, const core::Vec3& up)
{
  const core::Vec3 x = direction.normalized();
  // y level (square to up) and across the cue; where the cue is along up, any square to it
  core::Vec3 y = up.cross(x);
  if (y.norm() < 1e-9)
    y = x.unitOrthogonal();
  y.normalize();
  const core::Vec3 z = x.cross(y);
  Eigen::Matrix3d axes;
  axes.col(0) = x;
  axes.col(1) = y;
  axes.col(2) = z;
  CuePose pose;
  pose.position = centre + offset;
  pose.orientation = Eigen::Quaterniond(axes).normalized();
  return pose;
}
}  // namespace ball_collision_sim::bridge
