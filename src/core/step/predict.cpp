// Stage 1, predict: each ball's free motion over the step, from its record (position,
// velocity) and the floor, and its swept box in the grid.
// Reads balls_, feet_, spins_; writes motions_, spin_motions_, floor_uv_,
// chord_ends_ and the grid's boxes.
#include "spin_model.hpp"
#include "floor_motion.hpp"
#include "stages.hpp"
#include "flight.hpp"

#include <utility>

namespace ball_collision_sim::core
{
using namespace step;

void step::predictMotions(StepContext& c)
{
  static_assert(sizeof(Motion) == 40, "a Motion is its start, its displacement and its counters");
  c.grid_.start(c.balls_.size(), c.ground_.up(), c.settings_, c.ground_.spreadsAlongUp());
  // (taken back at once, so that a step cut short by an exception leaves none ready)
  if (std::exchange(c.motions_ready_, false))
    return;  // the last step's commit predicted them
  c.motions_.resize(c.balls_.size());
  c.spin_->startStep(c);
  c.floor_uv_.resize(c.feet_.empty() ? 0 : c.balls_.size());  // where balls keep foot points
  c.chord_ends_.assign(c.feet_.empty() ? 0 : c.balls_.size(), 1.0);
  c.flow_ends_.assign(c.chord_ends_.size(), StepState::FlowEnd{});
  c.flights_ = 0;
  c.forEachBall([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      c.predictMotion(i, true);
  });
}

void StepContext::predictMotion(std::size_t i, bool at_step_start)
{
  const Ball& ball = balls_[i];
  Motion& m = motions_[i];
  m = Motion{};
  if (!chord_ends_.empty())
  {
    chord_ends_[i] = 1.0;
    flow_ends_[i].x = -1.0;
  }
  if (!floor_uv_.empty())
    floor_uv_[i] = feet_[i];
  if (ball.asleep())
  {
    motions_[i].type = MotionType::kAsleep;  // where it is, an obstacle, until woken
    spin_->predictAsleep(*this, i);
    grid_.setBox(static_cast<std::uint32_t>(i), sweptBox(ball.position, ball.position, ball.radius));
    return;
  }
  const bool takes_off = at_step_start && !ball.flying() && leavesFloor(*this, i, ball.position, ball.velocity);
  if (ball.flying() || takes_off)
  {
    spin_->predictFlight(*this, i);
    liftOff(*this, i, 0.0);  // (its kind recorded where it leaves the floor, or left it just now)
    startFlight(*this, i);
    grid_.setBox(static_cast<std::uint32_t>(i), currentBox(i));
    return;
  }
  if (!spin_->predictOnFloor(*this, i))  // (its friction phase made its motion)
  {
    grid_.setBox(static_cast<std::uint32_t>(i), currentBox(i));
    return;
  }
  // (a chord's box reaches the uncut chord's end)
  grid_.setBox(static_cast<std::uint32_t>(i),
               motions_[i].accelerates() ? currentBox(i) : sweptBox(ball.position, ball.position + m.b, ball.radius));
}

Aabb StepContext::currentBox(std::size_t i) const
{
  const Motion& m = motions_[i];
  const double rest = 1 - m.x0;
  if (!motions_[i].accelerates())
    return sweptBox(startPosition(i), startPosition(i) + (chordEnd(i) - m.x0) * m.b, balls_[i].radius);
  // the parabola lies within (rest^2 / 4) |c| of its chord, along each axis
  Aabb box = sweptBox(startPosition(i), positionAt(i, 1.0), balls_[i].radius);
  const Vec3 sag = (0.25 * rest * rest) * pathTerm(i).cwiseAbs();
  box.min -= sag;
  box.max += sag;
  return box;
}
}  // namespace ball_collision_sim::core
