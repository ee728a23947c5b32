#include "ball_collision_sim/ros/outputs.hpp"

#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/markers.hpp"

#include <geometry_msgs/Pose.h>

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::bridge
{
rosgraph_msgs::Clock clockMessage(const ros::Time& stamp)
{
  rosgraph_msgs::Clock msg;
  msg.clock = stamp;
  return msg;
}

BallStateArray statesMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp)
{
  BallStateArray msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.balls.reserve(world.balls().size());
  for (std::size_t k = 0; k < world.balls().size(); ++k)
    msg.balls.push_back(toMsg(world, k));
  return msg;
}

tf2_msgs::TFMessage transformsMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp,
                                      std::size_t max_balls, const std::string& prefix)
{
  tf2_msgs::TFMessage msg;
  const std::size_t count = std::min(world.balls().size(), max_balls);
  msg.transforms.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    msg.transforms.push_back(toTransform(world.balls()[i], frame_id, stamp, prefix));
  return msg;
}

BallColoring ballColoring(const core::World& world, const NodeSettings& node)
{
  BallColoring coloring;
  coloring.mode = node.ball_color;
  coloring.speed_max = node.speed_color_max;
  if (!(coloring.speed_max > 0))
  {
    coloring.speed_max = 0;
    for (const core::Ball& ball : world.balls())
      coloring.speed_max = std::max(coloring.speed_max, ball.velocity.norm());
    if (!(coloring.speed_max > 0))
      coloring.speed_max = 1.0;
  }
  return coloring;
}

visualization_msgs::MarkerArray ballMarkers(const core::World& world, const std::string& frame_id,
                                            const ros::Time& stamp, std::size_t list_threshold,
                                            const BallColoring& coloring)
{
  visualization_msgs::MarkerArray msg;
  if (world.balls().size() <= list_threshold)
  {
    msg.markers.reserve(world.balls().size());
    for (std::size_t k = 0; k < world.balls().size(); ++k)
      msg.markers.push_back(ballMarker(world.balls()[k], frame_id, stamp, coloring, world.motionKind(k)));
    return msg;
  }
  // One list per distinct radius, in increasing radius.
  std::vector<double> radii;
  radii.reserve(world.balls().size());
  for (const core::Ball& ball : world.balls())
    radii.push_back(ball.radius);
  std::sort(radii.begin(), radii.end());
  radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
  msg.markers.resize(radii.size());
  for (std::size_t k = 0; k < radii.size(); ++k)
  {
    visualization_msgs::Marker& m = msg.markers[k];
    core::Ball shape;
    shape.radius = radii[k];
    m = ballMarker(shape, frame_id, stamp, coloring);
    m.ns = kBallListsNs;
    m.id = static_cast<int>(k);
    m.type = visualization_msgs::Marker::SPHERE_LIST;
    m.pose = geometry_msgs::Pose();
    m.pose.orientation.w = 1.0;
  }
  for (std::size_t k = 0; k < world.balls().size(); ++k)
  {
    const core::Ball& ball = world.balls()[k];
    visualization_msgs::Marker& m =
        msg.markers[static_cast<std::size_t>(std::lower_bound(radii.begin(), radii.end(), ball.radius) - radii.begin())];
    m.points.push_back(toPoint(ball.position));
    m.colors.push_back(ballColor(ball, coloring, world.motionKind(k)));
  }
  return msg;
}

visualization_msgs::MarkerArray staticMarkers(const core::World& world, const std::string& frame_id)
{
  visualization_msgs::MarkerArray msg;
  if (world.floor())
    msg.markers.push_back(floorMarker(*world.floor(), frame_id));
  for (const core::Wall& wall : world.walls())
    msg.markers.push_back(wallMarker(wall, frame_id));
  const std::vector<core::PocketDef>& pockets = world.scene().pockets;
  for (std::size_t k = 0; k < pockets.size(); ++k)
    msg.markers.push_back(pocketMarker(pockets[k], static_cast<int>(k), world.floor(), frame_id));
  return msg;
}

void CollisionFlashes::add(const std::vector<core::CollisionEvent>& events)
{
  for (const core::CollisionEvent& event : events)
  {
    if (pending_.size() >= max_per_set_)
      return;
    if (!event.resting)
      pending_.push_back(event);
  }
}

std::vector<visualization_msgs::Marker> CollisionFlashes::take(const std::string& frame_id, const ros::Time& stamp)
{
  std::vector<visualization_msgs::Marker> out;
  out.reserve(pending_.size());
  for (const core::CollisionEvent& event : pending_)
  {
    out.push_back(collisionFlash(event, frame_id, stamp, next_id_));
    next_id_ = (next_id_ + 1) % kIdCycle;
  }
  pending_.clear();
  return out;
}

std::uint64_t stepsPer(double rate, double dt)
{
  if (!(rate > 0))
    return 1;
  // clamped: a vanishing rate must not overflow the count
  return static_cast<std::uint64_t>(std::clamp(std::round(1.0 / (rate * dt)), 1.0, 1e15));
}
}  // namespace ball_collision_sim::bridge
