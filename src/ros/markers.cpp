#include "ball_collision_sim/ros/markers.hpp"

#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/core/placement.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::bridge
{
namespace
{
std_msgs::ColorRGBA mix(const std_msgs::ColorRGBA& a, const std_msgs::ColorRGBA& b, double t)
{
  return rgba(a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b), a.a + t * (b.a - a.a));
}

/// A colour of full saturation for hue h in [0, 1).
std_msgs::ColorRGBA hue(double h, double value, double alpha)
{
  const double x = 6 * (h - std::floor(h));
  const double r = std::clamp(std::abs(x - 3) - 1, 0.0, 1.0);
  const double g = std::clamp(2 - std::abs(x - 2), 0.0, 1.0);
  const double b = std::clamp(2 - std::abs(x - 4), 0.0, 1.0);
  return rgba(value * r, value * g, value * b, alpha);
}

visualization_msgs::Marker base(const std::string& ns, int id, int type, const std::string& frame_id)
{
  visualization_msgs::Marker m;
  m.header.frame_id = frame_id;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  return m;
}
}  // namespace

visualization_msgs::Marker floorMarker(const core::Floor& floor, const std::string& frame_id, int resolution)
{
  visualization_msgs::Marker m = base(kFloorNs, 0, visualization_msgs::Marker::TRIANGLE_LIST, frame_id);
  const int n = std::max(1, floor.isPlane() ? 1 : resolution);
  std::vector<core::Vec3> grid;
  grid.reserve((n + 1) * (n + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      grid.push_back(floor.point(core::Vec2(double(i) / n, double(j) / n)));
  // Shade by height along "up": low is dark green-blue, high is light.
  double lo = 1e300, hi = -1e300;
  for (const core::Vec3& p : grid)
  {
    lo = std::min(lo, p.dot(floor.up()));
    hi = std::max(hi, p.dot(floor.up()));
  }
  auto shade = [&](const core::Vec3& p) {
    const double t = hi > lo ? (p.dot(floor.up()) - lo) / (hi - lo) : 0.5;
    return rgba(0.15 + 0.35 * t, 0.35 + 0.4 * t, 0.3 + 0.2 * t, 1.0);
  };
  auto at = [&](int i, int j) -> const core::Vec3& { return grid[i * (n + 1) + j]; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (const auto& [a, b] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 0}, std::pair{1, 1},
                                 std::pair{0, 1}})
      {
        const core::Vec3& p = at(i + a, j + b);
        m.points.push_back(toPoint(p));
        m.colors.push_back(shade(p));
      }
  m.color = rgba(0.4, 0.6, 0.45, 1.0);
  return m;
}

visualization_msgs::Marker wallMarker(const core::Wall& wall, const std::string& frame_id)
{
  visualization_msgs::Marker m = base(kWallsNs, wall.id, visualization_msgs::Marker::TRIANGLE_LIST, frame_id);
  const auto& c = wall.corners;
  // Colours per vertex: rviz then draws the triangles unlit and shows them from both
  // sides (with one colour only it lights them from no normal, and they come out nearly
  // black). Pale blue glass, clearer toward the far edge (point + v, the top of an
  // upright wall).
  for (const int k : {0, 1, 2, 0, 2, 3})
  {
    m.points.push_back(toPoint(c[k]));
    m.colors.push_back(k < 2 ? rgba(0.6, 0.8, 1.0, 0.45) : rgba(0.6, 0.8, 1.0, 0.2));
  }
  m.color = rgba(0.6, 0.8, 1.0, 1.0);  // rviz multiplies each vertex's alpha by this one
  return m;
}

visualization_msgs::Marker pocketMarker(const core::PocketDef& pocket, int index, const std::optional<core::Floor>& floor,
                                        const std::string& frame_id)
{
  visualization_msgs::Marker m = base(kPocketsNs, index, visualization_msgs::Marker::CYLINDER, frame_id);
  // (on the floor under its centre, as a ball of no size would stand there)
  core::BallDef probe;
  probe.position = core::Vec3(pocket.position.x(), pocket.position.y(), 0.0);
  probe.radius = 1e-4;
  core::placeOnFloor(probe, floor, nullptr, core::Landing::kUnder);
  const core::Vec3 up = floor ? floor->up() : core::Vec3(core::Vec3::UnitZ());
  m.pose.position = toPoint(probe.position - 0.5 * probe.radius * up);
  m.pose.orientation = toQuaternion(core::Quat::FromTwoVectors(core::Vec3::UnitZ(), up));
  m.scale.x = m.scale.y = 2 * pocket.radius;
  m.scale.z = probe.radius;
  m.color = rgba(0.02, 0.02, 0.02, 1.0);
  return m;
}

std_msgs::ColorRGBA ballColor(const core::Ball& ball, const BallColoring& coloring, core::MotionKind motion)
{
  if (coloring.mode == BallColor::kId)
    return hue(0.61803398875 * ball.id + 0.05, 0.95, 1.0);
  if (coloring.mode == BallColor::kMotion)
    switch (motion)
    {
      case core::MotionKind::kSliding:
        return rgba(0.95, 0.2, 0.15, 1.0);
      case core::MotionKind::kRolling:
        return rgba(0.2, 0.4, 1.0, 1.0);
      case core::MotionKind::kSpinning:
        return rgba(1.0, 0.6, 0.1, 1.0);
      case core::MotionKind::kStationary:
        return rgba(0.55, 0.55, 0.55, 1.0);
      case core::MotionKind::kFlying:
        return rgba(0.2, 0.85, 0.35, 1.0);
    }
  const double t = coloring.speed_max > 0 ? std::clamp(ball.velocity.norm() / coloring.speed_max, 0.0, 1.0) : 1.0;
  const std_msgs::ColorRGBA slow = rgba(0.2, 0.35, 1.0, 1.0), middle = rgba(0.9, 0.15, 0.65, 1.0),
                            fast = rgba(1.0, 0.85, 0.1, 1.0);
  return t < 0.5 ? mix(slow, middle, 2 * t) : mix(middle, fast, 2 * t - 1);
}

visualization_msgs::Marker ballMarker(const core::Ball& ball, const std::string& frame_id, const ros::Time& stamp,
                                      const BallColoring& coloring, core::MotionKind motion)
{
  visualization_msgs::Marker m = base(kBallsNs, ball.id, visualization_msgs::Marker::SPHERE, frame_id);
  m.header.stamp = stamp;
  m.pose.position = toPoint(ball.position);
  m.pose.orientation.x = ball.orientation.x();
  m.pose.orientation.y = ball.orientation.y();
  m.pose.orientation.z = ball.orientation.z();
  m.pose.orientation.w = ball.orientation.w();
  m.scale.x = m.scale.y = m.scale.z = 2 * ball.radius;
  m.color = ballColor(ball, coloring, motion);
  return m;
}

visualization_msgs::Marker collisionFlash(const core::CollisionEvent& event, const std::string& frame_id,
                                          const ros::Time& stamp, int id)
{
  visualization_msgs::Marker m = base(kCollisionsNs, id, visualization_msgs::Marker::SPHERE, frame_id);
  m.header.stamp = stamp;
  m.pose.position = toPoint(event.point);
  m.scale.x = m.scale.y = m.scale.z = kFlashSize;
  m.color = rgba(1.0, 1.0, 0.75, 0.9);
  m.lifetime = ros::Duration(kFlashLifetime);
  return m;
}

visualization_msgs::Marker deleteMarker(const std::string& ns, int id, const std::string& frame_id)
{
  visualization_msgs::Marker m = base(ns, id, visualization_msgs::Marker::SPHERE, frame_id);
  m.action = visualization_msgs::Marker::DELETE;
  return m;
}

visualization_msgs::Marker deleteAllMarker(const std::string& frame_id)
{
  visualization_msgs::Marker m = base("", 0, visualization_msgs::Marker::SPHERE, frame_id);
  m.action = visualization_msgs::Marker::DELETEALL;
  return m;
}
}  // namespace ball_collision_sim::bridge
