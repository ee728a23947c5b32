// Stage 5, commit: every ball to the step's end, back on the floor, its velocity
// there (solved across the step's resting contacts by the contact solver), its turn by
// rolling; and, while the visiting order stays, the next step's prediction. Reads
// motions_, step_starts_, resting_, blocked_; writes balls_, feet_, the contact solver's
// work space.
#include "contact_group.hpp"
#include "rolling.hpp"
#include "spin_phase.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

void World::commitToFloor(bool predict_next)
{
  // Without resting contacts every ball is finished in one pass; with them, velocities
  // are settled across the contacts first.
  const bool settle = !resting_.empty() || !blocked_.get().empty();
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
      motions_[i].b = done.moved;  // the motion is done with: b keeps the step's move for roll()
  }
  step_starts_.clear();  // (each ball's was taken back by its commit)
  if (!settle)
  {
    stats_.sleeping_balls = asleep;
    return;
  }
  settleRestingVelocities();
  for (std::size_t i = 0; i < balls_.size(); ++i)
    roll(i, floor_normals_[i], motions_[i].b);
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
  const Ground::End end = motions_[i].asleep ? ground_.stillEnd(ball.position, ball.radius, guessOf(i), settle)
                                             : ground_.end(positionAt(i, 1.0), ball.radius, guessOf(i));
  if (!feet_.empty())
    feet_[i] = end.foot;
  if (settle)
    floor_normals_[i] = end.normal;
  // (its record holds where its last motion started until the end of this: where the
  // step started it is kept apart if that motion is not its first)
  std::uint32_t& start = step_start_of_[i];
  const Vec3 moved = end.centre - (start == kNoStepStart ? ball.position : step_starts_[start]);
  start = kNoStepStart;
  // (a ball that ends the step without motion, frozen or held still by its contacts,
  // keeps no speed it does not move with)
  const Motion& m = motions_[i];
  ball.velocity = m.frozen || m.held ? Vec3::Zero() : onFloorVelocity(i, 1.0, end.centre, end.normal);
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
  ball.position = end.centre;
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
  lastOfEachPair(resting_, last_of_pair_);
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
    if (const std::int32_t blocked = motions_[i].blocked; blocked >= 0)
      group.addBlocked(k, blocked_.get(), blocked,
                       [this](std::uint64_t source) { return isWallSource(source); });
  }
  return group;
}

void World::roll(std::size_t i, const Vec3& normal, const Vec3& d)
{
  if (friction_)
  {
    turn(i, spin_motions_[i].turn);  // by its own spin
    return;
  }
  // rolling without slip, by the move along the floor (step::rolled())
  Ball& ball = balls_[i];
  ball.orientation = rolled(ball.orientation, normal, d, ball.radius);
}
}  // namespace ball_collision_sim::core
