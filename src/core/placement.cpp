#include "ball_collision_sim/core/placement.hpp"

#include "ball_collision_sim/core/format.hpp"


namespace ball_collision_sim::core
{
std::string placeOnFloor(BallDef& ball, const std::optional<Floor>& floor, Vec2* uv)
{
  if (!floor)
    return "";
  const FloorFoot foot = floor->project(ball.position, Vec2(0.5, 0.5));
  if (!foot.inside)
    return "off the floor (its foot point at u = " + formatNumber(foot.uv.x()) + ", v = " + formatNumber(foot.uv.y()) +
           " is outside [0, 1]^2)";
  if (foot.height < -kContactTolerance)
    return "off the floor (its centre is " + formatNumber(-foot.height) + " m below the surface)";
  if (foot.height > 2 * ball.radius + kContactTolerance)
    return "off the floor (its centre is " + formatNumber(foot.height) +
           " m above the surface; balls roll on it, centre one radius above)";
  ball.position = floor->ballCentre(foot, ball.radius);
  ball.velocity -= ball.velocity.dot(foot.normal) * foot.normal;
  if (uv)
    *uv = foot.uv;
  return "";
}

std::optional<Overlap> wallOverlap(const BallDef& ball, const std::vector<Wall>& walls)
{
  for (std::size_t k = 0; k < walls.size(); ++k)
  {
    const double depth = ball.radius - walls[k].distance(ball.position);
    if (depth > kContactTolerance)
      return Overlap{k, depth};
  }
  return std::nullopt;
}

Placement::Placement(const Scene& scene)
{
  if (scene.floor)
    floor_.emplace(*scene.floor, scene.gravity);
  for (std::size_t k = 0; k < scene.walls.size(); ++k)
    walls_.emplace_back(static_cast<int>(k), scene.walls[k], scene.restitution);
}

std::string Placement::place(BallDef& ball, Vec2* uv) const
{
  std::string why = placeOnFloor(ball, floor_, uv);
  if (why.empty())
    if (const auto overlap = wallOverlap(ball, walls_))
      why = "overlaps walls[" + std::to_string(overlap->index) + "] by " + formatNumber(overlap->depth) + " m";
  return why;
}
}  // namespace ball_collision_sim::core
