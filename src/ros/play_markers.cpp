// The balls and the cue as interactive markers: how they look and what their controls
// do in rviz (play_markers.hpp).
#include "ball_collision_sim/ros/play_markers.hpp"

#include "ball_collision_sim/ros/conversions.hpp"

#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MenuEntry.h>

#include <cstdlib>
#include <string>

namespace ball_collision_sim::bridge
{
namespace
{
using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::Marker;

/// The ring a ball is dragged by: its outer radius and thickness, in ball radii.
constexpr double kRingRadius = 1.4;
constexpr double kRingThickness = 0.15;
/// The cue as drawn, in radii of its ball: the tip this far behind the centre when
/// seated, the stick this long and thick, the aiming rings this wide.
constexpr double kCueTipBehind = 1.5;
constexpr double kCueLength = 24.0;
constexpr double kCueThickness = 0.4;
constexpr double kCueRings = 6.0;

/// The rotation that takes a to b (unit vectors).
geometry_msgs::Quaternion turning(const core::Vec3& a, const core::Vec3& b)
{
  return toQuaternion(Eigen::Quaterniond::FromTwoVectors(a, b));
}

visualization_msgs::MenuEntry menuEntry(std::uint32_t id, const std::string& title)
{
  visualization_msgs::MenuEntry entry;
  entry.id = id;
  entry.title = title;
  entry.command_type = visualization_msgs::MenuEntry::FEEDBACK;
  return entry;
}

/// A cylinder along the marker's x axis from x0 to x1.
Marker stick(double x0, double x1, double thickness, const std_msgs::ColorRGBA& colour)
{
  Marker m;
  m.type = Marker::CYLINDER;
  m.pose.position.x = (x0 + x1) / 2;
  m.pose.orientation = turning(core::Vec3::UnitZ(), core::Vec3::UnitX());
  m.scale.x = m.scale.y = thickness;
  m.scale.z = x1 - x0;
  m.color = colour;
  return m;
}

}  // namespace

std::string playMarkerName(int id)
{
  return "ball_" + std::to_string(id);
}

CuePose cuePoseOf(const geometry_msgs::Pose& pose)
{
  const geometry_msgs::Quaternion& q = pose.orientation;
  return CuePose{toVec3(pose.position), Eigen::Quaterniond(q.w, q.x, q.y, q.z)};
}

geometry_msgs::Pose poseOf(const CuePose& cue)
{
  geometry_msgs::Pose pose;
  pose.position = toPoint(cue.position);
  pose.orientation = toQuaternion(cue.orientation.normalized());
  return pose;
}

bool samePose(const geometry_msgs::Pose& a, const geometry_msgs::Pose& b)
{
  return a.position.x == b.position.x && a.position.y == b.position.y && a.position.z == b.position.z &&
         a.orientation.x == b.orientation.x && a.orientation.y == b.orientation.y &&
         a.orientation.z == b.orientation.z && a.orientation.w == b.orientation.w;
}

int ballOfPlayMarker(const std::string& name)
{
  const std::string prefix = "ball_";
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size())
    return 0;
  char* end = nullptr;
  const long id = std::strtol(name.c_str() + prefix.size(), &end, 10);
  return *end == '\0' && id >= core::kFirstId && id <= 2147483647L ? static_cast<int>(id) : 0;
}

InteractiveMarker ballPlayMarker(const core::Ball& ball, const std::string& frame_id, const core::Vec3& up)
{
  InteractiveMarker marker;
  marker.header.frame_id = frame_id;
  marker.name = playMarkerName(ball.id);
  marker.description = "ball " + std::to_string(ball.id);
  marker.pose.position = toPoint(ball.position);
  marker.pose.orientation.w = 1.0;
  marker.scale = static_cast<float>(2 * kRingRadius * ball.radius);
  marker.menu_entries.push_back(menuEntry(kMenuCueBall, "Cue ball"));

  InteractiveMarkerControl move;
  move.name = "move";
  move.interaction_mode = InteractiveMarkerControl::MOVE_PLANE;
  move.orientation_mode = InteractiveMarkerControl::FIXED;
  move.orientation = turning(core::Vec3::UnitX(), up);  // (the plane square to its x axis)
  move.always_visible = true;
  Marker ring;
  ring.type = Marker::CYLINDER;
  ring.pose.orientation = turning(core::Vec3::UnitZ(), up);
  ring.scale.x = ring.scale.y = 2 * kRingRadius * ball.radius;
  ring.scale.z = kRingThickness * ball.radius;
  ring.color = rgba(0.85, 0.85, 0.85, 0.45);
  move.markers.push_back(ring);
  marker.controls.push_back(move);
  return marker;
}

InteractiveMarker cuePlayMarker(const CuePose& pose, int ball_id, double radius, const std::string& frame_id,
                                const core::Vec3& up)
{
  InteractiveMarker marker;
  marker.header.frame_id = frame_id;
  marker.name = kCueMarker;
  marker.description = "cue on ball " + std::to_string(ball_id);
  marker.pose = poseOf(pose);
  marker.scale = static_cast<float>(kCueRings * radius);
  marker.menu_entries.push_back(menuEntry(kMenuPutAway, "Put the cue away"));

  // Pull back along the cue (its x axis) by the stick itself.
  InteractiveMarkerControl pull;
  pull.name = kCuePull;
  pull.interaction_mode = InteractiveMarkerControl::MOVE_AXIS;
  pull.orientation.w = 1.0;
  pull.always_visible = true;
  const double tip = -kCueTipBehind * radius;
  pull.markers.push_back(
      stick(tip - kCueLength * radius, tip - 0.5 * radius, kCueThickness * radius, rgba(0.8, 0.6, 0.35, 1.0)));
  pull.markers.push_back(stick(tip - 0.5 * radius, tip, kCueThickness * radius, rgba(0.2, 0.4, 0.9, 1.0)));
  marker.controls.push_back(pull);

  // Across the cue (its y-z plane) by a knob at its tip: where it meets the ball.
  InteractiveMarkerControl offset;
  offset.name = kCueOffset;
  offset.interaction_mode = InteractiveMarkerControl::MOVE_PLANE;
  offset.orientation.w = 1.0;
  offset.always_visible = true;
  Marker knob;
  knob.type = Marker::SPHERE;
  knob.pose.position.x = tip - 0.25 * radius;
  knob.pose.orientation.w = 1.0;
  knob.scale.x = knob.scale.y = knob.scale.z = 0.7 * radius;
  knob.color = rgba(0.95, 0.95, 0.95, 0.8);
  offset.markers.push_back(knob);
  marker.controls.push_back(offset);

  // Turned about the floor's normal (aim), and about its own y axis (elevation): rings
  // that rviz draws.
  InteractiveMarkerControl aim;
  aim.name = kCueAim;
  aim.interaction_mode = InteractiveMarkerControl::ROTATE_AXIS;
  aim.orientation_mode = InteractiveMarkerControl::FIXED;
  aim.orientation = turning(core::Vec3::UnitX(), up);
  marker.controls.push_back(aim);
  InteractiveMarkerControl elevation;
  elevation.name = kCueElevation;
  elevation.interaction_mode = InteractiveMarkerControl::ROTATE_AXIS;
  elevation.orientation = turning(core::Vec3::UnitX(), core::Vec3::UnitY());
  marker.controls.push_back(elevation);
  return marker;
}
}  // namespace ball_collision_sim::bridge
