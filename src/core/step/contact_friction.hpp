// Friction at resting contacts: each contact's two directions across its normal, as rows
// on the bodies' vectors u and their spins w, bounded together by Coulomb's law (the
// pair's impulse within a disc of mu times its normal row's impulse). Solved with the
// normal rows by projected Gauss-Seidel (Moreau and Jean; Catto's sequential impulses,
// with the friction disc of Jolt and Bullet), then where that does not converge by
// staggered projections (Kaufman, Sueda, James and Pai 2008): the normal rows solved
// exactly with friction held, friction solved again under the normal impulses found, until
// friction stops changing. Reads and writes only what it is given.
#pragma once

#include "contact_solver.hpp"

#include <array>

namespace ball_collision_sim::core::step
{
/// One direction across a contact's normal: the touching points' slip along it is
/// <u_a, push_a> + <w_a, turn_a> - <u_b, push_b> - <w_b, turn_b>, and its impulse moves a
/// by -impulse (inv_mass_a push_a, inv_inertia_a turn_a) and b by +impulse (...) likewise,
/// so that each update of one direction changes the bodies' kinetic energy by -s^2 / 2K at
/// most (s its slip, K its inverse mass along the pushes and turns).
struct FrictionRow
{
  Vec3 push_a = Vec3::Zero();
  Vec3 push_b = Vec3::Zero();
  Vec3 turn_a = Vec3::Zero();
  Vec3 turn_b = Vec3::Zero();
  double impulse = 0.0;
};

/// A contact's friction: its two directions, bounded by mu times the impulse of the
/// normal row `normal` (whose bodies they share).
struct FrictionPair
{
  std::uint32_t normal = 0;
  double mu = 0.0;
  std::array<FrictionRow, 2> rows;
};

/// The bodies' spins and how an impulse turns them (0 for a body that does not turn).
struct Spins
{
  std::vector<Vec3>& w;
  const std::vector<double>& inv_inertia;
};

/// Projected Gauss-Seidel over the normal rows and the friction pairs (each pair's
/// directions in turn, each kept within the disc where the other is), in the callers'
/// order, starting from the impulses they hold; until a sweep changes no row's closing or
/// slip by more than `tolerance` and no normal row closes past its target by more than
/// `tolerance`, or `max_sweeps` have run.
ContactSolve solveWithFriction(std::vector<Vec3>& u, const std::vector<double>& inv_mass, std::vector<ContactRow>& rows,
                               Spins spins, std::vector<FrictionPair>& pairs, double tolerance, int max_sweeps);

/// u and the spins moved by the pairs' impulses.
void applyFriction(std::vector<Vec3>& u, const std::vector<double>& inv_mass, const std::vector<ContactRow>& rows,
                   Spins spins, const std::vector<FrictionPair>& pairs);

/// Normal rows and friction solved together (solveWithFriction()), and where the sweeps do
/// not converge, the normal rows exactly (solveContactsExactly()) with friction held, and
/// friction again under the impulses found, at most `passes` times. u_free and w_free are
/// the vectors and spins before any impulse. True where the last exact solve found its
/// answer (or the sweeps converged); u, the spins and all impulses are set either way.
bool solveFrictionally(const std::vector<Vec3>& u_free, const std::vector<Vec3>& w_free, std::vector<Vec3>& u,
                       const std::vector<double>& inv_mass, std::vector<ContactRow>& rows, Spins spins,
                       std::vector<FrictionPair>& pairs, double slack, int sweeps, int passes,
                       const ExactSettings& exact);
}  // namespace ball_collision_sim::core::step
