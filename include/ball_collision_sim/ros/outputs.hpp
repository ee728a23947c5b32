#pragma once

#include "ball_collision_sim/core/world.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <ros/time.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <string>

namespace ball_collision_sim::bridge
{
// What the simulator puts out about its world, built in one place so that the node's
// topics and the offline tool's rosbags carry the same messages.

/// Simulated time for /clock.
rosgraph_msgs::Clock clockMessage(const ros::Time& stamp);

/// Every ball's state, stamped `stamp` in `frame_id`.
BallStateArray statesMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp);
/// frame_id -> ball_<id> for the first `max_balls` balls.
tf2_msgs::TFMessage transformsMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp,
                                      std::size_t max_balls);
/// A sphere marker per ball, or, past `list_threshold` balls, one sphere list per radius
/// (rviz draws a few lists far faster than thousands of markers).
visualization_msgs::MarkerArray ballMarkers(const core::World& world, const std::string& frame_id,
                                            const ros::Time& stamp, std::size_t list_threshold);
/// The floor and the walls.
visualization_msgs::MarkerArray staticMarkers(const core::World& world, const std::string& frame_id);

/// Steps between outputs at `rate` per simulated second: round(1 / (rate dt)), at least
/// one; rate 0 means every step.
std::uint64_t stepsPer(double rate, double dt);
}  // namespace ball_collision_sim::bridge
