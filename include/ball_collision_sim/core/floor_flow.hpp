#pragma once

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/types.hpp"

namespace ball_collision_sim::core
{
/// A ball on a curved floor as its laws move it, integrated: the foot point (u, v) whose
/// centre is S + r n, and the centre's velocity along the floor. The acceleration is the
/// law's along the floor, a_t, and the floor's push along n that keeps the centre on its
/// surface, (v . L (I - r L)^-1 v) n, L the floor's shape operator (Weingarten's,
/// I^-1 II in the basis (S_u, S_v)): a ball moving at speed s over a bowl of radius R
/// is pushed at s^2 / (R - r). The foot moves at (I - r II)^-1 (S_u . v, S_v . v). A law is
/// gravity's share along the floor and a drag against the velocity:
///   a_t = share g_t - drag (-g . n) v / |v|,
/// a frictionless ball's (share 1, drag 0) and a rolling one's (share 1 / (1 + k), drag
/// mu_r). Classical Runge-Kutta of fourth order in `substeps` equal steps.
class FloorFlow
{
public:
  struct Law
  {
    double share = 1.0;  ///< of gravity along the floor
    double drag = 0.0;   ///< against the velocity, times gravity into the floor
  };
  struct State
  {
    Vec2 foot = Vec2::Zero();
    Vec3 velocity = Vec3::Zero();
  };

  FloorFlow(const Floor& floor, const Vec3& gravity, double radius) : floor_(floor), gravity_(gravity), radius_(radius) {}

  /// The centre over foot point (u, v), and the floor's (up-oriented) unit normal there.
  Vec3 centre(const Vec2& foot, Vec3* normal = nullptr) const;
  /// `state` advanced by `duration` [s] in `substeps` steps under `law` (of its velocity,
  /// only the part along the floor counts); its velocity then along the floor where it
  /// is. Returns the centre there, and the floor's normal into `normal`.
  Vec3 advance(State& state, double duration, int substeps, const Law& law, Vec3& normal) const;
  Vec3 advance(State& state, double duration, int substeps, const Law& law) const
  {
    Vec3 normal;
    return advance(state, duration, substeps, law, normal);
  }
  /// The substeps that keep each one's turn below `turn` [rad] for a ball at speed
  /// `speed` over `duration` on a floor whose centres' paths bend at most by `curvature`
  /// [1/m] (and that gravity's pull along the floor swings, sqrt(g curvature), as often).
  static int substepsFor(double duration, double speed, double curvature, double gravity, double turn);

private:
  /// d(foot)/dt and dv/dt.
  void rates(const State& s, const Law& law, Vec2& foot_rate, Vec3& acceleration) const;

  const Floor& floor_;
  Vec3 gravity_;
  double radius_;
};
}  // namespace ball_collision_sim::core
