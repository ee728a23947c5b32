// How a ball's motion and spin go within the step in a world with friction, as a type
// (SpinMotion::phase): what depends on it is asked of the type, not branched on in the
// step's stages. The types:
// - Kept: no motion of its own (frozen by the event cap, or asleep); its spin stays.
// - Constrained: its contacts decide its motion (held, or kept out of blocked
//   directions); friction acts on its spin only (FrictionLaw::constrained()).
// - Rolled: a resting group's member that the group moves as a rolling mass (its floor
//   friction holds rolling): it rolls with the group's velocity wherever it is, under the
//   normal there; its spin about the normal dies as a constrained one's.
// - Frictionless: a friction phase without friction force; its velocity is a
//   frictionless ball's.
// - Still: a phase that holds the ball where it is (spinning or stationary); no share of
//   gravity moves it.
// - Driven: a phase its share of gravity and the friction force move (sliding, rolling).
// - Turning: a driven phase on a plane whose direction turns across the fall line; its
//   motion and spin are its TurningPhase's, exactly, and its path the parabola that
//   meets that motion where the phase or the step ends.
// Reads motions_, spin_motions_, the start velocities, chord ends, gravity and the
// ground; starting a phase writes the ball's motion (through floor_motion_).
#pragma once

#include "floor_motion.hpp"

namespace ball_collision_sim::core
{
struct StepState::SpinPhase
{
  virtual ~SpinPhase() = default;
  static const SpinPhase& kept();
  static const SpinPhase& constrained();
  static const SpinPhase& rolled();
  /// The phase `start` found on the floor whose motion type is `floor`: frictionless,
  /// still, driven, or turning.
  static const SpinPhase& of(const FrictionPhase& start, const FloorMotion& floor);
  /// Ball i's velocity at x under its phase's constant acceleration (SpinMotion::a): a
  /// still phase's anywhere, a driven one's on a plane.
  static Vec3 constantlyAccelerated(const StepContext& w, std::size_t i, double x);

  /// Its motion follows a friction phase (else its contacts', or none): a phase that
  /// ends within the step is an event, and a contact that takes the motion over takes
  /// the spin over too (StepContext::constrainSpin()).
  virtual bool ownsMotion() const { return false; }
  /// The ball's spin t seconds into its motion.
  virtual Vec3 spinAt(const SpinMotion& sm, double t) const { return sm.w0 + t * sm.alpha; }
  /// Ball i's spin at x where its velocity is then v, under `normal`: spinAt()'s, but for
  /// a phase whose spin follows its velocity.
  virtual Vec3 spinWith(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v) const;
  /// Gives ball i the motion of its new phase under `law` (StepContext::startFriction()); true
  /// where the caller is to give it a frictionless ball's motion, or the chord under
  /// SpinMotion::pull on a curved floor.
  virtual bool startMotion(StepContext&, std::size_t, const FrictionLaw&) const { return true; }
  /// Its velocity (and pull) are the phase's own, not a free ball's: a chord the floor's
  /// type makes for it is a MotionType::kPhaseChord.
  virtual bool givesVelocity() const { return false; }
  /// What pulls the ball's motion [m/s^2]: gravity, or with friction acting on the
  /// motion the phase's pull (gravity's share and the friction force).
  virtual const Vec3& pull(const StepContext& w, const SpinMotion&) const { return w.gravity_; }
  /// Ball i's velocity at x, at `position` on the floor with this normal.
  virtual Vec3 velocity(const StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& normal) const;
  /// |v|^2 of ball i at x where its motion is at p, from the energy.
  virtual double speedSquaredAt(const StepContext& w, std::size_t i, double, const Vec3& p) const
  {
    return w.pulledSpeedSquared(i, p);
  }
  /// On a curved floor: the law FloorFlow integrates its motion by (false: the chord
  /// under pull(), of first order).
  virtual bool flowLaw(const StepContext&, std::size_t, FloorFlow::Law&) const { return false; }
  /// |v|^2 where ball i's chord b ends, `rest` of the step on (StepContext::EnergyCheck).
  virtual double chordSpeedSquared(const StepContext& w, std::size_t i, double rest, const Vec3& b) const;
  /// Its spin rolls the ball where it ends the step (under the normal there) ...
  virtual bool rollsAtCommit(const SpinMotion&) const { return false; }
  /// ... and where an event finds it.
  virtual bool rollsAtEvent(const SpinMotion&) const { return false; }
  /// The kind it ends the step in, where its velocity is v and its spin w under `normal`.
  virtual MotionKind kindAtEnd(const StepContext&, std::size_t, const SpinMotion& sm, const Vec3&, const Vec3&,
                               const Vec3&) const
  {
    return sm.kind;
  }
  /// Where in the step (a fraction) ball i came to the kind it ends the step in, a kind
  /// its events did not report: where its motion started, or where its spin's change ran
  /// out.
  virtual double kindFrom(const StepContext& w, std::size_t i, const SpinMotion&) const;

private:
  struct Kept;
  struct Constrained;
  struct Rolled;
  struct Frictionless;
  struct Forced;
  struct Still;
  struct Driven;
  struct Turning;
};
}  // namespace ball_collision_sim::core
