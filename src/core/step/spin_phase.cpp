// The ways a ball's motion and spin go within the step under friction
// (StepState::SpinPhase): kept, constrained, rolled, frictionless, still, driven, turning.
// Reads motions_, spin_motions_, the start velocities, chord ends, gravity and the
// ground; starting a phase writes the ball's motion (through the floor's motion type,
// floor_motion_, where it depends on the floor).
#include "spin_phase.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
Vec3 StepState::SpinPhase::velocity(const StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& normal) const
{
  const Motion& m = w.motions_[i];
  return w.ground_.velocityAt(w.startVelocity(i), (x - m.x0) * w.dt_, w.startPosition(i), position, normal);
}

Vec3 StepState::SpinPhase::spinWith(const StepContext& w, std::size_t i, double x, const Vec3&, const Vec3&) const
{
  return spinAt(w.spin_motions_[i], (x - w.motions_[i].x0) * w.dt_);
}

double StepState::SpinPhase::kindFrom(const StepContext& w, std::size_t i, const SpinMotion&) const
{
  return w.motions_[i].x0;
}

double StepState::SpinPhase::chordSpeedSquared(const StepContext& w, std::size_t i, double rest, const Vec3& b) const
{
  return w.linearChordSpeedSquared(i, rest, b);
}

Vec3 StepState::SpinPhase::constantlyAccelerated(const StepContext& w, std::size_t i, double x)
{
  return w.startVelocity(i) + ((x - w.motions_[i].x0) * w.dt_) * w.spin_motions_[i].a;
}

StepState::SpinMotion::SpinMotion() : phase(&SpinPhase::kept()) {}

/// Kept: no motion of its own, its spin as it was.
struct StepState::SpinPhase::Kept final : StepState::SpinPhase
{
};

/// Constrained: its spin changes along the floor for along_time and about the normal for
/// normal_time; its kind at the end follows from its velocity and spin there.
struct StepState::SpinPhase::Constrained final : StepState::SpinPhase
{
  Vec3 spinAt(const SpinMotion& sm, double t) const override
  {
    return sm.w0 + std::min(t, sm.along_time) * sm.alpha + (std::min(t, sm.normal_time) * sm.normal_rate) * sm.normal;
  }
  /// (a slip its contacts left below what they resolve is none: FrictionLaw::settled())
  Vec3 spinWith(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v) const override
  {
    return w.frictionUnder(normal).settled(w.balls_[i].radius, v, spinAt(w.spin_motions_[i], (x - w.motions_[i].x0) * w.dt_));
  }
  MotionKind kindAtEnd(const StepContext& w, std::size_t i, const SpinMotion&, const Vec3& normal, const Vec3& v,
                       const Vec3& spin) const override
  {
    return w.frictionUnder(normal).constrainedKind(w.balls_[i].radius, v, spin);
  }
  /// (a slip ends where its spin reaches rolling's, a spin about the normal where it dies)
  double kindFrom(const StepContext& w, std::size_t i, const SpinMotion& sm) const override
  {
    const double x0 = w.motions_[i].x0;
    const double t = sm.reported == MotionKind::kSliding                                          ? sm.along_time
                     : sm.reported == MotionKind::kSpinning && sm.kind == MotionKind::kStationary ? sm.normal_time
                                                                                                   : 0.0;
    return std::min(1.0, x0 + t / w.dt_);
  }
};

/// Rolled: its spin along the floor is rolling's for its velocity, wherever an event or
/// the step's end finds it; about the normal it falls as a constrained one's.
struct StepState::SpinPhase::Rolled final : StepState::SpinPhase
{
  Vec3 spinAt(const SpinMotion& sm, double t) const override
  {
    return sm.w0 + (std::min(t, sm.normal_time) * sm.normal_rate) * sm.normal;
  }
  Vec3 spinWith(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v) const override
  {
    const SpinMotion& sm = w.spin_motions_[i];
    const Vec3 spin = spinAt(sm, (x - w.motions_[i].x0) * w.dt_);
    return normal.cross(v) / w.balls_[i].radius + spin.dot(sm.normal) * normal;
  }
  MotionKind kindAtEnd(const StepContext& w, std::size_t i, const SpinMotion&, const Vec3& normal, const Vec3& v,
                       const Vec3& spin) const override
  {
    return w.frictionUnder(normal).constrainedKind(w.balls_[i].radius, v, spin);
  }
};

/// Frictionless: a frictionless ball's motion (the caller gives it), its spin the phase's.
struct StepState::SpinPhase::Frictionless final : StepState::SpinPhase
{
  bool ownsMotion() const override { return true; }
  bool flowLaw(const StepContext&, std::size_t, FloorFlow::Law& law) const override
  {
    law = FloorFlow::Law{};  // (its spin stays; its spin's end about the normal is the phase's)
    return true;
  }
  bool rollsAtCommit(const SpinMotion& sm) const override { return sm.kind == MotionKind::kRolling; }
};

/// Friction acts on the motion: the phase's pull moves it.
struct StepState::SpinPhase::Forced : StepState::SpinPhase
{
  bool ownsMotion() const override { return true; }
  bool givesVelocity() const override { return true; }
  const Vec3& pull(const StepContext&, const SpinMotion& sm) const override { return sm.pull; }
  double chordSpeedSquared(const StepContext& w, std::size_t i, double rest, const Vec3& b) const override
  {
    return w.speedSquaredAt(i, w.chordEnd(i), w.startPosition(i) + rest * b);
  }
  bool rollsAtCommit(const SpinMotion& sm) const override { return sm.kind == MotionKind::kRolling; }
  bool rollsAtEvent(const SpinMotion& sm) const override { return sm.kind == MotionKind::kRolling; }
  /// (sliding and rolling: what the floor's motion type says the phase's energy is)
  double speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const override
  {
    const MotionKind kind = w.spin_motions_[i].kind;
    if (kind == MotionKind::kSliding || kind == MotionKind::kRolling)
      return w.floor_motion_->speedSquaredAt(w, i, x, p);
    return w.pulledSpeedSquared(i, p);
  }
};

/// Still (spinning or stationary): it stays where it is, its velocity the phase's.
struct StepState::SpinPhase::Still final : StepState::SpinPhase::Forced
{
  bool startMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override
  {
    return w.floor_motion_->stillMotion(w, i, law);
  }
  Vec3 velocity(const StepContext& w, std::size_t i, double x, const Vec3&, const Vec3&) const override
  {
    return constantlyAccelerated(w, i, x);
  }
};

/// Driven (sliding or rolling): its share of gravity and the friction force move it; its
/// velocity and the energy it has are the floor's motion type's to give.
struct StepState::SpinPhase::Driven final : StepState::SpinPhase::Forced
{
  bool startMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override
  {
    return w.floor_motion_->drivenMotion(w, i, law);
  }
  Vec3 velocity(const StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& normal) const override
  {
    return w.floor_motion_->phaseVelocity(w, i, x, position, normal);
  }
  /// (sliding or rolling, under the scene's coefficients)
  bool flowLaw(const StepContext& w, std::size_t i, FloorFlow::Law& law) const override
  {
    const MotionKind kind = w.spin_motions_[i].kind;
    if (kind != MotionKind::kRolling && kind != MotionKind::kSliding)
      return false;
    law.kind = kind == MotionKind::kRolling ? FloorFlow::Kind::kRolling : FloorFlow::Kind::kSliding;
    law.inertia = w.spins_[i].inertia;
    law.rolling = w.scene_.friction->rolling;
    law.sliding = w.scene_.friction->sliding;
    law.spinning = w.scene_.friction->spinning;
    return true;
  }
};

/// Turning (sliding or rolling across a plane's fall line): its TurningPhase's exact
/// motion and spin. Its path is the parabola from where it starts, at its velocity there,
/// to where that motion is when the phase or the step ends, whichever is first: the
/// phase's end, and the step's, find the ball where the closed form puts it.
struct StepState::SpinPhase::Turning final : StepState::SpinPhase::Forced
{
  bool startMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const override
  {
    Motion& m = w.motions_[i];
    SpinMotion& sm = w.spin_motions_[i];
    Vec3& v = w.startVelocity(i);
    v = law.along(v);
    m.b = w.dt_ * v;
    const double span = std::min(sm.x_end, 1.0) - m.x0;
    if (span > 0)
    {
      Vec3 velocity, move, spin_change;
      sm.turning.at(span * w.dt_, velocity, move, spin_change);
      sm.c = (move - span * m.b) / (span * span);
    }
    m.become(MotionType::kPhase);
    return false;
  }
  Vec3 spinAt(const SpinMotion& sm, double t) const override
  {
    // (the spin about the normal dies at its own rate, alpha's part along the normal)
    Vec3 velocity, move, spin_change;
    sm.turning.at(t, velocity, move, spin_change);
    return sm.w0 + (t * sm.alpha.dot(sm.normal)) * sm.normal + spin_change;
  }
  Vec3 velocity(const StepContext& w, std::size_t i, double x, const Vec3&, const Vec3&) const override
  {
    Vec3 velocity, move, spin_change;
    w.spin_motions_[i].turning.at((x - w.motions_[i].x0) * w.dt_, velocity, move, spin_change);
    return velocity;
  }
  double speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const override
  {
    return velocity(w, i, x, p, w.spin_motions_[i].normal).squaredNorm();
  }
};

const StepState::SpinPhase& StepState::SpinPhase::kept()
{
  static const Kept phase;
  return phase;
}

const StepState::SpinPhase& StepState::SpinPhase::constrained()
{
  static const Constrained phase;
  return phase;
}

const StepState::SpinPhase& StepState::SpinPhase::rolled()
{
  static const Rolled phase;
  return phase;
}

const StepState::SpinPhase& StepState::SpinPhase::of(const FrictionPhase& start, const FloorMotion& floor)
{
  static const Frictionless frictionless;
  static const Still still;
  static const Driven driven;
  static const Turning turning;
  if (start.conservative)
    return frictionless;
  if (start.turning.turns() && floor.followsTurns())
    return turning;
  if (start.gravity_share > 0)
    return driven;
  return still;
}
}  // namespace ball_collision_sim::core
