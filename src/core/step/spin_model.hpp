// A ball's spin within the step, as a type the scene's friction provides: what the step
// asks of a ball that depends on whether friction acts. Two types:
// - RollingSpin (no `friction` in the scene): a ball's spin is not its own. On the floor
//   it turns by rolling without slip along its path, in flight it does not turn; its
//   velocity is its free motion's, and no impact has a tangential part.
// - FrictionSpin: each ball keeps its spin (spins_) and, within the step, a phase of the
//   friction laws (spin_motions_, SpinPhase) that gives its velocity, what pulls its
//   chord, its energy and where its phase ends; impacts and landings have friction's
//   tangential impulse, and its kind (sliding, rolling, ...) is reported as it changes.
// The stages call it where a ball's spin is read or written, never branching on
// friction themselves. Reads and writes the StepContext's per-ball data.
#pragma once

#include "step_context.hpp"

#include <string>

namespace ball_collision_sim::core
{
struct StepState::SpinModel
{
  virtual ~SpinModel() = default;
  /// The spin type of a scene with (or without) friction.
  static const SpinModel& of(bool friction);

  // The balls' records (load, edits).
  /// Each loaded ball's spin from its definition (the scene's, or a random ball's), where
  /// its record has it now, on its foot point.
  virtual void makeSpins(StepContext& c, const std::vector<Vec2>& feet) const = 0;
  /// Room for one more ball (before any record is pushed, so that the pushes cannot throw).
  virtual void reserveOne(StepContext& c) const = 0;
  /// Spin of a ball added with this definition, or one whose slot s is set anew.
  virtual void addSpin(StepContext& c, const BallDef& placed, const Vec2& foot, bool flying) const = 0;
  virtual void setSpin(StepContext& c, std::size_t s, const BallDef& def, const Vec2& foot, bool flying) const = 0;
  /// A strike of ball s by `impulse` at `offset` from its centre, leaving it with
  /// `velocity` (in flight or not): the spin it gives, or why it is refused (then nothing
  /// changes).
  virtual std::string strike(StepContext& c, std::size_t s, const Vec3& impulse, const Vec3& offset,
                             const Vec3& velocity, bool flying) const = 0;
  /// Ball s's spin, kind of motion and inertia factor k (I = k m r^2) as World reports them.
  virtual Vec3 angularVelocity(const StepContext& c, std::size_t s) const = 0;
  virtual MotionKind kindOnFloor(const StepContext& c, std::size_t s) const = 0;
  virtual double inertia(const StepContext& c, std::size_t s) const = 0;

  // The step's motions.
  /// The step's per-ball spin data, for every ball (predictMotions()).
  virtual void startStep(StepContext& c) const = 0;
  /// Ball i's spin at its prediction: asleep; in flight (before its take-off or flight
  /// starts); on the floor, where its phase may make its motion (returns whether the
  /// floor's type is to predict it).
  virtual void predictAsleep(StepContext& c, std::size_t i) const = 0;
  virtual void predictFlight(StepContext& c, std::size_t i) const = 0;
  /// Ball i's motion on the floor over the step, and its spin: returns whether the
  /// floor's type made it (its free path or chord), not its friction phase.
  virtual bool predictOnFloor(StepContext& c, std::size_t i) const = 0;
  /// Ball i's new motion on the floor from x at `position` (startMotion()), its velocity
  /// startVelocity(i): its friction phase's, or the floor's type's path or chord (which,
  /// where a phase gives its velocity, is a MotionType::kPhaseChord).
  virtual void startOnFloor(StepContext& c, std::size_t i, double x, const Vec3& position, bool impact) const = 0;
  /// Ball i has no motion of its own from now in the step (frozen, or its group's to
  /// come): its spin stays as it is.
  virtual void hold(StepContext& c, std::size_t i) const = 0;
  /// The event cap stopped ball i for the rest of the step, spin and all.
  virtual void cap(StepContext& c, std::size_t i) const = 0;
  /// Ball i's motion is its resting group's, in which it rolls (`rolls`: the group moved it
  /// as a rolling mass) or not; or it stopped where its energy ran out.
  virtual void followGroup(StepContext& c, std::size_t i, bool rolls) const = 0;
  virtual void stop(StepContext& c, std::size_t i) const = 0;
  /// Ball i flies from now in the step (startFlight()), or leaves the floor at x (liftOff(),
  /// `flew`: it was in flight already).
  virtual void startFlight(StepContext& c, std::size_t i) const = 0;
  virtual void liftOff(StepContext& c, std::size_t i, double x, bool flew) const = 0;
  /// |v|^2 of ball i at x where its motion is at p, from its energy; what pulls its chord
  /// [m/s^2]; a chord's end speed squared with displacement b over `rest` of the step.
  virtual double speedSquaredAt(const StepContext& c, std::size_t i, double x, const Vec3& p) const = 0;
  /// On a curved floor: the law ball i's motion follows, where FloorFlow integrates it
  /// (a free ball's, a rolling one's); false where its chord is the first-order one.
  virtual bool flowLaw(const StepContext& c, std::size_t i, FloorFlow::Law& law) const = 0;
  virtual const Vec3& pull(const StepContext& c, std::size_t i) const = 0;
  virtual double chordSpeedSquared(const StepContext& c, std::size_t i, double rest, const Vec3& b) const = 0;
  /// Queues the end of ball i's phase where it falls within the step.
  virtual void queueEnd(StepContext& c, std::size_t i) const = 0;
  /// At ball i's motion's end at the event, where it has velocity v on the floor with
  /// this normal: its spin there, and at its phase's end the phase's end made exact.
  virtual void endMotion(StepContext& c, const Event& event, const Vec3& normal, Vec3& v) const = 0;
  /// Ball i's spin where it leaves the floor at x with velocity v under `normal`.
  virtual void takeOff(StepContext& c, std::size_t i, double x, const Vec3& normal, const Vec3& v) const = 0;

  // Impacts.
  /// An impact with a wall at x (n toward it, `before`: the velocity before, v after
  /// the normal impulse), and between two balls (the velocities before and after).
  virtual void wallImpact(StepContext& c, std::size_t i, double x, const Vec3& n, const Vec3& floor_normal,
                          double impulse, const Vec3& before, Vec3& v) const = 0;
  virtual void pairImpact(StepContext& c, const StepContext::PairContact& pair, double x, double impulse, const Vec3& va_before,
                          const Vec3& vb_before, Vec3& va, Vec3& vb) const = 0;
  /// A landing at x under the floor's normal n with this normal impulse (v after it);
  /// then, `lands`: whether the ball stays on the floor with velocity v.
  virtual void landingImpact(StepContext& c, std::size_t i, double x, const Vec3& n, double normal_impulse,
                             Vec3& v) const = 0;
  virtual void landed(StepContext& c, std::size_t i, double x, const Vec3& v) const = 0;

  // The step's end.
  /// Ball i's spin and kind where the step ends it at `end` with its velocity; its turn
  /// over the step, by the move d along the floor under `normal`.
  virtual void commit(StepContext& c, std::size_t i, const Ground::End& end) const = 0;
  virtual void roll(StepContext& c, std::size_t i, const Vec3& normal, const Vec3& d) const = 0;
  /// The kinetic energy of ball i's spin that counts as the ball's (where friction grips)
  /// [J], and that spin scaled by `scale`.
  virtual double spinEnergy(const StepContext& c, std::size_t i) const = 0;
  /// energies[i] += spinEnergy(i) for every ball.
  virtual void addSpinEnergies(const StepContext& c, std::vector<double>& energies) const = 0;
  /// The step's end changed ball i's velocity by `change` across its resting contacts
  /// (settleRestingVelocities()), on the floor with this normal: where the contacts move
  /// it as a rolling mass, the floor's grip turns its spin with it and its slip stays.
  virtual void settle(StepContext& c, std::size_t i, const Vec3& change, const Vec3& normal) const = 0;
  virtual void scaleSpin(StepContext& c, std::size_t i, double scale) const = 0;
  /// Ball i in a resting group under the floor's normal n rolls (friction holds it so).
  virtual bool rollsInGroup(const StepContext& c, std::size_t i, const Vec3& n) const = 0;
};
}  // namespace ball_collision_sim::core
