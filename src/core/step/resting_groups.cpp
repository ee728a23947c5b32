// Resting contacts as constraints: balls that touch and close no faster than they rest
// (at the step's start, or where they meet within it) are joined into groups; a group's
// motions over the rest of the step are its members' free motions with no contact
// closing by more than its gap, solved together (projected Gauss-Seidel, Moreau and
// Jean's time-stepping, with speculative contacts as in Box2D: a contact may close up to
// its gap). Detection skips the contacts of a group; an impact on a member, or a new
// resting contact, solves its group again from then on.
// Reads the start positions and velocities, walls_, the grid; writes motions_, the groups
// (group_parent_, group_next_, first_link_, links_), the contact solver's work space.
#include "contact_group.hpp"
#include "floor_motion.hpp"
#include "spin_phase.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;


std::uint32_t World::groupOf(std::size_t i)
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

void World::startGroups()
{
  if (!group_parent_.empty())
    return;
  const std::size_t n = balls_.size();
  group_parent_.assign(n, kNone32);
  group_next_.resize(n);
  first_link_.assign(n, kNone32);
  group_motion_.assign(n, 0);
  group_velocity_.resize(n);
}

void World::joinGroup(std::size_t i)
{
  startGroups();
  if (group_parent_[i] != kNone32)
    return;
  group_parent_[i] = group_next_[i] = static_cast<std::uint32_t>(i);
}

void World::mergeGroups(std::size_t i, std::size_t j)
{
  joinGroup(i);
  joinGroup(j);
  const std::uint32_t a = groupOf(i), b = groupOf(j);
  if (a == b)
    return;
  group_parent_[std::max(a, b)] = std::min(a, b);
  std::swap(group_next_[a], group_next_[b]);  // (the two rings become one)
}

bool World::linked(std::size_t i, std::uint32_t other) const
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

void World::link(std::size_t a, std::uint32_t other)
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

std::uint64_t World::linkKey(std::size_t a, std::uint32_t other) const
{
  const auto id_a = static_cast<std::uint64_t>(balls_[a].id);
  if (other & kWallRow)
    return (id_a << 32) | other;
  const auto id_b = static_cast<std::uint64_t>(balls_[other].id);
  return (std::min(id_a, id_b) << 32) | std::max(id_a, id_b);
}

Vec3 World::groupVelocityAt(std::size_t i, double x) const
{
  // (the span's impulses, gravity's and the contacts', spread evenly over it)
  const Motion& m = motions_[i];
  const Vec3 solved = m.b / dt_;
  const double span = chordEnd(i) - m.x0;
  if (!(span > 0))
    return solved;
  return group_velocity_[i] + ((x - m.x0) / span) * (solved - group_velocity_[i]);
}

double World::impulseEnergy(std::size_t i, double x, const Vec3& before, const Vec3& after) const
{
  // (a member of a group has at x the velocity the group's spread impulses give it, not
  // its chord's: the impulse's change is added to that)
  const Vec3 base = !group_motion_.empty() && group_motion_[i] ? groupVelocityAt(i, x) : before;
  return 0.5 * balls_[i].mass * ((base + (after - before)).squaredNorm() - base.squaredNorm());
}

void World::takeImpulse(std::size_t i, double x, const Vec3& position, const Vec3& dv)
{
  const Vec3 v = groupVelocityAt(i, x) + dv;
  beginMotion(i, x, position, v);
  motions_[i].b = dt_ * v;
  group_velocity_[i] = v;
  group_motion_[i] = 1;
}

void World::formRestingGroups()
{
  const std::size_t n = balls_.size();
  // (the groups' per-ball data is made when the step links its first contact: a step
  // without resting contacts reads none, and a world that never had one keeps none)
  group_parent_.clear();
  group_next_.clear();
  first_link_.clear();
  group_motion_.clear();
  group_velocity_.clear();
  // (the energy each ball may end the step with: its own at the step's start, which its
  // record holds only until its motion starts anew, and what impacts give it)
  energy_ref_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    energy_ref_[i] = energyOf(i, balls_[i].position, balls_[i].velocity);
  links_.clear();
  link_order_.clear();
  // Where gravity does not pull along the floor (a plane square to it), nothing brings
  // balls together: a resting contact there is met within the step, as an event, and
  // linked then; no search at the step's start.
  if (!FloorMotion::gathers(*this))
    return;
  // (the farthest any contact can be linked from, a first filter: gravity itself for its
  // part along the floor, and a margin for the round-off of speeds)
  const double g = gravity_.norm();
  const auto bound = [&](double e) {
    const double least = settings_.reach_least_restitution;
    const double bounces = e < 1 ? settings_.resting_steps * dt_ * g * (1 - e) / (2 * std::max(e, least)) : 0.0;
    return dt_ * (bounces + settings_.reach_speed_margin + dt_ * g);
  };
  double reach = bound(scene_.restitution);
  for (const Wall& wall : walls_)
    reach = std::max(reach, bound(wall.restitution));
  linkRestingWalls(reach);
  linkRestingPairs(reach);
  for (std::size_t i = 0; i < n && !group_parent_.empty(); ++i)
    if (group_parent_[i] == i)
      solveGroup(i, 0.0);
}

double World::speculativeReach(double rest_speed, double pull) const
{
  // Speculative contacts: a pair or wall that closes no faster than it rests, near enough
  // to close its gap within the step (at its resting speed, and what gravity along the
  // floor adds), is a constraint from the step's start, which allows it to close by its
  // gap; else it would meet as an event early in each step, and be solved again there.
  return dt_ * (rest_speed + dt_ * pull);
}

void World::linkRestingWalls(double reach)
{
  const double touch = settings_.touch_slack;
  grid_.forEachNearObstacle([&](std::uint32_t i) {
    if (motions_[i].frozen || balls_[i].flying)
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

void World::linkRestingPairs(double reach)
{
  const double touch = settings_.touch_slack;
  grid_.forEachPair([&](std::uint32_t i, std::uint32_t j) {
    if ((motions_[i].frozen && motions_[j].frozen) || balls_[i].flying || balls_[j].flying)
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

void World::solveGroup(std::size_t i, double x)
{
  gatherGroup(i);
  startMembers(x);
  const double span = groupSpan(x);
  if (span > 0)
  {
    makeRows(span);
    solveRows(span);
  }
  finishGroup(x, span);
}

void World::gatherGroup(std::size_t i)
{
  const std::uint32_t root = groupOf(i);
  members_.clear();
  std::uint32_t k = root;
  do
  {
    members_.push_back(k);
    k = group_next_[k];
  } while (k != root);
  // (the solver's order: by id, so that the bits do not depend on the records' order)
  std::sort(members_.begin(), members_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return balls_[a].id < balls_[b].id; });
  const std::size_t count = members_.size();
  member_positions_.resize(count);
  member_normals_.resize(count);
  member_velocities_.resize(count);
  member_pulls_.resize(count);
  member_caps_.resize(count);
  member_rolls_.resize(count);
}

void World::startMembers(double x)
{
  ContactGroup& group = contact_group_.get();
  group.clear();
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const std::size_t b = members_[m];
    group.localOf(b);
    const Vec3 p = positionAt(b, x);
    const Vec3 fn = floorNormalAt(b, p);
    member_positions_[m] = p;
    member_normals_[m] = fn;
    const bool still = motions_[b].frozen;
    // Time-stepped (Moreau): each member moves over the group's span with the velocity it
    // has at x plus what gravity along the floor adds by the span's end, less what its
    // contacts take. (A member already on its group's motion has at x its velocity before
    // the span's impulses plus their share so far: groupVelocityAt(). Then a group solved
    // again mid-step loses energy as a step does, and gravity's work along what the new
    // solve changes is paid for.)
    // With friction a member rolls: gravity along the floor gives it 1/(1 + k) of its pull,
    // an impulse moves it as a mass (1 + k) m, and rolling resistance holds it back by at
    // most mu_r g_n over the span (solved with its contacts: solveRows()).
    const bool rolls = rollsInGroup(b, fn);
    const double share = rolls ? 1 / (1 + spins_[b].inertia) : 1.0;
    member_velocities_[m] = still             ? Vec3::Zero()
                            : group_motion_[b] ? ground_.along(groupVelocityAt(b, x), fn)
                                               : onFloorVelocity(b, x, p, fn);
    member_pulls_[m] = still ? Vec3::Zero() : Vec3((share * dt_) * ground_.along(gravity_, fn));
    member_caps_[m] = rolls && !still ? dt_ * dt_ * frictionUnder(fn).rollingResistance() : 0.0;
    member_rolls_[m] = rolls;
    group.inv_mass[m] = groupInverseMass(b, rolls);
  }
}

double World::groupSpan(double x) const
{
  // The rest of the step, or on a curved floor, as much of it as keeps each member's chord
  // within what the floor allows (Ground::longestChord()): the group is solved again where
  // the span ends, as a ball alone goes on from where its chord is cut.
  const double rest = 1 - x;
  if (chord_ends_.empty() || !(rest > 0))
    return std::max(rest, 0.0);
  double span = rest;
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const double length = rest * dt_ * (member_velocities_[m] + rest * member_pulls_[m]).norm();
    const double longest = ground_.longestChord(balls_[members_[m]].radius);
    if (length > longest)
      span = std::min(span, rest * (longest / length));
  }
  return span;
}

void World::makeRows(double span)
{
  ContactGroup& group = contact_group_.get();
  row_links_.clear();
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const std::size_t a = members_[m];
    const Vec3& pa = member_positions_[m];
    for (std::uint32_t r = first_link_[a]; r != kNone32;)
    {
      const std::uint32_t index = r;
      const ContactLink& l = links_[r];
      const bool mine = l.a == a;
      r = mine ? l.next_a : l.next_b;
      if (!mine)
        continue;  // (each contact once, from its first ball)
      ContactRow row;
      row.a = static_cast<std::uint32_t>(m);
      row.impulse = l.rate * span;  // (the warm start: its last solve's, at the rate it had)
      // (a contact may close by its gap over the span: speculative)
      Vec3 d;
      double gap = 0.0;
      if (l.b & kWallRow)
      {
        d = walls_[l.b & ~kWallRow].closestPoint(pa) - pa;
        gap = d.norm() - balls_[a].radius;
        row.push_a = wallPush(d.normalized(), member_normals_[m]);
      }
      else
      {
        const std::uint32_t mb = group.localOf(l.b);
        d = member_positions_[mb] - pa;
        gap = d.norm() - (balls_[a].radius + balls_[l.b].radius);
        row.b = mb;
        row.push_a = ground_.along(d.normalized(), member_normals_[m]);
        row.push_b = ground_.along(d.normalized(), member_normals_[mb]);
      }
      if (!(d.norm() > 0))
        continue;
      row.target = gap / span;
      group.rows.push_back(row);
      row_links_.push_back(index);
    }
  }
  // (the rows in the order of their contacts' keys, whatever order they were made in)
  std::vector<std::size_t> order(group.rows.size());
  for (std::size_t r = 0; r < order.size(); ++r)
    order[r] = r;
  const auto keyOf = [&](std::size_t r) { return linkKey(links_[row_links_[r]].a, links_[row_links_[r]].b); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keyOf(a) < keyOf(b); });
  std::vector<ContactRow> rows(order.size());
  std::vector<std::uint32_t> links(order.size());
  for (std::size_t r = 0; r < order.size(); ++r)
  {
    rows[r] = group.rows[order[r]];
    links[r] = row_links_[order[r]];
  }
  group.rows.swap(rows);
  row_links_.swap(links);
}

void World::solveRows(double span)
{
  ContactGroup& group = contact_group_.get();
  const std::size_t count = members_.size();
  base_u_.resize(count);
  for (std::size_t m = 0; m < count; ++m)
    base_u_[m] = dt_ * (member_velocities_[m] + span * member_pulls_[m]);
  free_u_.resize(count);
  resisted_.assign(count, Vec3::Zero());
  const double slack = roundoffAt(member_positions_[0], 0.0, settings_);
  // Rolling resistance with the contacts: after each sweep of projected Gauss-Seidel
  // over the contacts, each member's resistance opposes its motion with its contacts'
  // pushes, up to its cap, and stops it where that is enough (a box constraint on a
  // friction impulse, as in Box2D's solver); then the contacts are solved exactly, with
  // the resistance found.
  if (friction_ && std::any_of(member_caps_.begin(), member_caps_.end(), [](double c) { return c > 0; }))
  {
    group.u = base_u_;
    const auto resist = [&](std::vector<Vec3>& u) {
      for (std::size_t m = 0; m < count; ++m)
      {
        const Vec3 moving = u[m] - resisted_[m];
        const double cap = span * member_caps_[m];
        const double speed = moving.norm();
        const Vec3 r = speed <= cap ? Vec3(-moving) : Vec3((-cap / speed) * moving);
        u[m] += r - resisted_[m];
        resisted_[m] = r;
      }
    };
    solveContacts(group.u, group.inv_mass, group.rows, slack, settings_.resistance_sweeps, resist);
  }
  for (std::size_t m = 0; m < count; ++m)
    free_u_[m] = base_u_[m] + resisted_[m];
  group.u = free_u_;
  solveGroupContacts(group, span, slack);
  for (std::size_t r = 0; r < group.rows.size(); ++r)
    links_[row_links_[r]].rate = group.rows[r].impulse / span;
}

void World::solveGroupContacts(ContactGroup& group, double span, double slack)
{
  const std::size_t count = members_.size();
  const auto project = [&](std::vector<Vec3>& u) {
    if (!floor_motion_->endsPutOnFloor())
      return;
    for (std::size_t m = 0; m < count; ++m)
      if (!motions_[members_[m]].frozen)
        u[m] = (onFloor(members_[m], member_positions_[m] + span * u[m]) - member_positions_[m]) / span;
  };
  // On a curved floor the rows are the contacts' distances linearized where the step
  // starts; the ends put back on the floor can lie closer. Each row's target then takes
  // what its linearization missed at the solved ends, and the group is solved again
  // from its free motions (Newton's method on the contacts' distances).
  for (int pass = 0; pass < settings_.group_passes; ++pass)
  {
    if (pass > 0)
      group.u = free_u_;
    // (the solve is linear, on the rows as they are; the ends go back on the floor after it)
    if (!solveContacts(group.u, group.inv_mass, group.rows, slack, settings_.group_sweeps).converged &&
        !solveContactsExactly(free_u_, group.inv_mass, group.rows, group.u, slack, exactSettings()))
    {
      // (more sweeps give the exact solve a better guess of which rows push)
      solveContacts(group.u, group.inv_mass, group.rows, slack, settings_.group_retry_sweeps);
      if (!solveContactsExactly(free_u_, group.inv_mass, group.rows, group.u, slack, exactSettings()))
        ++stats_.unsettled_contacts;  // (the exact solve found no answer: the sweeps' stays)
    }
    project(group.u);
    if (!floor_motion_->endsPutOnFloor())
      break;
    double deepest = 0.0;
    for (ContactRow& row : group.rows)
    {
      const Vec3 ea = member_positions_[row.a] + span * group.u[row.a];
      double gap = 0.0;
      const ContactLink& l = links_[row_links_[static_cast<std::size_t>(&row - group.rows.data())]];
      if (row.b == ContactRow::kImmovable)
        gap = walls_[l.b & ~kWallRow].distance(ea) - balls_[members_[row.a]].radius;
      else
        gap = (member_positions_[row.b] + span * group.u[row.b] - ea).norm() -
              (balls_[members_[row.a]].radius + balls_[members_[row.b]].radius);
      const double linear = span * (row.target - closingOf(group.u, row));
      if (gap < linear && gap < 0)
      {
        deepest = std::max(deepest, -gap);
        row.target += (gap - linear) / span;
      }
    }
    if (!(deepest > slack))
      break;
  }
}

bool World::rollsInGroup(std::size_t i, const Vec3& n) const
{
  return friction_ && frictionUnder(n).holdsRolling(spins_[i].inertia);
}

void World::finishGroup(double x, double span)
{
  ContactGroup& group = contact_group_.get();
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const std::size_t b = members_[m];
    if (motions_[b].frozen)
      continue;
    const Vec3 v = group.u[m] / dt_;
    // (a member rolls: its spin along the floor is rolling's, its spin about the normal
    // stays)
    const Vec3& n = member_normals_[m];
    const Vec3 spin_about_n = member_rolls_[m] ? Vec3(spinAt(b, x).dot(n) * n) : Vec3::Zero();
    beginMotion(b, x, member_positions_[m], v);
    motions_[b].b = group.u[m];
    if (!chord_ends_.empty())
      chord_ends_[b] = span > 0 ? x + span : 1.0;  // (where the group is solved again)
    group_velocity_[b] = member_velocities_[m];
    group_motion_[b] = 1;
    if (member_rolls_[m])
      spin_motions_[b].w0 = n.cross(v) / balls_[b].radius + spin_about_n;
    if (friction_)
      constrainSpin(b);
    if (x > 0)
    {
      renewMotion(b);
      detect(b);
    }
    else
      grid_.update(static_cast<std::uint32_t>(b), currentBox(b));
  }
}

const std::vector<std::uint32_t>& World::linksInKeyOrder()
{
  if (link_order_.size() != links_.size())
  {
    link_order_.resize(links_.size());
    for (std::size_t r = 0; r < links_.size(); ++r)
      link_order_[r] = static_cast<std::uint32_t>(r);
    std::sort(link_order_.begin(), link_order_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return linkKey(links_[a].a, links_[a].b) < linkKey(links_[b].a, links_[b].b);
    });
  }
  return link_order_;
}

World::ContactGroup& World::endGroup()
{
  ContactGroup& group = contact_group_.get();
  group.clear();
  warm_.clear();
  const double touch = settings_.touch_slack;
  for (const std::uint32_t index : linksInKeyOrder())
  {
    const ContactLink& l = links_[index];
    if (l.rate > 0 && settings_.warm_start)
      warm_[linkKey(l.a, l.b)] = l.rate;
    const Ball& a = balls_[l.a];
    if (l.b & kWallRow)
    {
      const Vec3 d = walls_[l.b & ~kWallRow].closestPoint(a.position) - a.position;
      const double dist = d.norm();
      if (!(dist - a.radius <= touch) || !(dist > 0))
        continue;
      ContactRow row;
      row.a = group.localOf(l.a);
      row.push_a = wallPush(d / dist, floor_normals_[l.a]);
      group.rows.push_back(row);
      continue;
    }
    const Ball& b = balls_[l.b];
    const Vec3 d = b.position - a.position;
    const double dist = d.norm();
    if (!(dist - (a.radius + b.radius) <= touch) || !(dist > 0))
      continue;
    const Vec3 u = d / dist;
    const Vec3 along_a = ground_.along(u, floor_normals_[l.a]), along_b = ground_.along(u, floor_normals_[l.b]);
    group.addPair(l.a, l.b, along_a, along_b);
  }
  for (std::size_t k = 0; k < group.size(); ++k)
  {
    const std::size_t i = group.ballAt(k);
    group.u[k] = balls_[i].velocity;
    group.inv_mass[k] = groupInverseMass(i, rollsInGroup(i, floor_normals_[i]));
  }
  return group;
}
void World::boundGroupEnergies()
{
  if (group_parent_.empty())
    return;
  const std::size_t n = balls_.size();
  std::vector<double> allowed(n, 0.0), now(n, 0.0), kinetic(n, 0.0);
  for (const std::uint32_t i : by_id_)  // (summed in id order, whatever the records' order)
  {
    const std::uint32_t root = groupOf(i);
    if (root == kNone32)
      continue;
    allowed[root] += energy_ref_[i];
    const Ball& ball = balls_[i];
    now[root] += energyOf(i, ball.position, ball.velocity);
    kinetic[root] += 0.5 * ball.mass * ball.velocity.squaredNorm();
    if (friction_ && friction_->grips())
      kinetic[root] +=
          0.5 * spins_[i].inertia * ball.mass * ball.radius * ball.radius * spins_[i].angular_velocity.squaredNorm();
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t root = groupOf(i);
    if (root == kNone32 || !(now[root] > allowed[root]))
      continue;
    const double left = kinetic[root] - (now[root] - allowed[root]);
    const double scale = left > 0 ? std::sqrt(left / kinetic[root]) : 0.0;
    balls_[i].velocity *= scale;
    if (friction_ && friction_->grips())
      spins_[i].angular_velocity *= scale;
  }
}

double World::separationRows()
{
  ContactGroup& group = contact_group_.get();
  group.clear();
  double deepest = 0.0;
  for (const std::uint32_t index : linksInKeyOrder())
  {
    const ContactLink& l = links_[index];
    const Ball& a = balls_[l.a];
    ContactRow row;
    Vec3 d;
    double gap = 0.0;
    if (l.b & kWallRow)
    {
      d = walls_[l.b & ~kWallRow].closestPoint(a.position) - a.position;
      gap = d.norm() - a.radius;
    }
    else
    {
      d = balls_[l.b].position - a.position;
      gap = d.norm() - (a.radius + balls_[l.b].radius);
    }
    if (!(d.norm() > 0) || !(gap <= settings_.touch_slack))
      continue;
    deepest = std::max(deepest, -gap);
    // (along the floor, not unit: a move u along it changes the distance by u . push;
    // where the floor all but faces the contact, along the contact's normal)
    const auto push = [&](std::size_t i) {
      const Vec3 t = ground_.along(d.normalized(), floor_normals_[i]);
      return t.squaredNorm() < settings_.separation_min_share ? Vec3(d.normalized()) : t;
    };
    row.a = group.localOf(l.a);
    row.push_a = push(l.a);
    if (!(l.b & kWallRow))
    {
      row.b = group.localOf(l.b);
      row.push_b = push(l.b);
    }
    row.target = gap;
    group.rows.push_back(row);
  }
  return deepest;
}

void World::separateAtEnd()
{
  // Each pass: the step's contacts as rows on the balls' moves along the floor, the
  // overlapping ones to open by their depth, the others to close by no more than their
  // gap, solved as the velocities are (exactly, whatever the masses: a light ball jammed
  // between a heavy one and a wall is not pushed back and forth); then each ball back on
  // the floor, which the next pass corrects.
  for (int pass = 0; pass < settings_.position_sweeps; ++pass)
  {
    ContactGroup& group = contact_group_.get();
    const double deepest = separationRows();
    if (!(deepest > 0))
      break;
    for (std::size_t k = 0; k < group.size(); ++k)
    {
      const std::size_t i = group.ballAt(k);
      group.u[k] = Vec3::Zero();
      group.inv_mass[k] = groupInverseMass(i, rollsInGroup(i, floor_normals_[i]));
    }
    const std::vector<Vec3> still(group.size(), Vec3::Zero());
    const double slack = roundoffAt(balls_[group.ballAt(0)].position, 0.0, settings_);
    if (!solveContacts(group.u, group.inv_mass, group.rows, slack, settings_.group_sweeps).converged &&
        !solveContactsExactly(still, group.inv_mass, group.rows, group.u, slack, exactSettings()))
      ++stats_.unsettled_contacts;
    for (std::size_t k = 0; k < group.size(); ++k)
    {
      const std::size_t i = group.ballAt(k);
      Ball& ball = balls_[i];
      const Vec3 to = onFloor(i, ball.position + group.u[k]);
      motions_[i].b += to - ball.position;
      ball.position = to;
    }
  }
}
}  // namespace ball_collision_sim::core
