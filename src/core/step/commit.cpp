// Stage 5, commit: every ball to the step's end, back on the floor, its velocity
// there (solved across the step's resting contacts by the contact solver), its turn by
// rolling; and, while the visiting order stays, the next step's prediction. Reads
// motions_, states_, resting_, blocked_sets_; writes balls_, feet_, the contact solver's
// work space.
#include "contact_group.hpp"
#include "spin_phase.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ball_collision_sim::core
{
using namespace step;

namespace
{
/// sin(x) / x and cos(x) from y = x^2 (both are even in x): series where |x| is small,
/// the usual way elsewhere; so a caller that has x^2 takes no square root. The series are
/// summed in pairs of terms (Estrin's scheme) so that they take a few dependent steps
/// rather than one per term.
void sincCosOfSquare(double y, double& sinc, double& c)
{
  if (!(y <= 0.25))
  {
    const double x = std::sqrt(y);
    sinc = std::sin(x) / x;
    c = std::cos(x);
    return;
  }
  // Taylor series to x^16 and x^18: the first term left out is below 3e-23 for |x| <= 1/2.
  // s[k] = (-1)^k / (2k + 1)!, c[k] = (-1)^k / (2k)!
  constexpr double s1 = -1.0 / 6, s2 = 1.0 / 120, s3 = -1.0 / 5040, s4 = 1.0 / 362880, s5 = -1.0 / 39916800,
                   s6 = 1.0 / 6227020800, s7 = -1.0 / 1307674368000, s8 = 1.0 / 355687428096000;
  constexpr double c1 = -1.0 / 2, c2 = 1.0 / 24, c3 = -1.0 / 720, c4 = 1.0 / 40320, c5 = -1.0 / 3628800,
                   c6 = 1.0 / 479001600, c7 = -1.0 / 87178291200, c8 = 1.0 / 20922789888000,
                   c9 = -1.0 / 6402373705728000;
  const double x2 = y, x4 = x2 * x2, x8 = x4 * x4;
  sinc = ((1 + s1 * x2) + x4 * (s2 + s3 * x2)) + x8 * (((s4 + s5 * x2) + x4 * (s6 + s7 * x2)) + x8 * s8);
  c = ((1 + c1 * x2) + x4 * (c2 + c3 * x2)) + x8 * (((c4 + c5 * x2) + x4 * (c6 + c7 * x2)) + x8 * (c8 + c9 * x2));
}
}  // namespace

void World::commitToFloor(bool predict_next)
{
  // Without resting contacts every ball is finished in one pass; with them, velocities
  // are settled across the contacts first.
  const bool settle = !resting_.empty() || !blocked_sets_.empty();
  std::uint64_t asleep = 0;
  if (settle)
    floor_normals_.resize(balls_.size());
  for (std::size_t i = 0; i < balls_.size(); ++i)
  {
    const Committed done = commitBall(i, settle);
    if (!settle)
    {
      Ball& ball = balls_[i];
      ball.quiet_steps = 0;  // it leaned on nothing
      asleep += ball.asleep ? 1 : 0;
      roll(i, done.normal, done.moved);
      if (predict_next)
        predictMotion(i);
    }
    else
      motions_[i].p0 = done.moved;  // the motion is done with: p0 keeps the step's move for roll()
  }
  if (!settle)
  {
    stats_.sleeping_balls = asleep;
    return;
  }
  settleRestingVelocities();
  for (std::size_t i = 0; i < balls_.size(); ++i)
    roll(i, floor_normals_[i], motions_[i].p0);
  // Groups at rest sleep; where gravity does not pull along the floor, nothing gathers
  // balls into groups, and none does.
  if (FloorMotion::gathers(*this))
    sleepStillGroups();
  if (predict_next)
    for (std::size_t i = 0; i < balls_.size(); ++i)
      predictMotion(i);
}

World::Committed World::commitBall(std::size_t i, bool settle)
{
  Ball& ball = balls_[i];
  // (a ball asleep stays where it is, on the foot point it had; the floor's normal there
  // counts only across resting contacts: its spin is kept as it is, SpinPhase::kept())
  const Ground::End end = states_[i].asleep ? ground_.stillEnd(ball.position, motions_[i].radius, guessOf(i), settle)
                                            : ground_.end(positionAt(i, 1.0), motions_[i].radius, guessOf(i));
  if (!feet_.empty())
    feet_[i] = end.foot;
  if (settle)
    floor_normals_[i] = end.normal;
  const Vec3 moved = end.centre - ball.position;
  ball.position = end.centre;
  // (a ball that ends the step without motion, frozen or held still by its contacts,
  // keeps no speed it does not move with)
  ball.velocity = states_[i].frozen || states_[i].held ? Vec3::Zero() : onFloorVelocity(i, 1.0, end.centre, end.normal);
  if (friction_)
  {
    // its own spin at the end, and its turn over the step by the mean of its spins
    SpinMotion& sm = spin_motions_[i];
    BallSpin& spin = spins_[i];
    // (a rolling ball rolls under the normal where it ends)
    const Vec3 w = floor_motion_->spinThere(*this, i, end.normal, ball.velocity, spinAt(i, 1.0),
                                            sm.phase->rollsAtCommit(sm));
    sm.turn = (0.5 * dt_) * (spin.angular_velocity + w);
    spin.angular_velocity = w;
    sm.kind = sm.phase->kindAtEnd(*this, i, sm, end.normal, ball.velocity, w);
    recordKind(i, motions_[i].x0);  // (a kind the step's events did not report)
    spin.kind = sm.kind;
  }
  return {moved, end.normal};
}

void World::settleRestingVelocities()
{
  // Resting contacts keep no closing speed into the step that follows.
  for (std::size_t i = 0; i < balls_.size(); ++i)
    balls_[i].velocity = redirected(i, balls_[i].velocity);
  if (resting_.empty())
    return;
  ContactGroup& group = velocityGroup();
  // (done where what closing is left is round-off of speeds, or of the closing there was)
  const double tolerance =
      std::max(settings_.resting_speed_floor, settings_.contact_tolerance * largestClosing(group.u, group.rows));
  if (!solveContacts(group.u, group.inv_mass, group.rows, tolerance, settings_.contact_sweeps).converged)
    ++stats_.unsettled_contacts;
  for (std::size_t k = 0; k < group.size(); ++k)
    balls_[group.ballAt(k)].velocity = group.u[k];
  for (std::size_t i = 0; i < balls_.size(); ++i)
  {
    // the impulses across the contacts may leave a velocity a part along the floor's
    // normal, which the floor takes (where speeds are the energy's, it keeps the speed)
    Ball& ball = balls_[i];
    ball.velocity = ground_.turned(ball.velocity, ground_.along(ball.velocity, floor_normals_[i]));
  }
}

World::ContactGroup& World::velocityGroup()
{
  // The closing speed that gravity gave a pair in the step, where it is faster than the
  // pair's resting speed, bounces as an impact would, pair by pair in the order they
  // met; then every pair that rested in the step (by its last resting contact: the
  // normal where they last met) is a constraint (no closing speed), and so is every
  // direction a ball leans on a wall along, solved together (contact_solver.hpp).
  ContactGroup& group = contact_group_.get();
  group.clear();
  lastOfPair(resting_, last_of_pair_);
  std::size_t next_last = 0;
  for (std::size_t r = 0; r < resting_.size(); ++r)
  {
    const RestingContact& contact = resting_[r];
    Ball& a = balls_[contact.ball];
    Ball& b = balls_[contact.other];
    const double inv_a = inverseMass(contact.ball);
    const double inv_b = inverseMass(contact.other);
    const double closing = a.velocity.dot(contact.dir_ball) - b.velocity.dot(contact.dir_other);
    const double rest = pairRestingSpeed(floor_normals_[contact.ball], a.position, a.radius,
                                         floor_normals_[contact.other], b.position, b.radius);
    if (closing > rest)
    {
      const double j = collisionImpulse(closing, inv_a, contact.dir_ball, inv_b, contact.dir_other, scene_.restitution);
      a.velocity -= (j * inv_a) * contact.dir_ball;
      b.velocity += (j * inv_b) * contact.dir_other;
    }
    if (next_last < last_of_pair_.size() && last_of_pair_[next_last] == r)
    {
      ++next_last;
      group.addPair(contact.ball, contact.other, contact.along_ball, contact.along_other);
    }
  }
  for (std::size_t k = 0; k < group.size(); ++k)
  {
    const std::size_t i = group.ballAt(k);
    group.u[k] = balls_[i].velocity;
    group.inv_mass[k] = inverseMass(i);
    if (states_[i].blocked >= 0)
      group.addBlocked(k, blocked_sets_[static_cast<std::size_t>(states_[i].blocked)],
                       [this](std::uint64_t source) { return isWallSource(source); });
  }
  return group;
}

void World::lastOfPair(const std::vector<RestingContact>& contacts, std::vector<std::size_t>& last)
{
  // (pairs by their smaller and larger visiting index, then the order they met in)
  last.resize(contacts.size());
  for (std::size_t r = 0; r < contacts.size(); ++r)
    last[r] = r;
  const auto key = [&](std::size_t r) {
    const RestingContact& c = contacts[r];
    return std::make_tuple(std::min(c.ball, c.other), std::max(c.ball, c.other), r);
  };
  std::sort(last.begin(), last.end(), [&](std::size_t p, std::size_t q) { return key(p) < key(q); });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < last.size(); ++k)
  {
    const bool final = k + 1 == last.size() || std::get<0>(key(last[k + 1])) != std::get<0>(key(last[k])) ||
                       std::get<1>(key(last[k + 1])) != std::get<1>(key(last[k]));
    if (final)
      last[kept++] = last[k];
  }
  last.resize(kept);
  std::sort(last.begin(), last.end());
}

void World::roll(std::size_t i, const Vec3& normal, const Vec3& d)
{
  if (friction_)
  {
    turn(i, spin_motions_[i].turn);  // by its own spin
    return;
  }
  // Rolling without slip: turned by |d| / r about n x d, d the move along the floor
  // (|n x d| is its length). Its angular velocity follows from n and v when asked for.
  Ball& ball = balls_[i];
  const double half_inv_radius = 0.5 / ball.radius;
  const Vec3 axis = normal.cross(d);
  const double axis_squared = axis.squaredNorm();
  if (axis_squared > 0)
  {
    // the half angle x = |n x d| / 2r; sin(x) / |n x d| = sinc(x) / 2r
    double sinc_half = 1, cos_half = 1;
    sincCosOfSquare(axis_squared * (half_inv_radius * half_inv_radius), sinc_half, cos_half);
    const Vec3 k = (sinc_half * half_inv_radius) * axis;
    Quat q = Quat(cos_half, k.x(), k.y(), k.z()) * ball.orientation;
    // back to unit length: the product of unit quaternions is off by round-off only, so
    // one Newton step of 1/sqrt does
    q.coeffs() *= 1.5 - 0.5 * q.coeffs().squaredNorm();
    ball.orientation = q;
  }
}
}  // namespace ball_collision_sim::core
