// Stage 4, resolve: events in time order, earliest first; an impact bounces (or, slow
// enough, becomes a resting contact), and the balls involved get new motions and are
// detected again. Reads and writes motions_, the queue, the start positions and velocities;
// writes events_ and stats_.
#include "spin_model.hpp"
#include "floor_motion.hpp"
#include "stages.hpp"
#include "flight.hpp"

#include "ball_collision_sim/core/response.hpp"
#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

void step::resolveEventsInTimeOrder(StepContext& c)
{
  while (!c.queue_.empty())
  {
    {
      // the first event's balls' data are fetched while the queue is put in order
      const auto fetch = [&](std::uint32_t k) {
        __builtin_prefetch(&c.motions_[k]);
        __builtin_prefetch(&c.balls_[k]);
      };
      const auto& next = c.queue_.top();
      fetch(next.i);
      if (!ofOneBall(next.kind))
        fetch(next.j);
    }
    const Event event = c.queue_.pop();
    if (c.motions_[event.i].epoch != event.epoch_i ||
        (!ofOneBall(event.kind) && c.motions_[event.j].epoch != event.epoch_j))
    {
      ++c.stats_.stale_events;  // a ball involved has had an event since this was found
      continue;
    }
    c.resolve(event);
  }
}

void StepContext::resolve(const Event& event)
{
  switch (event.kind)
  {
    case EventKind::kBallBall:
      return resolveBallBall(event);
    case EventKind::kBallWall:
      return resolveBallWall(event);
    case EventKind::kPocket:
      return resolvePocket(event);
    case EventKind::kMotionEnd:
      break;
  }
  switch (event.end)
  {
    case MotionEnd::kLanding:
      return resolveLanding(*this, event);
    case MotionEnd::kTakeOff:
      return resolveTakeOff(*this, event);
    case MotionEnd::kPhase:
    case MotionEnd::kCut:
      return resolveMotionEnd(event);
  }
}

void StepContext::resolveBallWall(const Event& event)
{
  const std::size_t i = event.i;
  const Wall& wall = walls_[event.j];
  const Ball& ball = balls_[i];
  const Vec3 p = positionAt(i, event.x);
  const Vec3 floor_normal = floorNormalAt(i, p);
  Vec3 v = onFloorVelocity(i, event.x, p, floor_normal);

  const Vec3 n = -event.normal;  // from the ball toward the wall
  // (a ball in flight is pushed along the normal itself; it rests on nothing)
  const Vec3 dir = ball.flying() ? n : wallPush(n, floor_normal);
  const double closing = v.dot(dir);
  const bool resting = !ball.flying() && closing <= restingSpeed(floor_normal, wall.restitution, p, ball.radius);
  if (resting)
  {
    // a resting contact: a constraint of the ball's group from now on
    link(i, kWallRow | static_cast<std::uint32_t>(event.j));
    joinGroup(i);
    recordEvent(CollisionEvent::Kind::kBallWall, ball.id, wall.id, p + ball.radius * n, n, 0.0, closing, true, event);
    solveGroup(i, event.x);
    return;
  }
  const double inv_mass = inverseMass(i);
  const double impulse = collisionImpulse(closing, inv_mass, dir, 0.0, dir, wall.restitution);
  const Vec3 before = v;
  v -= (impulse * inv_mass) * dir;
  spin_->wallImpact(*this, i, event.x, n, floor_normal, impulse, before, v);
  takeVelocity(i, event.x, p, floor_normal, before, v);
  recordEvent(CollisionEvent::Kind::kBallWall, ball.id, wall.id, p + ball.radius * n, n, impulse, closing, false, event);
  countEvent(i);
  goOnAfter(event);
}

void StepContext::wakeOnImpact(std::size_t i, std::size_t j, double closing, double rest_speed)
{
  // An impact on a sleeping ball (not one that would rest on it) wakes its group; the
  // sleeping ball's velocity is zero.
  if (motions_[i].asleep() != motions_[j].asleep() && closing > rest_speed)
    wakeGroup(motions_[j].asleep() ? j : i);
}

void StepContext::resolveBallBall(const Event& event)
{
  const std::size_t i = event.i, j = event.j;
  const Ball& a = balls_[i];
  const Ball& b = balls_[j];
  const Vec3 pa = positionAt(i, event.x);
  const Vec3 pb = positionAt(j, event.x);
  const Vec3 na = floorNormalAt(i, pa);
  const Vec3 nb = floorNormalAt(j, pb);
  Vec3 va = onFloorVelocity(i, event.x, pa, na);
  Vec3 vb = onFloorVelocity(j, event.x, pb, nb);

  Vec3 n = pb - pa;
  const double dist = n.norm();
  n = dist > 0 ? Vec3(n / dist) : Vec3(Vec3::UnitX());
  const double rest_speed = pairRestingSpeed(na, pa, a.radius, nb, pb, b.radius);
  wakeOnImpact(i, j, n.dot(va - vb), rest_speed);
  // Each ball on the floor is pushed along the normal's part tangent to the floor under
  // it; one in flight along the normal itself, and it rests on nothing.
  Vec3 ta = a.flying() ? n : ground_.along(n, na);
  Vec3 tb = b.flying() ? n : ground_.along(n, nb);
  double closing = va.dot(ta) - vb.dot(tb);
  const bool resting = !a.flying() && !b.flying() && closing <= rest_speed;
  if (resting)
  {
    // a resting contact: the two balls' groups become one, with it as a constraint
    link(std::min(i, j), static_cast<std::uint32_t>(std::max(i, j)));
    mergeGroups(i, j);
    recordEvent(CollisionEvent::Kind::kBallBall, a.id, b.id, pa + a.radius * n, n, 0.0, closing, true, event);
    solveGroup(i, event.x);
    return;
  }
  const double inv_a = inverseMass(i);
  const double inv_b = inverseMass(j);
  // (only a ball in flight lifts one on the floor)
  const std::size_t lifted = flights_ > 0 ? pairLift(i, j, n, na, nb, va, vb, ta, tb, closing) : kNoBall;
  const double impulse = collisionImpulse(closing, inv_a, ta, inv_b, tb, scene_.restitution);
  const Vec3 va_before = va, vb_before = vb;
  va -= (impulse * inv_a) * ta;
  vb += (impulse * inv_b) * tb;

  const PairContact pair{i, j, n, na, nb, ta, tb, ta, tb, inv_a, inv_b};
  spin_->pairImpact(*this, pair, event.x, impulse, va_before, vb_before, va, vb);
  // (a ball lifted flies from where it is on the floor)
  if (lifted != kNoBall)
    liftOff(*this, lifted, event.x);
  takeVelocity(i, event.x, lifted == i ? onFloor(i, pa) : pa, na, va_before, va);
  takeVelocity(j, event.x, lifted == j ? onFloor(j, pb) : pb, nb, vb_before, vb);
  recordEvent(CollisionEvent::Kind::kBallBall, a.id, b.id, pa + a.radius * n, n, impulse, closing, false, event);
  countEvent(i);
  countEvent(j);
  goOnAfter(event);
}

void StepContext::goOnAfter(const Event& event)
{
  const std::size_t i = event.i, j = event.j;
  const bool group_i = grouped(i);
  if (group_i)
    solveGroup(i, event.x);
  else
    detect(i);
  if (ofOneBall(event.kind))
    return;
  const bool group_j = grouped(j);
  if (group_j && !(group_i && groupOf(i) == groupOf(j)))
    solveGroup(j, event.x);
  else if (!group_j)
    detect(j, group_i ? kNoBall : i);  // (the pair itself was just found from i's side)
}

std::size_t StepContext::pairLift(std::size_t i, std::size_t j, const Vec3& n, const Vec3& na, const Vec3& nb,
                                  const Vec3& va, const Vec3& vb, Vec3& ta, Vec3& tb, double& closing) const
{
  // The floor only pushes: a ball on it that a ball in flight pushes away from it (struck
  // below its centre) is not held, takes the whole normal and flies. (Two balls on the
  // floor push each other along it, whatever their radii: the floor's plane model.)
  const bool a_flies = balls_[i].flying();
  if (a_flies == balls_[j].flying())
    return kNoBall;
  const double inv_a = inverseMass(i), inv_b = inverseMass(j);
  const double impulse = collisionImpulse(closing, inv_a, ta, inv_b, tb, scene_.restitution);
  // (the one on the floor: j where i flies, pushed by +impulse along n; else i, by -impulse)
  const bool lifts = a_flies ? liftedBy(j, (impulse * inv_b) * n, nb) : liftedBy(i, (-impulse * inv_a) * n, na);
  if (!lifts)
    return kNoBall;
  (a_flies ? tb : ta) = n;
  closing = va.dot(ta) - vb.dot(tb);
  return a_flies ? j : i;
}

bool StepContext::liftedBy(std::size_t i, const Vec3& dv, const Vec3& floor_normal) const
{
  // (as an edit's push: away from the floor for min_flight_time or more; a ball in a
  // group moves with it)
  const double away = dv.dot(floor_normal);
  return away > 0 && !(2 * away < settings_.min_flight_time * -gravity_.dot(floor_normal)) && !grouped(i);
}

void StepContext::takeVelocity(std::size_t i, double x, const Vec3& p, const Vec3& normal, const Vec3& before, const Vec3& v)
{
  if (!energy_ref_.empty())
    energy_ref_[i] += impulseEnergy(i, x, before, v);
  // (a ball on its group's motion takes the impulse into its free velocity, and its
  // group is solved again after the event)
  if (motions_[i].followsGroup())
    takeImpulse(i, x, p, v - onFloorVelocity(i, x, p, normal));
  else
    startMotion(i, x, p, v, true);
}

void StepContext::renewMotion(std::size_t i)
{
  // What was predicted for this ball before is stale now. Where the 16-bit epoch wraps,
  // the events queued under the one it is back at would pass for current: none is.
  if (++motions_[i].epoch == 0)
    queue_.forget(static_cast<std::uint32_t>(i));
  grid_.update(static_cast<std::uint32_t>(i), currentBox(i));
}

void StepContext::countEvent(std::size_t i)
{
  Motion& m = motions_[i];
  // What was predicted for this ball before is stale now. Where the 16-bit epoch wraps,
  // the events queued under the one it is back at would pass for current: none is.
  if (++m.epoch == 0)
    queue_.forget(static_cast<std::uint32_t>(i));
  // (counted up to one past the cap only: a frozen ball can still be hit by many others)
  if (!m.frozen() && ++m.events > settings_.max_events_per_ball_step)
  {
    m.type = MotionType::kCapped;
    startVelocity(i) = Vec3::Zero();
    motions_[i].b = Vec3::Zero();
    spin_->cap(*this, i);  // (its spin too)
    ++stats_.frozen_balls;
  }
  // its new motion may reach beyond where the grid has it
  grid_.update(static_cast<std::uint32_t>(i), currentBox(i));
}

void StepContext::recordEvent(CollisionEvent::Kind kind, int ball, int other, const Vec3& point, const Vec3& normal,
                        double impulse, double closing, bool resting, const Event& event)
{
  ++stats_.events;
  if (resting)
    ++stats_.resting_events;
  if (!record_events_)
    return;
  CollisionEvent out;
  out.kind = kind;
  out.time = (static_cast<double>(stats_.steps) + event.x) * dt_;
  out.ball = ball;
  out.other = other;
  out.feature = event.feature;
  out.point = point;
  out.normal = normal;
  out.impulse = impulse;
  out.approach_speed = closing;
  out.resting = resting;
  events_.push_back(out);
}

}  // namespace ball_collision_sim::core
