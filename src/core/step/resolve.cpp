// Stage 4, resolve: events in time order, earliest first; an impact bounces (or, slow
// enough, becomes a resting contact), and the balls involved get new motions and are
// detected again. Reads and writes motions_, the queue, the start positions and velocities;
// writes events_ and stats_.
#include "floor_motion.hpp"

#include "ball_collision_sim/core/response.hpp"
#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

void World::resolveEventsInTimeOrder()
{
  while (!queue_.empty())
  {
    {
      // the first event's balls' data are fetched while the queue is put in order
      const auto fetch = [&](std::uint32_t k) {
        __builtin_prefetch(&motions_[k]);
        __builtin_prefetch(&balls_[k]);
      };
      const auto& next = queue_.top();
      fetch(next.i);
      if (!next.wall)
        fetch(next.j);
    }
    const Event event = queue_.pop();
    if (motions_[event.i].epoch != event.epoch_i || (!event.wall && motions_[event.j].epoch != event.epoch_j))
    {
      ++stats_.stale_events;  // a ball involved has had an event since this was found
      continue;
    }
    if (event.transition)
      resolveMotionEnd(event);
    else if (event.wall)
      resolveBallWall(event);
    else
      resolveBallBall(event);
  }
}

void World::resolveBallWall(const Event& event)
{
  const std::size_t i = event.i;
  const Wall& wall = walls_[event.j];
  const Ball& ball = balls_[i];
  const Vec3 p = positionAt(i, event.x);
  const Vec3 floor_normal = floorNormalAt(i, p);
  Vec3 v = onFloorVelocity(i, event.x, p, floor_normal);
  if (friction_)
    spin_motions_[i].w0 = spinAtEvent(i, event.x, floor_normal, v);

  const Vec3 n = -event.normal;  // from the ball toward the wall
  Vec3 dir = ground_.along(n, floor_normal);
  if (dir.squaredNorm() < settings_.wall_along_floor_squared)
    dir = n;  // a wall parallel to the floor: answer in space
  dir.normalize();
  const double closing = v.dot(dir);
  const bool resting = closing <= restingSpeed(floor_normal, wall.restitution, p, ball.radius);
  const double inv_mass = inverseMass(i);
  const double impulse =
      collisionImpulse(std::max(closing, 0.0), inv_mass, dir, 0.0, dir, resting ? 0.0 : wall.restitution);
  v -= (impulse * inv_mass) * dir;
  if (friction_)
    ballWallFriction(i, n, floor_normal, resting ? 0.0 : impulse, v);

  if (resting)
  {
    // leaning on the wall until the step ends; where the floor is not square to the wall,
    // also no motion into the wall itself (else it comes back at once, again and again)
    addBlocked(i, dir, wallSource(event.j, false), wall.restitution);
    if (dir.dot(n) < 1 - settings_.same_direction)
      addBlocked(i, n, wallSource(event.j, true), wall.restitution);
  }
  startMotion(i, event.x, p, v, !resting);
  recordEvent(CollisionEvent::Kind::kBallWall, ball.id, wall.id, p + ball.radius * n, n, impulse, closing, resting,
              event);
  countEvent(i);
  detect(i);
}

void World::wakeOnImpact(std::size_t i, std::size_t j, double closing, double rest_speed)
{
  // An impact on a sleeping ball (not one that would rest on it) wakes its group; the
  // sleeping ball's velocity is zero.
  if (motions_[i].asleep != motions_[j].asleep && closing > rest_speed)
    wakeGroup(motions_[j].asleep ? j : i);
}

void World::resolveBallBall(const Event& event)
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
  if (motions_[i].frozen)
    va = Vec3::Zero();
  if (motions_[j].frozen)
    vb = Vec3::Zero();
  if (friction_)
  {
    // (the spins there, before the impact changes the velocities; they become the new
    // motions' w0)
    const Vec3 wa = spinAtEvent(i, event.x, na, va), wb = spinAtEvent(j, event.x, nb, vb);
    spin_motions_[i].w0 = wa;
    spin_motions_[j].w0 = wb;
  }

  Vec3 n = pb - pa;
  const double dist = n.norm();
  n = dist > 0 ? Vec3(n / dist) : Vec3(Vec3::UnitX());
  const double rest_speed = pairRestingSpeed(na, pa, a.radius, nb, pb, b.radius);
  wakeOnImpact(i, j, n.dot(va - vb), rest_speed);
  // Each ball is pushed along the normal's part tangent to the floor under it, less any
  // part toward what it leans on (that part of the impulse goes into the wall).
  const Vec3 along_a = ground_.along(n, na);
  const Vec3 along_b = ground_.along(n, nb);
  const Vec3 ta = -allowed(i, -along_a);
  const Vec3 tb = allowed(j, along_b);
  const double inv_a = inverseMass(i);
  const double inv_b = inverseMass(j);
  const double closing = va.dot(ta) - vb.dot(tb);
  const bool resting = closing <= rest_speed;
  const double impulse =
      collisionImpulse(std::max(closing, 0.0), inv_a, ta, inv_b, tb, resting ? 0.0 : scene_.restitution);
  va -= (impulse * inv_a) * ta;
  vb += (impulse * inv_b) * tb;

  const PairContact pair{i, j, n, na, nb, along_a, along_b, ta, tb, inv_a, inv_b};
  if (friction_)
    ballBallFriction(pair, resting ? 0.0 : impulse, va, vb);
  const bool both_still = resting && blockAtRest(pair, va, vb);
  startMotion(i, event.x, pa, va, !resting);
  startMotion(j, event.x, pb, vb, !resting);
  if (resting)
    settleRestingPair(pair, event.x, pa, pb, both_still);
  recordEvent(CollisionEvent::Kind::kBallBall, a.id, b.id, pa + a.radius * n, n, impulse, closing, resting, event);
  countEvent(i);
  countEvent(j);
  detect(i);
  detect(j);
}

void World::countEvent(std::size_t i)
{
  Motion& m = motions_[i];
  // What was predicted for this ball before is stale now. Where the 16-bit epoch wraps,
  // the events queued under the one it is back at would pass for current: none is.
  if (++m.epoch == 0)
    queue_.forget(static_cast<std::uint32_t>(i));
  // (counted up to one past the cap only: a frozen ball can still be hit by many others)
  if (!m.frozen && ++m.events > settings_.max_events_per_ball_step)
  {
    m.frozen = true;
    startVelocity(i) = Vec3::Zero();
    motions_[i].b = Vec3::Zero();
    m.accelerates = false;
    if (friction_)
    {
      keepSpin(i);
      spin_motions_[i].w0 = Vec3::Zero();  // (its spin too: no motion at all, and no energy made)
    }
    ++stats_.frozen_balls;
  }
  // its new motion may reach beyond where the grid has it
  grid_.update(static_cast<std::uint32_t>(i), currentBox(i));
}

void World::recordEvent(CollisionEvent::Kind kind, int ball, int other, const Vec3& point, const Vec3& normal,
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

void World::recordEvents(bool record)
{
  record_events_ = record;
  if (!record)
    std::vector<CollisionEvent>().swap(events_);
}
bool World::blockAtRest(const PairContact& c, const Vec3& va, const Vec3& vb)
{
  const std::size_t i = c.i, j = c.j;
  const Vec3 &along_a = c.along_a, &along_b = c.along_b;
  // A ball that cannot move (held, or frozen: asleep or stopped by the event cap) blocks
  // the other's approach for the rest of the step, as a wall does, and two balls that are
  // both all but still (a pile at rest) block each other, so that piles settle in one
  // event per contact instead of passing vanishing impulses back and forth. (A ball that
  // gives way, however little, is left to: the corrections of the pair's motions weigh
  // each ball by how far it can go, FloorMotion::separate().)
  const double still = std::max(stillSpeed(c.na), stillSpeed(c.nb));
  const bool both_still = va.norm() <= still && vb.norm() <= still;
  const bool a_fixed = both_still || motions_[i].held || motions_[i].frozen;
  const bool b_fixed = both_still || motions_[j].held || motions_[j].frozen;
  if (a_fixed && along_b.squaredNorm() > 0)
    addBlocked(j, -along_b.normalized(), ballSource(i), scene_.restitution);
  if (b_fixed && along_a.squaredNorm() > 0)
    addBlocked(i, along_a.normalized(), ballSource(j), scene_.restitution);
  return both_still;
}

void World::settleRestingPair(const PairContact& c, double x, const Vec3& pa, const Vec3& pb, bool both_still)
{
  const std::size_t i = c.i, j = c.j;
  const Vec3 &n = c.n, &ta = c.ta, &tb = c.tb;
  const double inv_a = c.inv_a, inv_b = c.inv_b;
  Motion& ma = motions_[i];
  Motion& mb = motions_[j];
  toChord(i);
  toChord(j);
  // No approach left in the motions either (gravity along the floor would press them
  // together again at once); a held ball does not give way.
  const double rest = 1 - x;
  floor_motion_->separate(*this, c, rest, ma.held ? 0.0 : inv_a, mb.held ? 0.0 : inv_b, pa, pb);
  // Two balls all but still whose motions still close in (a pile in a corner of a
  // curved floor, where the floor, the walls and each other leave no room to settle
  // into), or that are in a jam: they stay where they are for the rest of the step,
  // whatever resting contact comes next (else each such contact would start them
  // again, and one the next, without end). So do two whose motions still close in by
  // more than detection lets pass, because keepEnergy turned them back into each other
  // (shortened or slid downhill) or because neither could give way (on a curved floor,
  // FloorMotion::separate()): it would find this contact again at once, and again.
  keepEnergy(i);
  keepEnergy(j);
  const std::uint32_t jam = settings_.jam_events_per_ball_step;
  const bool jammed = ma.events >= jam || mb.events >= jam;
  const double closing_in = rest * (ma.b.dot(n) - mb.b.dot(n));
  const bool again = closing_in > settings_.closing_slop * (balls_[i].radius + balls_[j].radius);
  if (jammed || (both_still && closing_in > 0) || again)
  {
    ma.b = mb.b = Vec3::Zero();
    hold(i);
    hold(j);
  }
  resting_.push_back({i, j, ta, tb, c.along_a, c.along_b});
}
}  // namespace ball_collision_sim::core
