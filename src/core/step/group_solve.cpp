// A resting group solved from an event's time on: its members gathered, their motions
// started at that time, the contacts' rows made over the rest of the step and solved
// (the contact solver), and each member's motion over the rest of the step set from the
// solution. Reads the groups' links, the start positions and velocities; writes motions_,
// the members' work space, the grid's boxes.
#include "spin_model.hpp"
#include "contact_group.hpp"
#include "floor_motion.hpp"
#include "spin_phase.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

void StepContext::solveGroup(std::size_t i, double x)
{
  gatherGroup(i);
  if (members_.empty())
    return;  // (its last member dropped into a pocket)
  startMembers(x);
  const double span = groupSpan(x);
  if (span > 0)
  {
    makeRows(span);
    makeFrictionRows(x);
    solveRows(span);
  }
  finishGroup(x, span);
}

void StepContext::gatherGroup(std::size_t i)
{
  const std::uint32_t root = groupOf(i);
  members_.clear();
  std::uint32_t k = root;
  do
  {
    if (!motions_[k].gone())  // (one that dropped into a pocket is no member any more)
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

void StepContext::startMembers(double x)
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
    const bool still = motions_[b].frozen();
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
    member_velocities_[m] = onFloorVelocity(b, x, p, fn);
    member_pulls_[m] = still ? Vec3::Zero() : Vec3((share * dt_) * ground_.along(gravity_, fn));
    member_caps_[m] = rolls && !still ? dt_ * dt_ * frictionUnder(fn).rollingResistance() : 0.0;
    member_rolls_[m] = rolls;
    group.inv_mass[m] = groupInverseMass(b, rolls);
  }
}

double StepContext::groupSpan(double x) const
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

void StepContext::makeRows(double span)
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
      if (!mine || linkGone(l))
        continue;  // (each contact once, from its first ball; none with a ball in a pocket)
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

void StepContext::solveRows(double span)
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
  if (std::any_of(member_caps_.begin(), member_caps_.end(), [](double c) { return c > 0; }))
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

void StepContext::solveGroupContacts(ContactGroup& group, double span, double slack)
{
  const std::size_t count = members_.size();
  const auto project = [&](std::vector<Vec3>& u) {
    if (!floor_motion_->endsPutOnFloor())
      return;
    for (std::size_t m = 0; m < count; ++m)
      if (!motions_[members_[m]].frozen())
        u[m] = (onFloor(members_[m], member_positions_[m] + span * u[m]) - member_positions_[m]) / span;
  };
  // On a curved floor the rows are the contacts' distances linearized where the step
  // starts; the ends put back on the floor can lie closer. Each row's target then takes
  // what its linearization missed at the solved ends, and the group is solved again
  // from its free motions (Newton's method on the contacts' distances).
  for (int pass = 0; pass < settings_.group_passes; ++pass)
  {
    if (pass > 0)
    {
      group.u = free_u_;
      group.w = free_w_;
    }
    // (the solve is linear, on the rows as they are; the ends go back on the floor after it)
    if (!group.friction.empty())
    {
      if (!solveFrictionally(free_u_, free_w_, group.u, group.inv_mass, group.rows, Spins{group.w, group.inv_inertia},
                             group.friction, slack, settings_.group_sweeps, settings_.friction_passes,
                             exactSettings()))
        ++stats_.unsettled_contacts;
    }
    else if (!solveContacts(group.u, group.inv_mass, group.rows, slack, settings_.group_sweeps).converged &&
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

bool StepContext::rollsInGroup(std::size_t i, const Vec3& n) const
{
  return spin_->rollsInGroup(*this, i, n);
}

void StepContext::finishGroup(double x, double span)
{
  ContactGroup& group = contact_group_.get();
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const std::size_t b = members_[m];
    if (motions_[b].frozen())
      continue;
    const Vec3 v = group.u[m] / dt_;
    // (a member rolls: its spin along the floor is rolling's, its spin about the normal
    // stays, or is what friction at its contacts made it, group.w, as a sliding member's
    // whole spin is)
    const Vec3& n = member_normals_[m];
    const bool turned = !group.friction.empty();
    const Vec3 spin_about_n = !member_rolls_[m] ? Vec3::Zero() : turned ? group.w[m] : Vec3(spinAt(b, x).dot(n) * n);
    const Vec3 spin = turned && !member_rolls_[m] ? group.w[m] : Vec3::Zero();
    beginMotion(b, x, member_positions_[m], v);
    motions_[b].b = group.u[m];
    if (!chord_ends_.empty())
      chord_ends_[b] = span > 0 ? x + span : 1.0;  // (where the group is solved again)
    group_velocity_[b] = member_velocities_[m];
    motions_[b].become(MotionType::kGrouped);
    if (member_rolls_[m])
      spin_motions_[b].w0 = n.cross(v) / balls_[b].radius + spin_about_n;
    else if (turned)
      spin_motions_[b].w0 = spin;
    spin_->followGroup(*this, b, member_rolls_[m]);
    if (x > 0)
    {
      renewMotion(b);
      detect(b);
    }
    else
      grid_.update(static_cast<std::uint32_t>(b), currentBox(b));
  }
}
}  // namespace ball_collision_sim::core
