// What a World tells of itself between steps: its energy, momentum and state hash, a
// ball by id, and each ball's spin, motion kind and inertia. Reads the StepContext's
// records (balls_, spins_, feet_) in id order.
#include "ball_collision_sim/core/world.hpp"

#include "step/step_context.hpp"
#include "step/spin_model.hpp"

#include "ball_collision_sim/core/state_hash.hpp"

namespace ball_collision_sim::core
{

Energy World::energy() const
{
  const StepContext& c = *c_;
  // (summed in id order: the same sums whatever order the records are in)
  Energy e;
  for (const std::uint32_t s : c.by_id_)
  {
    const Ball& ball = c.balls_[s];
    e.kinetic += 0.5 * ball.mass * ball.velocity.squaredNorm();
    e.potential -= ball.mass * c.gravity_.dot(ball.position);
  }
  if (!c.spins_.empty())
    for (const std::uint32_t s : c.by_id_)
    {
      const Ball& ball = c.balls_[s];
      e.rotational +=
          0.5 * c.spins_[s].inertia * ball.mass * ball.radius * ball.radius * c.spins_[s].angular_velocity.squaredNorm();
    }
  return e;
}

Vec3 World::momentum() const
{
  const StepContext& c = *c_;
  Vec3 p = Vec3::Zero();
  for (const std::uint32_t s : c.by_id_)
    p += c.balls_[s].mass * c.balls_[s].velocity;
  return p;
}

std::uint64_t World::stateHash() const
{
  const StepContext& c = *c_;
  Fnv1a h;
  h.add(c.stats_.steps);
  h.add(c.balls_.size());
  for (const std::uint32_t s : c.by_id_)
  {
    const Ball& ball = c.balls_[s];
    h.add(ball.id);
    h.add(ball.radius);
    h.add(ball.mass);
    h.add(ball.position.data(), 3 * sizeof(double));
    h.add(ball.velocity.data(), 3 * sizeof(double));
    h.add(ball.orientation.coeffs().data(), 4 * sizeof(double));
  }
  for (std::size_t k = 0; k < c.spins_.size(); ++k)
  {
    const BallSpin& spin = c.spins_[c.by_id_[k]];
    h.add(spin.angular_velocity.data(), 3 * sizeof(double));
    h.add(spin.inertia);
    h.add(spin.kind);
  }
  return h.value();
}

const Ball* World::findBall(int id) const
{
  const StepContext& c = *c_;
  const std::size_t s = c.slotOf(id);
  return s < c.balls_.size() ? &c.balls_[s] : nullptr;
}

Vec3 World::angularVelocity(std::size_t k) const
{
  const StepContext& c = *c_;
  return c.spin_->angularVelocity(c, c.by_id_.at(k));
}

MotionKind World::motionKind(std::size_t k) const
{
  const StepContext& c = *c_;
  const std::size_t s = c.by_id_.at(k);
  if (c.balls_[s].flying())
    return MotionKind::kFlying;
  return c.spin_->kindOnFloor(c, s);
}

double World::inertia(std::size_t k) const
{
  const StepContext& c = *c_;
  return c.spin_->inertia(c, c.by_id_.at(k));
}

void World::recordEvents(bool record)
{
  StepContext& c = *c_;
  c.record_events_ = record;
  if (!record)
    std::vector<CollisionEvent>().swap(c.events_);
}
}  // namespace ball_collision_sim::core
