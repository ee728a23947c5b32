// The step's own types and tunables, shared by the files of the step (src/core/step/):
// a ball's motion within the step, its counters, the directions it may not move along,
// and a predicted event. Not part of the public interface.
#pragma once

#include "step_context.hpp"

#include "contact_solver.hpp"

#include <cstdint>
#include <limits>

namespace ball_collision_sim::core
{
namespace step
{
/// A length [m] below the round-off of positions around p (with a ball of radius r):
/// where the corrections of a ball's motion on a curved floor are down to this, putting
/// it on the floor and out of what it leans on only trade round-off back and forth.
inline double roundoffAt(const Vec3& p, double r, const StepSettings& settings)
{
  return settings.roundoff_epsilons * std::numeric_limits<double>::epsilon() * (p.cwiseAbs().maxCoeff() + r);
}
}  // namespace step

/// The kind of path a ball's motion within the step follows, in the step fraction x
/// shared by all balls, from its start p0 at x0 with displacement b per unit of x. Each
/// kind names where the rest of its data is; the step asks a motion through
/// StepContext's kinematics (positionAt(), rateAt(), parabolaOf(), onFloorVelocity(),
/// inverseMass(); src/core/step/kinematics.cpp), which alone tell the kinds apart.
enum class MotionType : std::uint8_t
{
  /// c(x) = p0 + (x - x0) b: a line on a plane or without a floor, a chord between
  /// points of a curved floor (ending at chordEnd()), a still ball
  kLine,
  /// a member of a resting group: the chord its group's solve gave it (kLine's path),
  /// its velocity the group's spread impulses' (groupVelocityAt())
  kGrouped,
  /// no motion for the rest of the step, immovable (inverse mass 0): stopped by the
  /// event cap
  kCapped,
  /// no motion, immovable: the ball sleeps, until an impact or an edit wakes it
  kAsleep,
  /// dropped into a pocket: no motion, and nothing meets it for the rest of the step,
  /// at whose end it leaves the world
  kPocketed,
  /// a friction phase's chord on a curved floor, or a still phase's stay there: kLine's
  /// path, its velocity its phase's (SpinPhase::velocity()), not the free motion's
  kPhaseChord,
  // (the parabolas last, so that telling them from lines is one comparison)
  /// a free ball's parabola where the ground gives its path an acceleration a (a sloped
  /// plane, no floor): c(x) = p0 + (x - x0) b + (x - x0)^2 path_c_, path_c_ = a dt^2 / 2
  kPath,
  /// a friction phase's parabola on a plane: as kPath with the phase's own term
  /// (SpinMotion::c), its spin and end in SpinMotion
  kPhase,
  /// in flight: as kPath with gravity's term, flight_c_ = g dt^2 / 2; off the floor
  kFlight,
};

/// A ball's motion inside the current step: its start, its displacement and its kind
/// (MotionType); a new one starts at every event. It holds the rest of what detection
/// reads and the ball's counters in the step; the ball's record holds p0, its velocity at
/// x0 and its radius (startPosition(), startVelocity()).
struct StepState::Motion
{
  Motion() : events(0) {}
  double x0 = 0.0;               ///< where this motion starts, fraction of the step
  Vec3 b = Vec3::Zero();         ///< displacement per unit of x [m]; zero while frozen
  /// Bumped at every event of this ball: what was predicted before is stale. It counts
  /// from 0 each step; where it wraps, the queue forgets the ball's events (countEvent()).
  std::uint16_t epoch = 0;
  /// events of this ball in this step, up to one past the cap (kMaxEventCap)
  std::uint16_t events : 12;
  MotionType type = MotionType::kLine;

  /// No motion for the rest of the step, immovable: capped, asleep or pocketed.
  bool frozen() const
  {
    return type == MotionType::kCapped || type == MotionType::kAsleep || type == MotionType::kPocketed;
  }
  bool asleep() const { return type == MotionType::kAsleep; }
  /// Out of the step: dropped into a pocket (kPocketed).
  bool gone() const { return type == MotionType::kPocketed; }
  /// Its path is a parabola (kPath, kPhase, kFlight), not a line.
  bool accelerates() const { return type >= MotionType::kPath; }
  /// It moves as its resting group's solve says (kGrouped).
  bool followsGroup() const { return type == MotionType::kGrouped; }
  /// Starts a new path of this kind, unless the ball is frozen for the step.
  void become(MotionType kind)
  {
    if (!frozen())
      type = kind;
  }
};

inline Vec3 StepContext::positionAt(std::size_t i, double x) const
{
  const Motion& m = motions_[i];
  const Vec3 p = startPosition(i) + (x - m.x0) * m.b;
  if (!m.accelerates())
    return p;
  const double s = x - m.x0;
  return p + (s * s) * pathTerm(i);
}

inline Vec3 StepContext::predictedEnd(std::size_t i, const Vec3& p, const Vec3& v, double span, const Vec3& pull)
{
  // seed (1): ds = dt v + dt^2 g / 2, then back onto the floor, seed (2)-(4)
  const Vec3 q = p + span * v + (0.5 * span * span) * pull;
  return ground_.landKeepingFoot(q, balls_[i].radius, guessOf(i));
}

inline Vec3 StepContext::onFloorVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const
{
  const Motion& m = motions_[i];
  if (m.type == MotionType::kLine || m.type == MotionType::kPath)  // (a free line or path on the floor: the ground's)
  {
    Vec3 v;
    if (!flow_ends_.empty() && flowVelocity(i, x, position, normal, v))
      return v;  // (a chord's end on a curved floor, where its laws take it)
    return ground_.velocityAt(startVelocity(i), (x - m.x0) * dt_, startPosition(i), position, normal);
  }
  return motionVelocity(i, x, position, normal);
}

inline step::ExactSettings StepContext::exactSettings() const
{
  step::ExactSettings exact;
  exact.rounds = settings_.exact_solves;
  exact.regularization = settings_.exact_regularization;
  exact.refinements = settings_.exact_refinements;
  exact.pivot_tries = settings_.exact_pivot_tries;
  exact.interior_iterations = settings_.exact_interior_iterations;
  return exact;
}

/// The largest event cap a Motion's 12-bit count holds with one past it [events].
constexpr std::uint32_t kMaxEventCap = (1u << 12) - 2;

inline double StepContext::inverseMass(std::size_t i) const
{
  return motions_[i].frozen() ? 0.0 : 1.0 / balls_[i].mass;
}
inline double StepContext::groupInverseMass(std::size_t i, bool rolls) const
{
  if (motions_[i].frozen())
    return 0.0;
  return rolls ? 1.0 / ((1 + spins_[i].inertia) * balls_[i].mass) : 1.0 / balls_[i].mass;
}
/// A ball's friction phase in the step (worlds with friction), by visiting index: while
/// `free`, its motion's parabola term is c = a dt^2 / 2 and its spin at x is
/// w0 + alpha (x - x0) dt, until x_end, where the phase ends as `ends` says.
struct StepState::SpinMotion
{
  SpinMotion();  ///< kept (SpinPhase::kept())
  Vec3 w0 = Vec3::Zero();     ///< spin at the motion's start [rad/s]
  Vec3 alpha = Vec3::Zero();  ///< angular acceleration [rad/s^2]
  Vec3 a = Vec3::Zero();      ///< acceleration [m/s^2]
  Vec3 c = Vec3::Zero();      ///< a dt^2 / 2 [m]
  /// at the commit: the rotation over the step [rad]
  Vec3 turn = Vec3::Zero();
  double x_end = 2.0;         ///< where the phase ends (beyond 1: not in this step)
  MotionKind kind = MotionKind::kStationary;
  std::uint8_t ends = kPhaseRuns;
  /// How its motion and spin go in the step (src/core/step/spin_phase.hpp): kept,
  /// constrained, or a phase of its own (frictionless, still, driven).
  const SpinPhase* phase;
  double along_time = 0.0;   ///< [s]
  double normal_rate = 0.0;  ///< [rad/s^2]
  double normal_time = 0.0;  ///< [s]
  /// the kind clients last heard of (a transition is recorded where it changes)
  MotionKind reported = MotionKind::kStationary;
  /// the floor's normal the phase was found under
  Vec3 normal = Vec3::UnitZ();
  /// curved floors: the chord's pull, gravity and the phase's friction force per unit
  /// mass, in gravity's place (StepContext::pullOf()) [m/s^2]
  Vec3 pull = Vec3::Zero();
  /// curved floors, sliding: the slip at the start [m/s], the rate it falls at along its
  /// direction [m/s^2] and friction's deceleration mu_s g_n [m/s^2], for the energy the
  /// slip takes (StepContext::speedSquaredAt())
  double slip0 = 0.0;
  double slip_rate = 0.0;
  double slip_force = 0.0;
  /// curved floors, rolling: mu_r g_n [m/s^2]
  double roll_resistance = 0.0;
  /// a plane, sliding or rolling across its fall line: the phase's exact motion from its
  /// start (SpinPhase's turning type)
  TurningPhase turning;
};
}  // namespace ball_collision_sim::core
