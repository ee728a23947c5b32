// Stage 5, commit: every ball to the step's end, back on the floor, its velocity
// there (solved across the step's resting contacts by the contact solver), its turn by
// rolling; and, while the visiting order stays, the next step's prediction. Reads
// motions_, step_starts_, the resting groups' links; writes balls_, feet_, the contact solver's
// work space.
#include "spin_model.hpp"
#include "floor_motion.hpp"
#include "contact_group.hpp"
#include "stages.hpp"
#include "flight.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <atomic>

namespace ball_collision_sim::core
{
using namespace step;

void step::commitToFloor(StepContext& c, bool predict_next)
{
  // Without resting contacts every ball is finished in one pass; with them, velocities
  // are settled across the contacts first.
  const bool settle = !c.links_.empty();
  if (predict_next)
    c.flights_ = 0;  // (counted again as the next step's motions are predicted)
  c.stats_.resting_contacts += c.links_.size();
  std::atomic<std::uint64_t> asleep{0};
  if (settle)
    c.floor_normals_.resize(c.balls_.size());
  // (each ball's commit, turn and next motion are its own: on the step's threads)
  c.forEachBall([&](std::size_t begin, std::size_t end) {
    std::uint64_t run_asleep = 0;
    for (std::size_t i = begin; i < end; ++i)
    {
      const StepContext::Committed done = c.commitBall(i, settle);
      if (!settle)
      {
        Ball& ball = c.balls_[i];
        ball.quiet_steps = 0;  // it leaned on nothing
        run_asleep += ball.asleep() ? 1 : 0;
        c.roll(i, done.normal, done.moved);
        if (predict_next)
          c.predictMotion(i);
      }
      else
        c.motions_[i].b = done.moved;  // the motion is done with: b keeps the step's move for roll()
    }
    asleep += run_asleep;
  });
  c.step_starts_.clear();  // (each ball's was taken back by its commit)
  if (!settle)
  {
    c.stats_.sleeping_balls = asleep;
    return;
  }
  c.separateAtEnd();
  c.settleRestingVelocities();
  c.boundGroupEnergies();
  c.forEachBall([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      c.roll(i, c.floor_normals_[i], c.motions_[i].b);
  });
  // Groups at rest sleep; where gravity does not pull along the floor, nothing gathers
  // balls into groups, and none does.
  if (StepState::FloorMotion::gathers(c))
    c.sleepStillGroups();
  if (predict_next)
    c.forEachBall([&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        c.predictMotion(i);
    });
}

StepContext::Committed StepContext::commitBall(std::size_t i, bool settle)
{
  Ball& ball = balls_[i];
  // (a ball asleep stays where it is, on the foot point it had; the floor's normal there
  // counts only across resting contacts: its spin is kept as it is, SpinPhase::kept())
  // (a chord that ends where its laws took the ball ends over the foot point they found)
  const Ground::End end = motions_[i].asleep() ? ground_.stillEnd(ball.position, ball.radius, guessOf(i), settle)
                          : ball.flying()      ? ground_.airEnd(positionAt(i, 1.0), guessOf(i))
                          : flowEndsAt(i, 1.0) ? Ground::End{positionAt(i, 1.0), flow_ends_[i].normal, guessOf(i)}
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
  // (a ball frozen by the event cap keeps no speed it does not move with)
  ball.velocity = onFloorVelocity(i, 1.0, end.centre, end.normal);
  spin_->commit(*this, i, end);
  ball.position = end.centre;
  // (a ball the floor cannot hold on its bend took off within the step: queueTakeOff())
  return {moved, end.normal};
}

void StepContext::settleRestingVelocities()
{
  // Resting contacts keep no closing speed into the step that follows.
  ContactGroup& group = endGroup();
  if (group.rows.empty())
    return;
  // (done where what closing is left is round-off of speeds, or of the closing there was)
  const double tolerance =
      std::max(settings_.resting_speed_floor, settings_.contact_tolerance * largestClosing(group.u, group.rows));
  const std::vector<Vec3> free = group.u;
  if (!solveContacts(group.u, group.inv_mass, group.rows, tolerance, settings_.contact_sweeps).converged &&
      !solveContactsExactly(free, group.inv_mass, group.rows, group.u, tolerance, exactSettings()))
    ++stats_.unsettled_contacts;
  for (std::size_t k = 0; k < group.size(); ++k)
  {
    // the impulses across the contacts may leave a velocity a part along the floor's
    // normal, which the floor takes (where speeds are the energy's, it keeps the speed)
    const std::size_t i = group.ballAt(k);
    const Vec3 before = balls_[i].velocity;
    balls_[i].velocity = ground_.turned(group.u[k], ground_.along(group.u[k], floor_normals_[i]));
    spin_->settle(*this, i, balls_[i].velocity - before, floor_normals_[i]);
  }
}

void StepContext::roll(std::size_t i, const Vec3& normal, const Vec3& d)
{
  spin_->roll(*this, i, normal, d);
}
}  // namespace ball_collision_sim::core
