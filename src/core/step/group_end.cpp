// The step's end for resting groups: every group's contacts in one solve at the end
// (their velocities settled), the energy each group may end with, and the separation of
// contacts that ended the step overlapping. Reads the groups' links and the committed
// positions; writes the balls' end velocities and positions, the contact solver's work
// space.
#include "spin_model.hpp"
#include "contact_group.hpp"
#include "floor_motion.hpp"
#include "spin_phase.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

const std::vector<std::uint32_t>& StepContext::linksInKeyOrder()
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

StepState::ContactGroup& StepContext::endGroup()
{
  ContactGroup& group = contact_group_.get();
  group.clear();
  warm_.clear();
  const double touch = settings_.touch_slack;
  for (const std::uint32_t index : linksInKeyOrder())
  {
    const ContactLink& l = links_[index];
    if (linkGone(l))
      continue;  // (a ball in a pocket)
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
void StepContext::boundGroupEnergies()
{
  if (group_parent_.empty())
    return;
  const std::size_t n = balls_.size();
  std::vector<double> allowed(n, 0.0), now(n, 0.0), kinetic(n, 0.0);
  for (const std::uint32_t i : by_id_)  // (summed in id order, whatever the records' order)
  {
    const std::uint32_t root = groupOf(i);
    if (root == kNone32 || motions_[i].gone())
      continue;  // (a ball in a pocket takes its energy with it)
    allowed[root] += energy_ref_[i];
    const Ball& ball = balls_[i];
    now[root] += energyOf(i, ball.position, ball.velocity);
    kinetic[root] += 0.5 * ball.mass * ball.velocity.squaredNorm();
    kinetic[root] += spinEnergy(i);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t root = groupOf(i);
    if (root == kNone32 || !(now[root] > allowed[root]))
      continue;
    const double left = kinetic[root] - (now[root] - allowed[root]);
    const double scale = left > 0 ? std::sqrt(left / kinetic[root]) : 0.0;
    balls_[i].velocity *= scale;
    spin_->scaleSpin(*this, i, scale);
  }
}

double StepContext::separationRows()
{
  ContactGroup& group = contact_group_.get();
  group.clear();
  double deepest = 0.0;
  for (const std::uint32_t index : linksInKeyOrder())
  {
    const ContactLink& l = links_[index];
    if (linkGone(l))
      continue;  // (a ball in a pocket)
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

void StepContext::separateAtEnd()
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
