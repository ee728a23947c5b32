#pragma once

#include "ball_collision_sim/core/types.hpp"

namespace ball_collision_sim::core
{
/// Impulse magnitude [N s] of a collision along the contact normal n.
///
/// Each body's velocity may change only along its own direction t_k: the normal's part
/// tangent to the floor under that body (t_k = n on a flat floor or in free space), so
/// that velocities stay on the floor. `closing` = <v1, t1> - <v2, t2> > 0 [m/s];
/// inv_mass = 1 / m [1/kg], 0 for an immovable body (a wall).
/// The velocities change by v1 -= J inv_mass1 t1, v2 += J inv_mass2 t2, with
/// J = (1 + e) closing / (inv_mass1 |t1|^2 + inv_mass2 |t2|^2). With t1 = t2 = n and
/// e = 1 this is the textbook elastic exchange (the seed's equations 16-19), and for
/// any t_k it conserves kinetic energy at e = 1.
inline double collisionImpulse(double closing, double inv_mass1, const Vec3& t1,
                               double inv_mass2, const Vec3& t2, double restitution)
{
  const double k = inv_mass1 * t1.squaredNorm() + inv_mass2 * t2.squaredNorm();
  return k > 0 ? (1 + restitution) * closing / k : 0.0;
}

/// The part of n tangent to a floor with unit normal floor_normal.
inline Vec3 tangentPart(const Vec3& n, const Vec3& floor_normal)
{
  return n - n.dot(floor_normal) * floor_normal;
}
}  // namespace ball_collision_sim::core
