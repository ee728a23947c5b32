// Balls that left the world (the ground says what that is: off the floor, or without a
// floor outside the box the walls span). Reads balls_, feet_, walls_; removeLostBalls()
// takes them out of balls_, feet_ and spins_.
#include "step/step_context.hpp"

#include <utility>

namespace ball_collision_sim::core
{
Ground::Bounds StepContext::wallBounds() const
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

std::string StepContext::whyLost(std::size_t s, const Ground::Bounds& bounds) const
{
  const Ball& ball = balls_[s];
  // (a ball in flight is in the world whatever lies under it, until it has fallen past the
  // floor's edge: near a wall the floor's nearest point to it can lie past that edge)
  if (ball.flying())
    return ground_.whyFallen(ball.position, ball.radius, bounds);
  return ground_.whyOff(ball.position, ball.radius, footOf(s), bounds);
}

int World::lostBalls() const
{
  const StepContext& c = *c_;
  const Ground::Bounds bounds = c.wallBounds();
  int lost = 0;
  for (std::size_t s = 0; s < c.balls_.size(); ++s)
    lost += c.whyLost(s, bounds).empty() ? 0 : 1;
  return lost;
}

std::vector<LostBall> World::removeLostBalls()
{
  StepContext& c = *c_;
  std::vector<LostBall> lost;
  const Ground::Bounds bounds = c.wallBounds();
  if (!c.ground_.bounded(bounds))
    return lost;
  bool any = false;
  for (std::size_t s = 0; s < c.balls_.size() && !any; ++s)
    any = !c.whyLost(s, bounds).empty();
  if (!any)
    return lost;
  c.sortById();  // (then a ball's slot is its place in balls(), and the lost come in id order)
  std::size_t kept = 0;
  for (std::size_t k = 0; k < c.balls_.size(); ++k)
  {
    std::string why = c.whyLost(k, bounds);
    if (!why.empty())
    {
      lost.push_back({c.balls_[k], angularVelocity(k), motionKind(k), inertia(k), std::move(why)});
      c.wakeTouching(c.balls_[k].position, c.balls_[k].radius);  // what leaned on it
      continue;
    }
    if (kept != k)
    {
      c.balls_[kept] = c.balls_[k];
      if (!c.feet_.empty())
        c.feet_[kept] = c.feet_[k];
      if (!c.spins_.empty())
        c.spins_[kept] = c.spins_[k];
    }
    ++kept;
  }
  c.balls_.resize(kept);
  c.by_id_.resize(kept);  // (in id order, slot k holds the k-th)
  if (!c.feet_.empty())
    c.feet_.resize(kept);
  if (!c.spins_.empty())
    c.spins_.resize(kept);
  c.forgetOrder();
  return lost;
}
}  // namespace ball_collision_sim::core
