// A ball's motion on the ground within the step, as a type the ground provides: what
// the step asks of a motion that depends on the kind of floor. Three types:
// - ExactMotion (a level plane): a free ball's path is exact, a line; a ball under its
//   contacts moves on a chord in the plane, and its energy is linear along the chord.
// - PathMotion (a sloped plane, or no floor): the same, but a free ball's exact path is
//   a parabola under gravity's part along the plane (MotionType::kPath).
// - ChordMotion (a curved floor): every motion is a chord between points of the floor,
//   no longer than the floor allows, and kept within the ball's energy (cut where the
//   energy runs out, or stopped where that is at once); friction laws are taken under the normal
//   where the ball is.
// A new kind of motion is a new type here, not a branch in the step's stages.
// Reads and writes what the StepContext's stages give it (motions_, spin_motions_, the motions' starts).
#pragma once

#include "step_types.hpp"

namespace ball_collision_sim::core
{
struct StepState::FloorMotion
{
  virtual ~FloorMotion() = default;
  /// The motion type of this ground.
  static const FloorMotion& of(const Ground& ground);

  /// Balls keep foot points (StepContext::feet_) between steps, as Newton's first guess.
  virtual bool keepsFeet() const = 0;
  /// A motion's end is put back on the floor (a chord across a curved one): a group's
  /// solved motions are, and its contacts' linearization is corrected where they end.
  virtual bool endsPutOnFloor() const = 0;
  /// A phase whose direction turns across a plane's fall line (TurningPhase) follows its
  /// exact motion (a plane's); else its start's accelerations (a curved floor's chord,
  /// under the normal where it is).
  virtual bool followsTurns() const = 0;
  /// Gravity pulls balls along the floor, so that they gather into groups at rest.
  static bool gathers(const StepContext& w) { return !w.ground_.straight(); }

  /// Ball i's free motion over the next step, from startPosition(i) with velocity v (no
  /// friction phase set it).
  virtual void predict(StepContext& w, std::size_t i, const Vec3& v) const = 0;
  /// Ball i's motion from x on, from `position` with start velocity v0 after a contact
  /// has redirected it.
  virtual void start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const = 0;

  // Friction.
  /// The friction laws under the floor's normal n.
  virtual FrictionLaw lawUnder(const StepContext& w, const Vec3& n) const = 0;
  /// A rolling ball that was not hit starts its next phase under `law`'s normal: its
  /// spin then (SpinMotion::w0).
  virtual void rollOn(StepContext& w, std::size_t i, const FrictionLaw& law) const = 0;
  /// After startFriction() has set a driven phase (sliding, rolling): its motion where
  /// the phase gives it one (returns false), or true where the caller is to move it as
  /// the chord under SpinMotion::pull.
  virtual bool drivenMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const = 0;
  /// The same for a still phase (spinning, stationary).
  virtual bool stillMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const = 0;
  /// Ball i's velocity at x, at `position` on the floor with this normal, in a driven
  /// phase.
  virtual Vec3 phaseVelocity(const StepContext& w, std::size_t i, double x, const Vec3& position,
                             const Vec3& normal) const = 0;
  /// |v|^2 of ball i at x where its motion is at p, from the energy (StepContext::speedSquaredAt()).
  virtual double speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const = 0;
  /// Ball i's spin at x (an event or the step's end), where its velocity is v under
  /// `normal`, from its phase's spin there; `rolling`: its phase rolls.
  virtual Vec3 spinThere(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v,
                         const Vec3& spin, bool rolling) const = 0;
};

struct StepState::ExactMotion : StepState::FloorMotion
{
  bool keepsFeet() const override { return false; }
  bool endsPutOnFloor() const override { return false; }
  bool followsTurns() const override { return true; }
  void predict(StepContext& w, std::size_t i, const Vec3& v) const override;
  void start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const override;
  FrictionLaw lawUnder(const StepContext& w, const Vec3& n) const override;
  void rollOn(StepContext&, std::size_t, const FrictionLaw&) const override {}
  bool drivenMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override;
  bool stillMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override;
  Vec3 phaseVelocity(const StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& normal) const override;
  double speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const override;
  Vec3 spinThere(const StepContext&, std::size_t, double, const Vec3&, const Vec3&, const Vec3& spin, bool) const override
  {
    return spin;
  }
};

struct StepState::PathMotion final : StepState::ExactMotion
{
  void predict(StepContext& w, std::size_t i, const Vec3& v) const override;
  void start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const override;
};

struct StepState::ChordMotion final : StepState::FloorMotion
{
  bool keepsFeet() const override { return true; }
  bool endsPutOnFloor() const override { return true; }
  bool followsTurns() const override { return false; }
  void predict(StepContext& w, std::size_t i, const Vec3& v) const override;
  void start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const override;
  FrictionLaw lawUnder(const StepContext& w, const Vec3& n) const override;
  void rollOn(StepContext& w, std::size_t i, const FrictionLaw& law) const override;
  bool drivenMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override;
  bool stillMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override;
  Vec3 phaseVelocity(const StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& normal) const override;
  double speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const override;
  Vec3 spinThere(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v, const Vec3& spin,
                 bool rolling) const override;

private:
  /// Shortens ball i's chord where its end would lie higher than its energy reaches.
  static void keepEnergy(StepContext& w, std::size_t i);
  /// Cuts ball i's chord where its speed runs out, `start` and `full` its speed squared
  /// at the chord's start and end (full < 0); a motion whose energy runs out at once
  /// slides downhill as far as it can, or the ball stops (StepContext::stop()).
  static void shorten(StepContext& w, std::size_t i, const StepContext::EnergyCheck& energy, double start, double full);
  /// Where on its chord (a fraction in [0, 1]) the ball's speed runs out.
  static double energyRunsOut(const StepContext& w, const StepContext::EnergyCheck& energy, double start, double full);
  /// A motion starting above or below the floor where the energy does not reach: the
  /// ball slides downhill as far as it takes, or is held.
  static void slideDownhill(StepContext& w, const StepContext::EnergyCheck& energy, double start);
};
}  // namespace ball_collision_sim::core
