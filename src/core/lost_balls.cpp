// Balls that left the world (the ground says what that is: off the floor, or without a
// floor outside the box the walls span). Reads balls_, feet_, walls_; removeLostBalls()
// takes them out of balls_, feet_ and spins_.
#include "ball_collision_sim/core/world.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace ball_collision_sim::core
{
namespace
{
/// Whether the line through p along `up` meets the box, grown by `margin`.
bool overBox(const Vec3& p, const Vec3& up, const Ground::Bounds& box, double margin)
{
  double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    const double lo = box.lo[a] - margin - p[a], hi = box.hi[a] + margin - p[a];
    if (up[a] == 0)
    {
      if (lo > 0 || hi < 0)
        return false;
      continue;
    }
    const double ta = lo / up[a], tb = hi / up[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}
}  // namespace

Ground::Bounds World::wallBounds() const
{
  Ground::Bounds bounds;
  for (const Wall& wall : walls_)
  {
    bounds.lo = bounds.any ? bounds.lo.cwiseMin(wall.box_min) : wall.box_min;
    bounds.hi = bounds.any ? bounds.hi.cwiseMax(wall.box_max) : wall.box_max;
    bounds.any = true;
  }
  return bounds;
}

std::string World::whyLost(std::size_t s, const Ground::Bounds& bounds) const
{
  const Ball& ball = balls_[s];
  // (a ball in flight over the walls' box, or in it, is in the world whatever lies under
  // it: near a wall the floor's nearest point to it can lie past the floor's edge, and it
  // comes down into the box again)
  if (ball.flying && bounds.any && overBox(ball.position, ground_.up(), bounds, ball.radius))
    return "";
  return ground_.whyOff(ball.position, ball.radius, footOf(s), bounds);
}

int World::lostBalls() const
{
  const Ground::Bounds bounds = wallBounds();
  int lost = 0;
  for (std::size_t s = 0; s < balls_.size(); ++s)
    lost += whyLost(s, bounds).empty() ? 0 : 1;
  return lost;
}

std::vector<LostBall> World::removeLostBalls()
{
  std::vector<LostBall> lost;
  const Ground::Bounds bounds = wallBounds();
  if (!ground_.bounded(bounds))
    return lost;
  bool any = false;
  for (std::size_t s = 0; s < balls_.size() && !any; ++s)
    any = !whyLost(s, bounds).empty();
  if (!any)
    return lost;
  sortById();  // (then a ball's slot is its place in balls(), and the lost come in id order)
  std::size_t kept = 0;
  for (std::size_t k = 0; k < balls_.size(); ++k)
  {
    std::string why = whyLost(k, bounds);
    if (!why.empty())
    {
      lost.push_back({balls_[k], angularVelocity(k), motionKind(k), inertia(k), std::move(why)});
      wakeTouching(balls_[k].position, balls_[k].radius);  // what leaned on it
      continue;
    }
    if (kept != k)
    {
      balls_[kept] = balls_[k];
      if (!feet_.empty())
        feet_[kept] = feet_[k];
      if (!spins_.empty())
        spins_[kept] = spins_[k];
    }
    ++kept;
  }
  balls_.resize(kept);
  by_id_.resize(kept);  // (in id order, slot k holds the k-th)
  if (!feet_.empty())
    feet_.resize(kept);
  if (!spins_.empty())
    spins_.resize(kept);
  forgetOrder();
  return lost;
}
}  // namespace ball_collision_sim::core
