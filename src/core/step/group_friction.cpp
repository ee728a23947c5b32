// Friction at a resting group's contacts: each contact's two directions across its
// normal as rows on the members' motions and spins, bounded by Coulomb's law with the
// `ball_ball` or `wall` coefficient (solved with the contacts: contact_friction.hpp).
// A member that rolls moves with its spin along the floor, so its touching point moves
// as its motion and its spin about the floor's normal give; one that slides turns freely.
// Reads the group's members and rows; writes contact_group_'s spins and friction, free_w_.
#include "contact_group.hpp"
#include "step_context.hpp"

#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

namespace
{
/// A member's touching point at rho [m] from its centre, under a floor of normal n: what
/// moving the member along the floor moves the point by along e ...
Vec3 touchPush(const Ground& ground, const Vec3& n, bool rolls, double radius, const Vec3& rho, const Vec3& e)
{
  if (!rolls)
    return ground.along(e, n);
  // (a motion v rolls the ball at n x v / r: the point moves by v + (n x v) x rho / r)
  return ground.along(e + (e * n.dot(rho) - rho * e.dot(n)) / radius, n);
}

/// ... and what turning it does, over a step of dt (where it rolls, its spin along the
/// floor is its motion's: ContactGroup::w holds its spin about the normal)
Vec3 touchTurn(double dt, const Vec3& n, bool rolls, const Vec3& rho, const Vec3& e)
{
  const Vec3 turn = dt * rho.cross(e);
  return rolls ? Vec3(turn.dot(n) * n) : turn;
}
}  // namespace

void StepContext::makeFrictionRows(double x)
{
  if (!scene_.friction || !(scene_.friction->ball_ball > 0 || scene_.friction->wall > 0))
    return;
  ContactGroup& group = contact_group_.get();
  for (std::size_t m = 0; m < members_.size(); ++m)
  {
    const std::size_t b = members_[m];
    if (motions_[b].frozen())
      continue;  // (a ball without motion is still, its surface too)
    const Vec3 spin = spinAt(b, x);
    const Vec3& n = member_normals_[m];
    const Ball& ball = balls_[b];
    group.w[m] = member_rolls_[m] ? Vec3(spin.dot(n) * n) : spin;
    group.inv_inertia[m] = 1 / (spins_[b].inertia * ball.mass * ball.radius * ball.radius * dt_ * dt_);
  }
  free_w_ = group.w;
  for (std::size_t r = 0; r < group.rows.size(); ++r)
  {
    const ContactLink& l = links_[row_links_[r]];
    const ContactRow& row = group.rows[r];
    const bool wall = (l.b & kWallRow) != 0;
    FrictionPair pair;
    pair.normal = static_cast<std::uint32_t>(r);
    pair.mu = wall ? scene_.friction->wall : scene_.friction->ball_ball;
    if (!(pair.mu > 0))
      continue;
    const Vec3& pa = member_positions_[row.a];
    const Vec3 d =
        (wall ? Vec3(walls_[l.b & ~kWallRow].closestPoint(pa) - pa) : Vec3(member_positions_[row.b] - pa)).normalized();
    // (across the normal d: along the floor, and across that)
    Vec3 e1 = member_normals_[row.a].cross(d);
    e1 = e1.squaredNorm() > settings_.wall_along_floor_squared ? Vec3(e1.normalized()) : d.unitOrthogonal();
    const Vec3 e2 = d.cross(e1);
    const Vec3 rho_a = balls_[members_[row.a]].radius * d;
    // (where both roll, motion toward the contact moves their touching points across the
    // floor's plane only as it closes the contact: a resting contact holds that, and a row
    // across the floor would share the contact's push, which is then no longer determined,
    // and take from its bound. Impacts give that friction.)
    const bool rolls = member_rolls_[row.a] && (wall || member_rolls_[row.b]);
    for (std::size_t k = 0; k < (rolls ? 1u : 2u); ++k)
    {
      const Vec3& e = k == 0 ? e1 : e2;
      FrictionRow& f = pair.rows[k];
      f.push_a =
          touchPush(ground_, member_normals_[row.a], member_rolls_[row.a], balls_[members_[row.a]].radius, rho_a, e);
      f.turn_a = touchTurn(dt_, member_normals_[row.a], member_rolls_[row.a], rho_a, e);
      if (wall)
        continue;
      const Vec3 rho_b = -balls_[members_[row.b]].radius * d;
      f.push_b =
          touchPush(ground_, member_normals_[row.b], member_rolls_[row.b], balls_[members_[row.b]].radius, rho_b, e);
      f.turn_b = touchTurn(dt_, member_normals_[row.b], member_rolls_[row.b], rho_b, e);
    }
    group.friction.push_back(pair);
  }
}
}  // namespace ball_collision_sim::core
