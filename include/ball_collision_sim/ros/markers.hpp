#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/collision_event.hpp"
#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/friction.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/wall.hpp"
#include "ball_collision_sim/node_settings.hpp"

#include <ros/time.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/Marker.h>

#include <string>

namespace ball_collision_sim::bridge
{
/// Marker namespaces; within each the marker id is the object's id.
constexpr const char* kFloorNs = "floor";
constexpr const char* kWallsNs = "walls";
/// Pockets: the marker id is the pocket's index in the scene.
constexpr const char* kPocketsNs = "pockets";
constexpr const char* kBallsNs = "balls";
/// Many balls: one SPHERE_LIST per radius, id = the radius' rank.
constexpr const char* kBallListsNs = "ball_lists";
/// Short-lived flashes at collisions' contact points; ids cycle (see collisionFlash).
constexpr const char* kCollisionsNs = "collisions";

/// How long a collision flash stays in rviz [s] (rviz counts it on its clock: simulated
/// time when /use_sim_time is set).
constexpr double kFlashLifetime = 0.3;
/// Diameter of a collision flash [m].
constexpr double kFlashSize = 0.12;

/// How balls are coloured.
struct BallColoring
{
  BallColor mode = BallColor::kSpeed;
  double speed_max = 1.0;  ///< speed shown at the top of the scale, and above it [m/s]; > 0
};

/// By speed: blue when still, through magenta, to yellow at `speed_max` and above (never
/// green, so balls stand out on the green floor). By id: golden-ratio steps of hue, so
/// that neighbouring ids get clearly different colours. By motion (`motion`, its state):
/// sliding red, rolling blue, spinning orange, stationary grey.
std_msgs::ColorRGBA ballColor(const core::Ball& ball, const BallColoring& coloring,
                              core::MotionKind motion = core::MotionKind::kRolling);

/// The floor as a triangle mesh of resolution x resolution quads, shaded by height.
visualization_msgs::Marker floorMarker(const core::Floor& floor, const std::string& frame_id, int resolution = 24);
/// A translucent wall: two triangles, pale blue, more transparent toward point + v.
visualization_msgs::Marker wallMarker(const core::Wall& wall, const std::string& frame_id);
/// A pocket as a black disc on the floor under its centre.
visualization_msgs::Marker pocketMarker(const core::PocketDef& pocket, int index, const std::optional<core::Floor>& floor,
                                        const std::string& frame_id);
/// A sphere with the ball's radius and orientation, coloured by ballColor().
visualization_msgs::Marker ballMarker(const core::Ball& ball, const std::string& frame_id, const ros::Time& stamp,
                                      const BallColoring& coloring,
                                      core::MotionKind motion = core::MotionKind::kRolling);
/// A bright sphere of kFlashSize at the contact point, gone after kFlashLifetime.
visualization_msgs::Marker collisionFlash(const core::CollisionEvent& event, const std::string& frame_id,
                                          const ros::Time& stamp, int id);
visualization_msgs::Marker deleteMarker(const std::string& ns, int id, const std::string& frame_id);
visualization_msgs::Marker deleteAllMarker(const std::string& frame_id);
}  // namespace ball_collision_sim::bridge
