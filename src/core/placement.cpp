#include "ball_collision_sim/core/placement.hpp"

#include "ball_collision_sim/core/format.hpp"

#include <cmath>

namespace ball_collision_sim::core
{
namespace
{
/// Most Newton steps along gravity to find where a ball rests under a point. The distance
/// to the surface has the normal as its gradient, so the steps converge quadratically:
/// a handful suffice on any floor that is a graph over the plane across gravity.
constexpr int kMaxLandingIterations = 32;
/// Newton along gravity stops when the centre is this close to one radius above the
/// surface, relative to the ball's size and distance from the origin: round-off.
constexpr double kLandingTolerance = 1e-14;

std::string offTheFloor(const FloorFoot& foot)
{
  return "off the floor (its foot point at u = " + formatNumber(foot.uv.x()) + ", v = " + formatNumber(foot.uv.y()) +
         " is outside [0, 1]^2)";
}

/// The foot of the centre that rests on the floor under `p` along gravity: the point
/// p + h up at height r above the surface, by Newton's method on h.
FloorFoot footUnder(const Floor& floor, const Vec3& p, double radius)
{
  const Vec3& up = floor.up();
  const double scale = kLandingTolerance * (radius + p.cwiseAbs().maxCoeff());
  FloorFoot foot = floor.project(p, Vec2(0.5, 0.5));
  double h = 0.0;
  for (int it = 0; it < kMaxLandingIterations && std::abs(foot.height - radius) > scale; ++it)
  {
    // d(height)/dh = <normal, up>: the floor's slope; a floor at right angles to gravity
    // has no point under p to rest on
    const double rise = foot.normal.dot(up);
    if (!(rise > 0))
      break;
    h -= (foot.height - radius) / rise;
    foot = floor.project(p + h * up, foot.uv);
  }
  return foot;
}
}  // namespace

namespace
{
/// placeOnFloor() as Landing::kAsGiven says: the centre and velocity stay as they are.
std::string placeAsGiven(BallDef& ball, const Floor& floor, Vec2* uv, bool* flying)
{
  const FloorFoot foot = floor.project(ball.position, Vec2(0.5, 0.5));
  if (!foot.inside)
    return offTheFloor(foot);
  const double gap = foot.height - ball.radius;
  if (gap < -kContactTolerance)
    return "below the floor (its centre is " + formatNumber(foot.height) + " m from the surface, less than its radius " +
           formatNumber(ball.radius) + " m)";
  // (touching the floor, it takes off at once where its velocity points away from it;
  // else the floor takes the velocity's part into it)
  const double along_normal = ball.velocity.dot(foot.normal);
  const bool in_flight = gap > kContactTolerance || along_normal > 0;
  if (!in_flight)
    ball.velocity -= along_normal * foot.normal;
  if (flying)
    *flying = in_flight;
  if (uv)
    *uv = foot.uv;
  return "";
}
}  // namespace

Landing landingOf(BallPlacement placement)
{
  return placement == BallPlacement::kAsGiven ? Landing::kAsGiven : Landing::kNearest;
}

std::string placeOnFloor(BallDef& ball, const std::optional<Floor>& floor, Vec2* uv, Landing landing, bool* flying)
{
  if (flying)
    *flying = false;
  if (!floor)
    return "";
  if (landing == Landing::kAsGiven)
    return placeAsGiven(ball, *floor, uv, flying);
  const FloorFoot foot = landing == Landing::kUnder ? footUnder(*floor, ball.position, ball.radius)
                                                    : floor->project(ball.position, Vec2(0.5, 0.5));
  if (!foot.inside)
    return offTheFloor(foot);
  if (landing == Landing::kUnder && std::abs(foot.height - ball.radius) > kContactTolerance)
    return "off the floor (no point of it under the centre along gravity)";
  if (landing == Landing::kExact && std::abs(foot.height - ball.radius) > kContactTolerance)
    return "not resting on the floor (its centre is " + formatNumber(foot.height) +
           " m from the surface, its radius " + formatNumber(ball.radius) + " m)";
  if (landing == Landing::kNearest && foot.height < -kContactTolerance)
    return "off the floor (its centre is " + formatNumber(-foot.height) + " m below the surface)";
  if (landing == Landing::kNearest && foot.height > 2 * ball.radius + kContactTolerance)
    return "off the floor (its centre is " + formatNumber(foot.height) +
           " m above the surface; balls roll on it, centre one radius above)";
  ball.position = floor->ballCentre(foot, ball.radius);
  ball.velocity -= ball.velocity.dot(foot.normal) * foot.normal;
  if (uv)
    *uv = foot.uv;
  return "";
}

std::string overlapMessage(const std::string& what, double depth)
{
  return "overlaps " + what + " by " + formatNumber(depth) + " m";
}

std::string placeAmongWalls(BallDef& ball, const std::optional<Floor>& floor, const std::vector<Wall>& walls,
                            Landing landing, Vec2* uv, const std::function<std::string(std::size_t)>& wall_name,
                            bool* flying)
{
  std::string why = placeOnFloor(ball, floor, uv, landing, flying);
  if (why.empty())
    if (const auto overlap = wallOverlap(ball, walls))
      why = overlapMessage(wall_name(overlap->index), overlap->depth);
  return why;
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
  return placeAmongWalls(ball, floor_, walls_, landingOf(ball.placement), uv,
                         [](std::size_t k) { return "walls[" + std::to_string(k) + "]"; });
}
}  // namespace ball_collision_sim::core
