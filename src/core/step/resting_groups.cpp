// Resting contacts as constraints: balls that touch and close no faster than they rest
// (at the step's start, or where they meet within it) are joined into groups; a group's
// motions over the rest of the step are its members' free motions with no contact
// closing by more than its gap, solved together (projected Gauss-Seidel, Moreau and
// Jean's time-stepping, with speculative contacts as in Box2D: a contact may close up to
// its gap). Detection skips the contacts of a group; an impact on a member, or a new
// resting contact, solves its group again from then on. This file: the groups
// themselves (union-find, the contacts' links, their keys) and the search for resting
// contacts at the step's start; group_solve.cpp solves a group, group_end.cpp ends the
// step's groups.
// Reads the start positions and velocities, walls_, the grid; writes the groups
// (group_parent_, group_next_, first_link_, links_) and what impacts give their members.
#include "spin_model.hpp"
#include "contact_group.hpp"
#include "stages.hpp"
#include "floor_motion.hpp"
#include "spin_phase.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

std::uint32_t StepContext::groupOf(std::size_t i)
{
  if (group_parent_.empty())
    return kNone32;
  std::uint32_t k = group_parent_[i];
  if (k == kNone32)
    return kNone32;
  while (group_parent_[k] != k)
    k = group_parent_[k] = group_parent_[group_parent_[k]];
  return k;
}

void StepContext::startGroups()
{
  if (!group_parent_.empty())
    return;
  const std::size_t n = balls_.size();
  group_parent_.assign(n, kNone32);
  group_next_.resize(n);
  first_link_.assign(n, kNone32);
  group_velocity_.resize(n);
}

void StepContext::joinGroup(std::size_t i)
{
  startGroups();
  if (group_parent_[i] != kNone32)
    return;
  group_parent_[i] = group_next_[i] = static_cast<std::uint32_t>(i);
}

void StepContext::mergeGroups(std::size_t i, std::size_t j)
{
  joinGroup(i);
  joinGroup(j);
  const std::uint32_t a = groupOf(i), b = groupOf(j);
  if (a == b)
    return;
  group_parent_[std::max(a, b)] = std::min(a, b);
  std::swap(group_next_[a], group_next_[b]);  // (the two rings become one)
}

bool StepContext::linked(std::size_t i, std::uint32_t other) const
{
  if (first_link_.empty())
    return false;
  for (std::uint32_t r = first_link_[i]; r != kNone32;)
  {
    const ContactLink& link = links_[r];
    if (link.a == i ? link.b == other : link.a == other)
      return true;
    r = link.a == i ? link.next_a : link.next_b;
  }
  return false;
}

void StepContext::link(std::size_t a, std::uint32_t other)
{
  startGroups();
  const auto r = static_cast<std::uint32_t>(links_.size());
  const auto warm = warm_.find(linkKey(a, other));
  const double rate = warm == warm_.end() ? 0.0 : warm->second;
  ContactLink l{static_cast<std::uint32_t>(a), other, first_link_[a], kNone32, rate};
  first_link_[a] = r;
  if (!(other & kWallRow))
  {
    l.next_b = first_link_[other];
    first_link_[other] = r;
  }
  links_.push_back(l);
}

std::uint64_t StepContext::linkKey(std::size_t a, std::uint32_t other) const
{
  const auto id_a = static_cast<std::uint64_t>(balls_[a].id);
  if (other & kWallRow)
    return (id_a << 32) | other;
  const auto id_b = static_cast<std::uint64_t>(balls_[other].id);
  return (std::min(id_a, id_b) << 32) | std::max(id_a, id_b);
}

Vec3 StepContext::groupVelocityAt(std::size_t i, double x) const
{
  // (the span's impulses, gravity's and the contacts', spread evenly over it)
  const Motion& m = motions_[i];
  const Vec3 solved = m.b / dt_;
  const double span = chordEnd(i) - m.x0;
  if (!(span > 0))
    return solved;
  return group_velocity_[i] + ((x - m.x0) / span) * (solved - group_velocity_[i]);
}

double StepContext::impulseEnergy(std::size_t i, double x, const Vec3& before, const Vec3& after) const
{
  // (a member of a group has at x the velocity the group's spread impulses give it, not
  // its chord's: the impulse's change is added to that)
  const Vec3 base = motions_[i].followsGroup() ? groupVelocityAt(i, x) : before;
  return 0.5 * balls_[i].mass * ((base + (after - before)).squaredNorm() - base.squaredNorm());
}

void StepContext::takeImpulse(std::size_t i, double x, const Vec3& position, const Vec3& dv)
{
  const Vec3 v = groupVelocityAt(i, x) + dv;
  beginMotion(i, x, position, v);
  motions_[i].b = dt_ * v;
  group_velocity_[i] = v;
  motions_[i].become(MotionType::kGrouped);
}

void step::formRestingGroups(StepContext& c)
{
  const std::size_t n = c.balls_.size();
  // (the groups' per-ball data is made when the step links its first contact: a step
  // without resting contacts reads none, and a world that never had one keeps none)
  c.group_parent_.clear();
  c.group_next_.clear();
  c.first_link_.clear();
  c.group_velocity_.clear();
  // (the energy each ball may end the step with: its own at the step's start, which its
  // record holds only until its motion starts anew, and what impacts give it)
  c.energy_ref_.resize(n);
  c.forEachBall([&](std::size_t begin, std::size_t end) {  // (each ball's its own: on the step's threads)
    for (std::size_t i = begin; i < end; ++i)
      c.energy_ref_[i] = c.motionEnergyOf(i, c.balls_[i].position, c.balls_[i].velocity);
  });
  c.spin_->addSpinEnergies(c, c.energy_ref_);
  c.links_.clear();
  c.link_order_.clear();
  // Where gravity does not pull along the floor (a plane square to it), nothing brings
  // balls together: a resting contact there is met within the step, as an event, and
  // linked then; no search at the step's start.
  if (!StepState::FloorMotion::gathers(c))
    return;
  // (the farthest any contact can be linked from, a first filter: gravity itself for its
  // part along the floor, and a margin for the round-off of speeds)
  const double g = c.gravity_.norm();
  const auto bound = [&](double e) {
    const double least = c.settings_.reach_least_restitution;
    const double bounces = e < 1 ? c.settings_.resting_steps * c.dt_ * g * (1 - e) / (2 * std::max(e, least)) : 0.0;
    return c.dt_ * (bounces + c.settings_.reach_speed_margin + c.dt_ * g);
  };
  double reach = bound(c.scene_.restitution);
  for (const Wall& wall : c.walls_)
    reach = std::max(reach, bound(wall.restitution));
  c.linkRestingWalls(reach);
  c.linkRestingPairs(reach);
  for (std::size_t i = 0; i < n && !c.group_parent_.empty(); ++i)
    if (c.group_parent_[i] == i)
      c.solveGroup(i, 0.0);
}

double StepContext::speculativeReach(double rest_speed, double pull) const
{
  // Speculative contacts: a pair or wall that closes no faster than it rests, near enough
  // to close its gap within the step (at its resting speed, and what gravity along the
  // floor adds), is a constraint from the step's start, which allows it to close by its
  // gap; else it would meet as an event early in each step, and be solved again there.
  return dt_ * (rest_speed + dt_ * pull);
}

void StepContext::linkRestingWalls(double reach)
{
  const double touch = settings_.touch_slack;
  grid_.forEachNearObstacle([&](std::uint32_t i) {
    if (motions_[i].frozen() || balls_[i].flying())
      return;
    const Ball& ball = balls_[i];
    for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      if (!grid_.reaches(i, w))
        continue;
      const Vec3 d = walls_[w].closestPoint(ball.position) - ball.position;
      const double dist = d.norm();
      if (!(dist > 0) || !(dist - ball.radius <= touch + reach))
        continue;
      const Vec3 fn = floorNormalAt(i, ball.position);
      const Vec3 dir = wallPush(d / dist, fn);
      const double rest_speed = restingSpeed(fn, walls_[w].restitution, ball.position, ball.radius);
      const double closing = ball.velocity.dot(dir);
      const double pull = ground_.gravityAlong(fn);
      // (one that moves away faster than gravity along the floor can turn it back within
      // the step does not meet it)
      if (std::abs(closing) <= rest_speed && closing + dt_ * pull > 0 &&
          dist - ball.radius <= touch + speculativeReach(rest_speed, pull))
      {
        link(i, kWallRow | static_cast<std::uint32_t>(w));
        joinGroup(i);
      }
    }
  });
}

void StepContext::linkRestingPairs(double reach)
{
  const double touch = settings_.touch_slack;
  grid_.forEachPair([&](std::uint32_t i, std::uint32_t j) {
    if ((motions_[i].frozen() && motions_[j].frozen()) || balls_[i].flying() || balls_[j].flying())
      return;
    const Ball& a = balls_[i];
    const Ball& b = balls_[j];
    const Vec3 d = b.position - a.position;
    const double dist = d.norm();
    const double gap = dist - (a.radius + b.radius);  // (the same bits whichever is a)
    if (!(dist > 0) || !(gap <= touch + reach) || wallBetween(a, b))
      return;
    const Vec3 u = d / dist;
    const Vec3 na = floorNormalAt(i, a.position), nb = floorNormalAt(j, b.position);
    const double closing = a.velocity.dot(ground_.along(u, na)) - b.velocity.dot(ground_.along(u, nb));
    const double rest_speed = pairRestingSpeed(na, a.position, a.radius, nb, b.position, b.radius);
    const double pull_a = ground_.gravityAlong(na), pull_b = ground_.gravityAlong(nb);
    if (std::abs(closing) <= rest_speed && closing + dt_ * (pull_a + pull_b) > 0 &&
        gap <= touch + std::max(speculativeReach(rest_speed, pull_a), speculativeReach(rest_speed, pull_b)))
    {
      link(std::min(i, j), std::max(i, j));
      mergeGroups(i, j);
    }
  });
}
}  // namespace ball_collision_sim::core
