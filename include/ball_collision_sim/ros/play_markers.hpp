#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/types.hpp"
#include "ball_collision_sim/ros/cue_shot.hpp"

#include <geometry_msgs/Pose.h>
#include <visualization_msgs/InteractiveMarker.h>

#include <cstdint>
#include <string>

namespace ball_collision_sim::bridge
{
/// Interactive markers' names: "ball_<id>" per ball, and the cue.
std::string playMarkerName(int id);
constexpr const char* kCueMarker = "cue";
/// The ball id a marker's name gives ("ball_<id>"), or 0.
int ballOfPlayMarker(const std::string& name);

/// A ball's control, by name (feedback's control_name): dragged in the floor's plane.
constexpr const char* kBallMove = "move";
/// The cue's controls: pulled back along its axis, moved across it (the offset), turned
/// about the floor's normal (aim) and about its own y axis (elevation).
constexpr const char* kCuePull = "pull";
constexpr const char* kCueOffset = "offset";
constexpr const char* kCueAim = "aim";
constexpr const char* kCueElevation = "elevation";
/// Menu entries (feedback's menu_entry_id): "Cue ball" on a ball, "Put the cue away" on the cue.
constexpr std::uint32_t kMenuCueBall = 1;
constexpr std::uint32_t kMenuPutAway = 2;

/// A ball's marker at its centre: a translucent ring around it (1.4 radii), dragged in the
/// plane square to `up` (the floor's normal), with the menu entry "Cue ball".
visualization_msgs::InteractiveMarker ballPlayMarker(const core::Ball& ball, const std::string& frame_id,
                                                     const core::Vec3& up);
/// The cue at `pose` (cue_shot.hpp's frame) on ball `ball_id` of radius `radius` [m]: a
/// stick along its -x axis with its tip 1.5 radii behind the origin (pulled by the stick),
/// a knob at the tip (moved across the cue), and two rings rviz draws (turned about `up`
/// and about the cue's y axis); its menu puts it away.
visualization_msgs::InteractiveMarker cuePlayMarker(const CuePose& pose, int ball_id, double radius,
                                                    const std::string& frame_id, const core::Vec3& up);

geometry_msgs::Pose poseOf(const CuePose& cue);
CuePose cuePoseOf(const geometry_msgs::Pose& pose);
/// Every field the same, to the bit.
bool samePose(const geometry_msgs::Pose& a, const geometry_msgs::Pose& b);
}  // namespace ball_collision_sim::bridge
