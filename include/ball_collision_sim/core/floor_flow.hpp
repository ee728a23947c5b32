#pragma once

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/friction.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <cstdint>

namespace ball_collision_sim::core
{
/// A ball on a curved floor as its laws move it, integrated: the foot point (u, v) whose
/// centre is S + r n, the centre's velocity along the floor, and the ball's spin. The
/// acceleration is the law's along the floor, a_t, and the floor's push along n that keeps
/// the centre on its surface, (v . L (I - r L)^-1 v) n, L the floor's shape operator
/// (Weingarten's, I^-1 II in the basis (S_u, S_v)): a ball moving at speed s over a bowl of
/// radius R is pushed at s^2 / (R - r). The foot moves at (I - r II)^-1 (S_u . v, S_v . v).
/// The laws (docs/physics.md, under the normal where the ball is, g_n = -g . n):
///   free:    a_t = g_t; the spin stays;
///   rolling: a_t = g_t / (1 + k) - mu_r g_n v/|v|; the spin n x v / r + w_n n;
///   sliding: a_t = g_t - mu_s g_n u/|u|, the spin along the floor w_t turned by
///            (mu_s g_n / (k r)) n x u/|u| and carried along the floor as n turns, u = v +
///            r n x w_t the contact point's slip;
/// and in both the spin about the normal w_n falls at mu_sp g_n / (k r) to 0 (a turning
/// normal carries the spin along the floor with it, and leaves w_n as it is).
/// Classical Runge-Kutta of fourth order. A sliding phase ends where the slip reaches 0,
/// a rolling one where the velocity does, either where the spin about the normal does;
/// each is found by steps of half the time the rates there give it (so that no step
/// crosses it, where the laws turn), down to 1e-12 of the quantity's scale. Any law's
/// motion ends where the floor would have to pull the ball to keep it (its support, the
/// push less gravity's pull along n, falls below zero, as over a crest): found by
/// halving the step that crossed it, to within 1e-12 s, on the side past it.
class FloorFlow
{
public:
  enum class Kind : std::uint8_t
  {
    kFree,
    kRolling,
    kSliding,
  };
  struct Law
  {
    Kind kind = Kind::kFree;
    double inertia = 0.0;   ///< k
    double rolling = 0.0;   ///< mu_r
    double sliding = 0.0;   ///< mu_s
    double spinning = 0.0;  ///< mu_sp

    /// No drag takes energy: a free ball's law, or a rolling one's without rolling
    /// resistance (its speed is then its energy's).
    bool keepsEnergy() const { return kind == Kind::kFree || (kind == Kind::kRolling && !(rolling > 0)); }
  };
  struct State
  {
    Vec2 foot = Vec2::Zero();
    Vec3 velocity = Vec3::Zero();
    Vec3 spin = Vec3::Zero();  ///< sliding: the spin along the floor; free: kept as it is
    double spin_n = 0.0;       ///< rolling, sliding: the spin about the normal
  };
  /// Where an advance() ended: the centre, the floor's normal, the time taken [s] and what
  /// ended the phase there (PhaseEnd bits; kPhaseRuns where the time ran out).
  struct End
  {
    Vec3 centre = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
    double time = 0.0;
    std::uint8_t ends = kPhaseRuns;
  };

  FloorFlow(const Floor& floor, const Vec3& gravity, double radius) : floor_(floor), gravity_(gravity), radius_(radius) {}

  /// The centre over foot point (u, v), and the floor's (up-oriented) unit normal there.
  Vec3 centre(const Vec2& foot, Vec3* normal = nullptr) const;
  /// `state` advanced under `law` by `duration` [s] in `substeps` equal steps, or to where
  /// its phase ends before that (End::ends); of its velocity only the part along the floor
  /// counts, and it ends along the floor there. A step is shortened where the slip (or a
  /// rolling ball's velocity) would turn by more than `turn` [rad] in it at the rate its
  /// pull across it turns it (fast near its end, where it is small), in all at most
  /// `step_cap` such steps (a slow ball in a pile, whose tiny velocity or slip turns
  /// about, would take ever more; past the cap, the substeps).
  End advance(State& state, double duration, int substeps, const Law& law, double turn, int step_cap) const;
  /// The substeps that keep each one's turn below `turn` [rad] for a ball at speed
  /// `speed` over `duration` on a floor whose centres' paths bend at most by `curvature`
  /// [1/m] (and that gravity's pull along the floor swings, sqrt(g curvature), as often).
  static int substepsFor(double duration, double speed, double curvature, double gravity, double turn);

private:
  /// The state's rates, and what ends its phase: the slip (sliding) or the velocity
  /// (rolling) q along the floor and its rate, and the rate the spin about the normal falls.
  struct Rates
  {
    Vec2 foot;
    Vec3 acceleration;
    Vec3 spin;
    double spin_n;
    Vec3 q, q_rate;
    double spin_n_rate;
    double support;  ///< what the floor must push with along n, per mass: push + g_n [m/s^2]
    double drag;     ///< the part of q's rate along -q/|q| (friction's, whose direction turns with q) [m/s^2]
  };
  Rates rates(const State& s, const Law& law) const;
  State rungeKutta(const State& s, double h, const Law& law, const Rates& first) const;
  /// The time until the first of the phase's ends at the rates `d` (infinite where none
  /// comes), and which it is.
  double timeToEnd(const State& s, const Law& law, const Rates& d, std::uint8_t& which) const;
  /// The time in which q turns by `turn` (for a drag of g; by turn (g / drag)^(1/3) for
  /// another, the error of a step going as the drag times the turn cubed) at its rate
  /// across it, taking in that a shrinking q turns faster as it goes (infinite without a
  /// drag: a free ball, or rolling without rolling resistance).
  double turnTime(const Rates& d, double turn) const;
  /// From `before` (its rates `rates`), the state where a step of at most `step` first
  /// has the floor's support below zero, within 1e-12 s on that side; its time in `time`.
  State takeOff(const State& before, const Rates& rates, double step, const Law& law, double& time) const;

  const Floor& floor_;
  Vec3 gravity_;
  double radius_;
};
}  // namespace ball_collision_sim::core
