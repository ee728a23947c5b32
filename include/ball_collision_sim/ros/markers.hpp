#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <ros/time.h>
#include <visualization_msgs/Marker.h>

#include <string>

namespace ball_collision_sim::bridge
{
/// Marker namespaces; within each the marker id is the object's id.
constexpr const char* kFloorNs = "floor";
constexpr const char* kWallsNs = "walls";
constexpr const char* kBallsNs = "balls";
/// Many balls: one SPHERE_LIST per radius, id = the radius' rank.
constexpr const char* kBallListsNs = "ball_lists";

/// The floor as a triangle mesh of resolution x resolution quads, shaded by height.
visualization_msgs::Marker floorMarker(const core::Floor& floor, const std::string& frame_id, int resolution = 24);
/// A translucent wall (two triangles a side).
visualization_msgs::Marker wallMarker(const core::Wall& wall, const std::string& frame_id);
/// A sphere with the ball's radius and orientation, coloured by id.
visualization_msgs::Marker ballMarker(const core::Ball& ball, const std::string& frame_id, const ros::Time& stamp);
visualization_msgs::Marker deleteMarker(const std::string& ns, int id, const std::string& frame_id);
visualization_msgs::Marker deleteAllMarker(const std::string& frame_id);
}  // namespace ball_collision_sim::bridge
