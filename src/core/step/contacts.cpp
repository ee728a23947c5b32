// Resting contacts: the directions a ball may not move along for the rest of the step,
// holding balls still, and what a motion's energy allows (FloorMotion::keepEnergy(), with
// the floor's motion type saying where its motion ends and how it is cut short).
// Reads and writes motions_, balls_' sleep, and a stopped ball's spin_motions_; reads the
// contact solver's work space (the step's resting contacts at its end).
#include "spin_model.hpp"
#include "contact_group.hpp"
#include "spin_phase.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

void StepContext::wakeGroup(std::size_t first)
{
  std::vector<std::size_t> todo{first};
  while (!todo.empty())
  {
    const std::size_t k = todo.back();
    todo.pop_back();
    if (!motions_[k].asleep())
      continue;
    motions_[k].type = MotionType::kLine;  // (still, until its next motion starts)
    Ball& ball = balls_[k];
    ball.support = Ball::Support::kFloor;
    ball.quiet_steps = 0;
    ++stats_.woken_balls;
    grid_.query(static_cast<std::uint32_t>(k), [&](std::uint32_t other) {
      const Ball& b = balls_[other];
      const double reach = b.radius + ball.radius + settings_.touch_slack;
      if (motions_[other].asleep() && (b.position - ball.position).norm() <= reach && !wallBetween(ball, b))
        todo.push_back(other);
    });
  }
}

bool StepContext::wallBetween(const Ball& a, const Ball& b) const
{
  // Balls that touch one another meet where their centres' line crosses; balls on the
  // two sides of a wall meet the wall there instead.
  const Vec3 middle = 0.5 * (a.position + b.position);
  const double near = 0.5 * std::min(a.radius, b.radius);
  return std::any_of(walls_.begin(), walls_.end(), [&](const Wall& wall) { return wall.distance(middle) < near; });
}

void StepContext::wakeAll()
{
  // (a ball awake keeps its count of still steps: the edit did not move it, and a step
  // that it moves in starts the count again)
  for (Ball& ball : balls_)
    if (ball.asleep())
    {
      ball.support = Ball::Support::kFloor;
      ball.quiet_steps = 0;
    }
  motions_ready_ = false;  // (a prediction made while they slept)
}

void StepContext::wakeTouching(const Vec3& position, double radius)
{
  for (Ball& ball : balls_)
    if (ball.asleep() && (ball.position - position).norm() <= ball.radius + radius + settings_.touch_slack)
    {
      ball.support = Ball::Support::kFloor;
      ball.quiet_steps = 0;
      ++stats_.woken_balls;
    }
  motions_ready_ = false;
}

void StepContext::sleepStillGroups()
{
  // Groups: balls joined by the step's resting contacts that touch at its end (endGroup()'s
  // rows), by union-find over the visiting order (its smallest index stands for a group;
  // the same groups whatever the order).
  const ContactGroup& group = contact_group_.made();
  const std::size_t n = balls_.size();
  std::vector<std::uint32_t> parent(n);
  for (std::size_t k = 0; k < n; ++k)
    parent[k] = static_cast<std::uint32_t>(k);
  const auto root = [&](std::size_t k) {
    while (parent[k] != k)
      k = parent[k] = parent[parent[k]];
    return k;
  };
  std::vector<char> leans(n, 0);
  for (const ContactRow& row : group.rows)
  {
    const std::size_t i = group.ballAt(row.a);
    leans[i] = 1;
    if (row.b == ContactRow::kImmovable)
      continue;  // (a wall)
    const std::size_t j = group.ballAt(row.b);
    leans[j] = 1;
    if (motions_[i].asleep() || motions_[j].asleep())
      continue;  // a sleeping ball holds the other like a wall does
    const std::size_t a = root(i), b = root(j);
    parent[std::max(a, b)] = static_cast<std::uint32_t>(std::min(a, b));
  }
  // a group sleeps when every ball in it has been still long enough
  std::vector<char> restless(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    Ball& ball = balls_[k];
    if (ball.asleep())
      continue;
    const bool still = leans[k] && ball.velocity.norm() <= settings_.sleep_speed;
    ball.quiet_steps = still ? static_cast<std::uint16_t>(std::min<int>(ball.quiet_steps + 1, 0xffff)) : 0;
    if (ball.quiet_steps < sleep_steps_)
      restless[root(k)] = 1;
  }
  std::uint64_t asleep = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    Ball& ball = balls_[k];
    if (!ball.asleep() && ball.quiet_steps >= sleep_steps_ && !restless[root(k)])
    {
      ball.support = Ball::Support::kAsleep;
      ball.velocity = Vec3::Zero();
    }
    asleep += ball.asleep() ? 1 : 0;
  }
  stats_.sleeping_balls = asleep;
}

void StepContext::stop(std::size_t i)
{
  noteStopped();
  motions_[i].b = startVelocity(i) = Vec3::Zero();
  if (!flow_ends_.empty())
    flow_ends_[i].x = -1.0;
  // (with friction its spin then follows from its contacts, not from a phase whose motion
  // it does not make: FrictionLaw::constrained())
  spin_->stop(*this, i);
}

double StepContext::EnergyCheck::speedSquaredWith(const Vec3& b) const
{
  return world->speedSquaredAt(i, world->chordEnd(i), world->onFloor(i, world->startPosition(i) + rest * b));
}

double StepContext::EnergyCheck::speedSquared(double s) const
{
  return speedSquaredWith(s * world->motions_[i].b);
}

double StepContext::EnergyCheck::chordSpeedSquared(const Vec3& b) const
{
  // (a chord's: its end is off the floor)
  return world->spin_->chordSpeedSquared(*world, i, rest, b);
}
}  // namespace ball_collision_sim::core
