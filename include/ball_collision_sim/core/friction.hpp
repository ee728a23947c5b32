#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/turning_drag.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <cstdint>

namespace ball_collision_sim::core
{
/// How a ball moves on the floor (pooltool's motion states).
enum class MotionKind : std::uint8_t
{
  kSliding,     ///< its contact point slips on the floor
  kRolling,     ///< moving without slip
  kSpinning,    ///< still, turning about the floor's normal only
  kStationary,  ///< still, not turning
  kFlying,      ///< off the floor, on its parabola under gravity
};
/// "sliding", "rolling", "spinning", "stationary", "flying"
const char* motionKindName(MotionKind kind);

/// What ends a phase of constant accelerations (bits; several may end at once).
enum PhaseEnd : std::uint8_t
{
  kPhaseRuns = 0,
  kSlipStops = 1,  ///< the contact point's slip reaches zero
  kBallStops = 2,  ///< the ball's velocity reaches zero
  kSpinStops = 4,  ///< the spin about the floor's normal reaches zero
  /// (a motion integrated on a curved floor, FloorFlow) the floor would have to pull the
  /// ball to keep it on its bend: it leaves the floor
  kTakesOff = 8,
};

/// A sliding or rolling phase on a tilted plane whose direction turns: the slip (sliding)
/// or the velocity (rolling) crosses gravity's line along the plane, and friction's
/// direction turns with it toward the fall line. Exact, from the drag of that slip or
/// velocity (TurningDrag): with q the slip or the velocity,
///   v(t) = v0 + t drift + share (q(t) - q0),
///   p(t) - p0 = t v0 + t^2 drift / 2 + share (Q(t) - t q0),
/// sliding: drift = g_t / (1 + k), share = k / (1 + k); rolling: q = v, drift 0, share 1;
/// the spin along the plane changes by n x (dv - slip_share dq) / r (slip_share 1
/// sliding, 0 rolling), which keeps a rolling ball rolling and a sliding one's slip q.
struct TurningPhase
{
  TurningDrag drag;
  Vec3 q0 = Vec3::Zero();
  Vec3 v0 = Vec3::Zero();
  Vec3 drift = Vec3::Zero();
  double share = 1.0;
  double slip_share = 0.0;
  Vec3 normal = Vec3::UnitZ();
  double radius = 1.0;

  bool turns() const { return drag.turns(); }
  /// t seconds into the phase (t up to its end): the velocity, the move from its start
  /// and the change of the spin along the plane.
  void at(double t, Vec3& velocity, Vec3& move, Vec3& spin_change) const;
};

/// A stretch of a ball's motion on a plane under the friction laws, with constant
/// linear and angular acceleration, up to the first transition; or, where its direction
/// turns across a tilted plane, `turning`'s exact motion (its acceleration then the one
/// at its start).
struct FrictionPhase
{
  MotionKind kind = MotionKind::kSliding;
  Vec3 acceleration = Vec3::Zero();          ///< [m/s^2], along the floor
  Vec3 angular_acceleration = Vec3::Zero();  ///< [rad/s^2]
  double duration = 0.0;                     ///< [s] until `ends`; infinite where nothing ends it
  std::uint8_t ends = kPhaseRuns;            ///< PhaseEnd bits
  /// No friction force acts (its acceleration is gravity's along the floor): the motion
  /// is a frictionless ball's, and keeps its energy as one does.
  bool conservative = false;
  /// The part of gravity along the floor in the acceleration: 1 sliding, 1 / (1 + k)
  /// rolling (the rest turns the ball), 0 still; the rest of the acceleration is
  /// friction's. On a curved floor the chord is pulled by this part of gravity itself.
  double gravity_share = 1.0;
  /// Sliding: the direction the slip's friction opposes (unit, along the floor).
  Vec3 slip_direction = Vec3::Zero();
  /// Sliding or rolling across a tilted plane's fall line: the exact motion (turns()),
  /// whose end is `duration`.
  TurningPhase turning;
};

/// The friction laws of a ball of radius r and inertia k m r^2 on a floor with unit normal
/// n (against gravity) under gravity g; g_n = -<g, n>, g_t = g + g_n n, slip u = v + r n x w.
///   sliding:    dv/dt = g_t - mu_s g_n u/|u|,  dw/dt = (mu_s g_n / (k r)) n x u/|u|
///   rolling:    dv/dt = g_t / (1 + k) - mu_r g_n v/|v|,  w = n x v / r + (w.n) n
///   stationary: while |g_t| / (1 + k) <= mu_r g_n
///   spin about n decays at mu_sp g_n / (k r) in every state.
/// On a plane square to gravity and along a tilted plane's fall line the slip's and the
/// velocity's directions stay, and the accelerations are constant; across the fall line
/// they turn toward it, and the phase's `turning` holds its exact motion (TurningDrag).
class FrictionLaw
{
public:
  /// `along`: gravity's part along the floor, as the floor gives it (zero where it is
  /// round-off), so that a motion without friction force is a frictionless ball's.
  /// `still_speed` [m/s]: speeds (and r times spins) below it are round-off of zero, where
  /// a relative tolerance says nothing (StepSettings::resting_speed_floor).
  FrictionLaw(const FrictionDef& mu, const Vec3& normal, const Vec3& gravity, const Vec3& along, double slip_tolerance,
              double still_speed);

  /// The phase that starts from (v, w). A slip below slip_tolerance of the ball's speeds
  /// is taken away (by the sticking impulse, as at the end of a sliding phase, where
  /// there is sliding friction) and a rolling ball's spin made exactly
  /// n x v / r + (w.n) n, so v and w may change. A spin about n below slip_tolerance of
  /// |w| + |v| / r is none (round-off of the projection that ended it); so are a velocity
  /// and a spin along the floor both below still_speed (and r w).
  FrictionPhase start(double k, double r, Vec3& v, Vec3& w) const;
  /// How the spin of a ball whose motion its contacts decide (leaning on a wall or in a
  /// pile; v its velocity there) changes: friction's torque turns its spin along the floor
  /// toward rolling's, n x v / r, at mu_s g_n / (k r), where that does not raise its
  /// energy (|n x v / r| at most the spin's), until it gets there; the spin about n dies
  /// as always. The force's linear part goes into the contacts. The spin's change does not
  /// change the ball's path, so its ends are not events: the spin after t is
  /// w + min(t, along_time) along_rate + min(t, normal_time) normal_rate n.
  struct ConstrainedSpin
  {
    Vec3 along_rate = Vec3::Zero();  ///< [rad/s^2]
    double along_time = 0.0;         ///< [s]
    double normal_rate = 0.0;        ///< [rad/s^2]
    double normal_time = 0.0;        ///< [s]
  };
  ConstrainedSpin constrained(double k, double r, const Vec3& v, Vec3& w) const;
  /// The kind of a ball whose contacts decide its motion, from its velocity and spin: its
  /// contacts settle velocities to the still speed, and a slip below that is theirs ...
  MotionKind constrainedKind(double r, const Vec3& v, const Vec3& w) const;
  /// ... and its spin w with such a slip taken away (rolling's, its spin about the
  /// normal kept); a larger slip is friction's to take.
  Vec3 settled(double r, const Vec3& v, const Vec3& w) const;
  /// Rolling's spin for velocity v: n x v / r, and about n the spin wn, cut where it would
  /// make |w| larger than the spin w it replaces; w itself where n x v / r alone would
  /// (the velocity changed since w was rolling's: a slip).
  Vec3 rollingSpin(double r, const Vec3& v, const Vec3& w, double wn) const;
  /// The motion kind start() would give, without changing anything.
  MotionKind kindOf(double k, double r, const Vec3& v, const Vec3& w) const;
  /// The state at a phase's end made exact: slip 0 by the impulse at the contact point
  /// that stops it (which keeps the angular momentum about that point and loses energy),
  /// velocity 0 (and the spin of rolling with it), spin about n 0, as `ends` says. A
  /// velocity left by the sticking impulse below slip_tolerance of `speeds`, the ball's
  /// speeds at the phase's start (speeds()), is round-off of a ball
  /// stopping dead (a stop shot): it is 0.
  void finish(std::uint8_t ends, double k, double r, double speeds, Vec3& v, Vec3& w) const;
  /// |v| + r |w|: the speeds of the ball's surface, what slip_tolerance is a part of (a
  /// spin about a normal off by round-off makes a slip of round-off of r |w|) [m/s].
  double speeds(double r, const Vec3& v, const Vec3& w) const { return v.norm() + r * w.norm(); }
  /// The contact point's slip on the floor, v + r n x w (v's part along the floor: a
  /// normal part of round-off is the floor's, not a slip).
  Vec3 slip(double r, const Vec3& v, const Vec3& w) const { return along(v) + r * normal_.cross(w); }
  /// x less its part along n.
  Vec3 along(const Vec3& x) const { return x - x.dot(normal_) * normal_; }
  const Vec3& normal() const { return normal_; }
  /// Gravity along the floor, g_t [m/s^2].
  const Vec3& gravityAlong() const { return g_t_; }
  /// Rolling resistance's deceleration of a rolling ball, mu_r g_n [m/s^2].
  double rollingResistance() const { return mu_.rolling * g_n_; }
  /// Friction grips a ball of inertia k here, so that it rolls rather than slides: there is
  /// sliding friction, and it holds rolling against gravity along the floor,
  /// k |g_t| / (1 + k) <= mu_s g_n.
  bool holdsRolling(double k) const
  {
    return mu_.sliding > 0 && k * g_t_.norm() / (1 + k) <= mu_.sliding * g_n_;
  }
  /// There is sliding friction: spin and motion exchange energy.
  bool grips() const { return mu_.sliding > 0; }

private:
  /// A constrained ball's slip is more than its contacts resolve (constrainedKind()).
  bool slipsBeyondContacts(double r, const Vec3& v, const Vec3& w) const;
  /// Removes slip u by the impulse at the contact point that stops it.
  void stick(double k, double r, Vec3& v, Vec3& w) const;
  FrictionPhase sliding(double k, double r, const Vec3& u_direction, double u_norm) const;
  FrictionPhase rolling(double k, double r, const Vec3& v, const Vec3& direction) const;
  /// Where a sliding phase's slip or a rolling one's velocity q0 crosses the fall line:
  /// `phase` made TurningPhase's exact motion from v0, its end the drag's.
  void turn(const Vec3& q0, const Vec3& v0, double k, double r, FrictionPhase& phase) const;
  /// w.n, or 0 (and w made so) where it is round-off.
  double spinAboutNormal(double r, const Vec3& v, Vec3& w) const;
  /// Adds the decay of the spin about n to `phase`.
  void spinDecay(double k, double r, double wn, FrictionPhase& phase) const;

  FrictionDef mu_;
  Vec3 normal_;
  double g_n_;   ///< gravity into the floor [m/s^2]; friction forces scale with it
  Vec3 g_t_;     ///< gravity along the floor [m/s^2]
  double slip_tolerance_;
  double still_speed_;  ///< [m/s]
};

/// The tangential impulse of an impact, in the contact's tangent plane (unit t1, t2): the
/// touching points slip at `slip`, and an impulse J1 t1 + J2 t2 changes their slip by
/// `response` (J1, J2) (symmetric, positive definite: each body's 1/m along what it can
/// move along, plus 1/(k m)). It is the impulse that stops the slip, or where that is more
/// than mu times the normal impulse, that impulse scaled down to it: never more than
/// stops it, so it never makes energy [N s].
Vec3 tangentialImpulse(const Vec3& slip, const Vec3& t1, const Vec3& t2, const Mat2& response, double mu,
                       double normal_impulse);
}  // namespace ball_collision_sim::core
