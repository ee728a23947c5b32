// Resting contacts: the directions a ball may not move along for the rest of the step,
// holding balls still, and keeping a motion on the floor and within its energy.
// Reads and writes motions_, states_, blocked_sets_.
#include "step_types.hpp"

#include "../bracketed_root.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

Vec3 World::allowed(std::size_t i, const Vec3& w) const
{
  const std::int32_t blocked = states_[i].blocked;
  if (blocked < 0)
    return w;
  // A wall's own normal is blocked beside its direction along the floor (for chords off
  // a curved floor); on a plane it lets a motion out of the plane through (a ball in a
  // corner of two walls would move straight up or down), which the plane takes.
  return ground_.inPlane(blocked_sets_[static_cast<std::size_t>(blocked)].allowed(w, settings_));
}

Vec3 World::redirected(std::size_t i, const Vec3& v) const
{
  // What a ball leans on takes the part of its velocity into it (the bounces that a
  // resting contact sums); an elastic contact (e = 1, where only speeds at round-off
  // rest) only turns it: where gravity pulls along the floor a ball's speed is its
  // energy's (onFloorVelocity), and the turn keeps it.
  const std::int32_t blocked = states_[i].blocked;
  const Vec3 free = allowed(i, v);
  if (blocked < 0 || !blocked_sets_[static_cast<std::size_t>(blocked)].elastic)
    return free;
  return ground_.turned(v, free);
}

void World::addBlocked(std::size_t i, const Vec3& direction, double restitution)
{
  MotionState& m = states_[i];
  if (m.blocked < 0)
  {
    m.blocked = static_cast<std::int32_t>(blocked_sets_.size());
    blocked_sets_.emplace_back();
  }
  BlockedSet& set = blocked_sets_[static_cast<std::size_t>(m.blocked)];
  set.add(direction, settings_);
  set.elastic = set.elastic && !(restitution < 1);
}

void World::wakeGroup(std::size_t first)
{
  std::vector<std::size_t> todo{first};
  while (!todo.empty())
  {
    const std::size_t k = todo.back();
    todo.pop_back();
    if (!states_[k].asleep)
      continue;
    states_[k].frozen = states_[k].asleep = false;
    Ball& ball = balls_[k];
    ball.asleep = false;
    ball.quiet_steps = 0;
    ++stats_.woken_balls;
    grid_.query(static_cast<std::uint32_t>(k), [&](std::uint32_t other) {
      const Ball& b = balls_[other];
      if (states_[other].asleep && (b.position - ball.position).norm() <= b.radius + ball.radius + settings_.touch_slack &&
          !wallBetween(ball, b))
        todo.push_back(other);
    });
  }
}

bool World::wallBetween(const Ball& a, const Ball& b) const
{
  // Balls that touch one another meet where their centres' line crosses; balls on the
  // two sides of a wall meet the wall there instead.
  const Vec3 middle = 0.5 * (a.position + b.position);
  const double near = 0.5 * std::min(a.radius, b.radius);
  return std::any_of(walls_.begin(), walls_.end(), [&](const Wall& wall) { return wall.distance(middle) < near; });
}

void World::wakeAll()
{
  for (Ball& ball : balls_)
  {
    ball.asleep = false;
    ball.quiet_steps = 0;
  }
  motions_ready_ = false;  // (a prediction made while they slept)
}

void World::sleepStillGroups()
{
  // Groups: balls joined by the step's resting contacts, by union-find over the visiting
  // order (its smallest index stands for a group; the same groups whatever the order).
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
  for (const RestingContact& c : resting_)
  {
    leans[c.ball] = leans[c.other] = 1;
    if (states_[c.ball].asleep || states_[c.other].asleep)
      continue;  // a sleeping ball holds the other like a wall does
    const std::size_t a = root(c.ball), b = root(c.other);
    parent[std::max(a, b)] = static_cast<std::uint32_t>(std::min(a, b));
  }
  // a group sleeps when every ball in it has been still long enough
  std::vector<char> restless(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    Ball& ball = balls_[k];
    if (ball.asleep)
      continue;
    const bool still = (leans[k] || states_[k].blocked >= 0) && ball.velocity.norm() <= settings_.sleep_speed;
    ball.quiet_steps = still ? static_cast<std::uint16_t>(std::min<int>(ball.quiet_steps + 1, 0xffff)) : 0;
    if (ball.quiet_steps < sleep_steps_)
      restless[root(k)] = 1;
  }
  std::uint64_t asleep = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    Ball& ball = balls_[k];
    if (!ball.asleep && ball.quiet_steps >= sleep_steps_ && !restless[root(k)])
    {
      ball.asleep = true;
      ball.velocity = Vec3::Zero();
    }
    asleep += ball.asleep ? 1 : 0;
  }
  stats_.sleeping_balls = asleep;
}

void World::hold(std::size_t i)
{
  if (!states_[i].held)
    ++stats_.held_balls;
  states_[i].held = true;
}

void World::endOnFloor(std::size_t i)
{
  // The chord must end on the floor, where the step's end puts the ball: a ball moved
  // there after its motion was checked could be pressed into what it touches. Taking
  // out the blocked directions moves the end off a curved floor; back onto it and out of
  // them again, in turn, until both hold.
  Motion& m = motions_[i];
  const double rest = chordEnd(i) - m.x0;
  if (!ground_.bends() || states_[i].frozen || !(rest > 0))
    return;
  const double roundoff = roundoffAt(m.p0, m.radius, settings_);
  for (int pass = 0; pass < settings_.correction_passes; ++pass)
  {
    const Vec3 on = (onFloor(i, m.p0 + rest * m.b) - m.p0) / rest;
    const Vec3 free = allowed(i, on);
    const double off = (free - on).norm();
    const bool done = off <= settings_.correction_tolerance * on.norm() || rest * off <= roundoff;
    // (a pass that leaves the motion as it was would be repeated as it is: fully blocked
    // off the floor, say)
    const bool same = free == m.b;
    m.b = done ? on : free;
    if (done || same)
      return;
  }
}

double World::EnergyCheck::speedSquaredWith(const Vec3& b) const
{
  const Motion& m = world->motions_[i];
  return world->speedSquaredAt(i, world->chordEnd(i), world->onFloor(i, m.p0 + rest * b));
}

double World::EnergyCheck::speedSquared(double s) const
{
  return speedSquaredWith(s * world->motions_[i].b);
}

double World::EnergyCheck::chordSpeedSquared(const Vec3& b) const
{
  if (world->friction_ && world->spin_motions_[i].forced() && world->ground_.bends())
    return world->speedSquaredAt(i, world->chordEnd(i), world->motions_[i].p0 + rest * b);
  return world->startVelocity(i).squaredNorm() + 2 * rest * world->pullOf(i).dot(b);
}

void World::keepEnergy(std::size_t i)
{
  Motion& m = motions_[i];
  const double rest = chordEnd(i) - m.x0;
  if (ground_.straight() || states_[i].frozen || !(rest > 0))
    return;
  const EnergyCheck energy{this, i, rest};
  // (on a curved floor endOnFloor has put the chord's end on it, or as near as its blocked
  // directions let it: the chord's own end is what counts)
  const double full = ground_.bends() ? energy.chordSpeedSquared(m.b) : energy.speedSquared(1.0);
  if (full >= 0)
    return;
  // The chord ends higher than the ball's energy reaches (a turning point on a curved
  // floor, or a ball in a pile whose constraints turned its motion uphill): it stops
  // where the energy runs out instead, so that no energy is made.
  const double start = energy.speedSquared(0.0);
  double lo = 0.0;
  if (start > 0)
    lo = ground_.bends() ? energyRunsOut(energy, start, full) : start / (start - full);  // (linear in s)
  // (round-off may leave the end a hair too high; the speed is clamped to zero then)
  m.b *= lo;
  if (!ground_.bends())
    return;
  if (lo > 0)
  {
    const Vec3 b = allowed(i, (onFloor(i, m.p0 + rest * m.b) - m.p0) / rest);
    m.b = energy.chordSpeedSquared(b) >= 0 ? b : Vec3::Zero();
    if (m.b == Vec3::Zero())
      hold(i);
    return;
  }
  slideDownhill(energy, start);
}

double World::energyRunsOut(const EnergyCheck& energy, double start, double full) const
{
  // the root of the speed on [0, 1], where it is still >= 0
  return bracketedRoot([&](double s) { return energy.speedSquared(s); }, [](double v) { return v >= 0 ? 1 : -1; },
                       0.0, 1.0, start, full, settings_.energy_root_iterations, settings_.energy_root_width);
}

void World::slideDownhill(const EnergyCheck& energy, double start)
{
  const std::size_t i = energy.i;
  const double rest = energy.rest;
  Motion& m = motions_[i];
  // A motion that starts at an impact inside the step starts on the chord, below or
  // above the floor; where the floor above it is higher than the energy reaches, the
  // ball slides downhill from there instead, as far as it takes to be low enough.
  // Where it finds no way, it is held: it stays put through the step's resting contacts.
  // (keepEnergy only ever holds a ball: an impact, not a new motion, lets it go)
  const Vec3 foot = onFloor(i, m.p0);
  const Vec3 downhill = tangentPart(gravity_, floorNormalAt(i, foot));
  const double slope = downhill.norm();
  if (!(slope > 0))
    return hold(i);
  // (a short way only: the chord's sag is small next to the ball; else it stays put)
  // The reaches tried are first * 2^k below half the radius. Where the energy left grows
  // with the reach (the lower the end, the more), halving the range of k after the
  // longest has shown that one does finds the shortest that does; elsewhere it finds one
  // that does, or, where the longest does not, holds the ball (which makes no energy).
  const double first = std::max(-start / slope, settings_.slide_first_reach * m.radius);
  int count = 0;
  while (count < settings_.slide_doublings && std::ldexp(first, count) < settings_.slide_longest_reach * m.radius)
    ++count;
  const auto motionTo = [&](int k) {
    return allowed(i, (onFloor(i, foot + (std::ldexp(first, k) / slope) * downhill) - m.p0) / rest);
  };
  const auto keeps = [&](const Vec3& b) { return energy.speedSquaredWith(b) >= 0 && energy.chordSpeedSquared(b) >= 0; };
  if (count == 0)
    return hold(i);
  Vec3 found = motionTo(count - 1);
  if (!keeps(found))
    return hold(i);
  int fails = -1, works = count - 1;  // the largest k known to fail, the smallest known to work
  while (works - fails > 1)
  {
    const int k = fails + (works - fails) / 2;
    const Vec3 b = motionTo(k);
    if (keeps(b))
    {
      works = k;
      found = b;
    }
    else
      fails = k;
  }
  m.b = found;
}
}  // namespace ball_collision_sim::core
