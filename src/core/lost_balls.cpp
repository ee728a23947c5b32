// Balls that left the world (the ground says what that is: off the floor, or without a
// floor outside the box the walls span). Reads balls_, feet_, walls_; removeLostBalls()
// takes them out of balls_, feet_ and spins_ (removeBalls(), which the step's pockets use too).
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
  c.removeBalls([&](std::size_t s) {
    std::string why = c.whyLost(s, bounds);
    if (why.empty())
      return false;
    lost.push_back({c.balls_[s], angularVelocity(s), motionKind(s), inertia(s), std::move(why)});
    return true;
  });
  return lost;
}

void StepContext::removeBalls(const std::function<bool(std::size_t)>& gone)
{
  sortById();  // (then a ball's slot is its place in balls(), and the gone come in id order)
  std::size_t kept = 0;
  for (std::size_t k = 0; k < balls_.size(); ++k)
  {
    if (gone(k))
    {
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
}
}  // namespace ball_collision_sim::core
