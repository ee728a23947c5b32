// A ball's motion on the floor within the step: where it is, the floor's normal under
// it, its velocity there, the resting speed, and starting a new motion at an event.
// Reads motions_, states_, the floor; writes motions_ and the start velocity.
#include "step_types.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
using namespace step;

Vec3 World::positionAt(std::size_t i, double x) const
{
  const Motion& m = motions_[i];
  return m.p0 + (x - m.x0) * m.b;
}

Vec3 World::floorNormalAt(std::size_t i, const Vec3& position) const
{
  return ground_.normalAt(position, guessOf(i));
}

Vec3 World::onFloorVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const
{
  const Motion& m = motions_[i];
  return ground_.velocityAt(startVelocity(i), (x - m.x0) * dt_, m.p0, position, normal);
}

double World::stillSpeed(const Vec3& floor_normal) const
{
  return settings_.resting_steps * dt_ * ground_.gravityAlong(floor_normal) + settings_.resting_speed_floor;
}

double World::restingSpeed(const Vec3& floor_normal, double restitution) const
{
  // After an impact at closing speed v, gravity along the floor (a) brings the ball back
  // for bounces e times as fast each, which last 2 e v / (a (1 - e)) in all. Where that
  // is within resting_steps steps, their sum, rest against what was hit, is taken at
  // once: a resting contact. At e = 1 they never end (nor lose energy): no resting
  // contact but at round-off speeds.
  const double a = ground_.gravityAlong(floor_normal);
  if (!(restitution < 1))
    return settings_.resting_speed_floor;
  if (!(restitution > 0))
    return std::numeric_limits<double>::infinity();  // no bounce at all
  return settings_.resting_steps * dt_ * a * (1 - restitution) / (2 * restitution) + settings_.resting_speed_floor;
}

void World::startMotion(std::size_t i, double x, const Vec3& position, const Vec3& velocity, bool impact)
{
  Motion& m = motions_[i];
  Vec3& v0 = startVelocity(i);
  if (impact)
    states_[i].held = false;
  m.x0 = x;
  m.p0 = position;
  if (states_[i].frozen)
  {
    v0 = m.b = Vec3::Zero();
    return;
  }
  v0 = redirected(i, velocity);
  if (states_[i].held)
  {
    m.b = Vec3::Zero();  // still held (no impact let it go): it keeps no motion
    return;
  }
  const double rest = 1 - x;
  m.b = rest > 0 ? Vec3((predictedEnd(i, position, v0, rest * dt_) - position) / rest) : Vec3(dt_ * v0);
  m.b = allowed(i, m.b);
  endOnFloor(i);
  keepEnergy(i);
  if (states_[i].held)
    m.b = Vec3::Zero();
}

Vec3 World::onFloor(std::size_t i, const Vec3& q) const
{
  return ground_.land(q, motions_[i].radius, guessOf(i));
}
}  // namespace ball_collision_sim::core
