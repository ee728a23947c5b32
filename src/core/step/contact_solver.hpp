// The contact solver: a group's resting contacts as constraints, solved together by
// projected Gauss-Seidel (Moreau; Jean; Catto's sequential impulses, Box2D's solver
// loop). Each contact's impulse is at least zero (it pushes, never pulls) and is the
// least that leaves it no closing; a wall is a contact with a body that does not move.
// It works on any vector per body: velocities [m/s], or a step's motions [m per unit of
// the step]. Reads and writes only what it is given; knows nothing of the StepContext.
#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ball_collision_sim::core::step
{
/// One contact between bodies a and b (b may be kImmovable: a wall; a body of inverse
/// mass 0 does not give way either, and is taken to be at rest). Its impulse moves a by -impulse * inv_mass_a * push_a and b by
/// +impulse * inv_mass_b * push_b (the pushes are the contact's normal, from a toward b,
/// as each body can take it: along its floor), and its closing is <u_a, push_a> -
/// <u_b, push_b>, measured along the same directions: so each update of one contact
/// changes the bodies' kinetic energy by -c^2 / 2K (c its closing, K its inverse mass
/// along the pushes), never more, whatever the vectors.
struct ContactRow
{
  static constexpr std::uint32_t kImmovable = 0xffffffffu;
  std::uint32_t a = 0;
  std::uint32_t b = kImmovable;
  Vec3 push_a = Vec3::UnitX();
  Vec3 push_b = Vec3::UnitX();
  /// the closing the contact allows: 0 for rest; below zero, a bounce's separation
  double target = 0.0;
  /// accumulated, >= 0: in, where to start (a warm start, applied first); out, the result
  double impulse = 0.0;
};

/// The closing of `row` where the bodies' vectors are u.
inline double closingOf(const std::vector<Vec3>& u, const ContactRow& row)
{
  const double va = u[row.a].dot(row.push_a);
  const double vb = row.b == ContactRow::kImmovable ? 0.0 : u[row.b].dot(row.push_b);
  return va - vb;
}

/// The largest closing among `rows` (0 when none closes).
inline double largestClosing(const std::vector<Vec3>& u, const std::vector<ContactRow>& rows)
{
  double largest = 0.0;
  for (const ContactRow& row : rows)
    largest = std::max(largest, closingOf(u, row));
  return largest;
}

/// The most any of `rows` closes past its target (0 when none does).
inline double largestPastTarget(const std::vector<Vec3>& u, const std::vector<ContactRow>& rows)
{
  double largest = 0.0;
  for (const ContactRow& row : rows)
    largest = std::max(largest, closingOf(u, row) - row.target);
  return largest;
}

/// How a solve went: sweeps taken, and the largest closing left beyond a row's target.
struct ContactSolve
{
  int sweeps = 0;
  double residual = 0.0;
  bool converged = false;
};

/// What an impulse along `row` moves body k by per unit (0 for a wall).
inline double inverseMassOf(const std::vector<double>& inv_mass, std::uint32_t k)
{
  return k == ContactRow::kImmovable ? 0.0 : inv_mass[k];
}

/// u moved by an impulse d along `row`.
inline void applyRow(std::vector<Vec3>& u, const std::vector<double>& inv_mass, const ContactRow& row, double d)
{
  u[row.a] -= (d * inverseMassOf(inv_mass, row.a)) * row.push_a;
  if (row.b != ContactRow::kImmovable)
    u[row.b] += (d * inverseMassOf(inv_mass, row.b)) * row.push_b;
}

/// The rows' warm start (their impulses, at least zero) applied to u, and each row's
/// effective inverse mass: how much a unit impulse opens it.
inline std::vector<double> startRows(std::vector<Vec3>& u, const std::vector<double>& inv_mass,
                                     std::vector<ContactRow>& rows)
{
  std::vector<double> opens(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    ContactRow& row = rows[r];
    opens[r] = inverseMassOf(inv_mass, row.a) * row.push_a.squaredNorm() +
               (row.b == ContactRow::kImmovable ? 0.0 : inverseMassOf(inv_mass, row.b) * row.push_b.squaredNorm());
    row.impulse = std::max(row.impulse, 0.0);
    if (row.impulse > 0 && opens[r] > 0)
      applyRow(u, inv_mass, row, row.impulse);
    else
      row.impulse = 0.0;
  }
  return opens;
}

/// One sweep of projected Gauss-Seidel over `rows` in their order: for each row in turn,
/// the impulse that takes its closing to its target, clamped so that the accumulated
/// impulse stays >= 0. The largest change of a row's closing it made.
inline double sweepRows(std::vector<Vec3>& u, const std::vector<double>& inv_mass, std::vector<ContactRow>& rows,
                        const std::vector<double>& opens)
{
  double change = 0.0;
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    ContactRow& row = rows[r];
    if (!(opens[r] > 0))
      continue;  // neither body can give way along it
    const double next = std::max(row.impulse + (closingOf(u, row) - row.target) / opens[r], 0.0);
    const double d = next - row.impulse;
    if (d == 0)
      continue;
    applyRow(u, inv_mass, row, d);
    row.impulse = next;
    change = std::max(change, std::abs(d) * opens[r]);
  }
  return change;
}

/// Projected Gauss-Seidel over `rows` in their order (the caller's order makes it
/// deterministic): sweepRows() from the warm start. After each sweep `project(u)` may
/// put the bodies' vectors back where they must lie (on the floor); sweeps go on until a
/// sweep changes no row's closing by more than `tolerance` and none closes by more than
/// `tolerance` past its target, or `max_sweeps` have run.
template <class Project>
ContactSolve solveContacts(std::vector<Vec3>& u, const std::vector<double>& inv_mass, std::vector<ContactRow>& rows,
                           double tolerance, int max_sweeps, Project&& project)
{
  const std::vector<double> opens = startRows(u, inv_mass, rows);
  ContactSolve out;
  while (out.sweeps < max_sweeps)
  {
    ++out.sweeps;
    const double change = sweepRows(u, inv_mass, rows, opens);
    project(u);
    out.residual = largestPastTarget(u, rows);
    if (change <= tolerance && out.residual <= tolerance)
    {
      out.converged = true;
      break;
    }
  }
  return out;
}

/// How the exact stage solves (from StepSettings, where each is explained).
struct ExactSettings
{
  /// direct solves it may take, changing which rows push between them [solves]
  int rounds = 1024;
  /// A's diagonal is taken this much larger, so that rows that say the same (a jam's)
  /// share their push equally [ratio] ...
  double regularization = 1e-10;
  /// ... and the solution refined this many times against A itself [refinements]
  int refinements = 2;
  /// rounds that all wrong rows may change side together without making fewer of them,
  /// before the interior-point and primal active-set methods take over [rounds]
  int pivot_tries = 3;
  /// iterations of the interior-point method, which finds the rows that push for the
  /// active-set method to start from [iterations]
  int interior_iterations = 100;
};

/// The rows' closings, exactly, from where the contact solver left them (the rows whose
/// impulses are > 0 taken to push): the impulses that take the pushing rows' closings to
/// their targets from the free vectors u_free, solved directly (A lambda = closing -
/// target, A = J M^-1 J^T over the pushing rows, by sparse LDL^T; the subspace
/// minimization of Silcowitz, Niebe and Erleben 2010 after projected Gauss-Seidel). Rows
/// then change sides where they are wrong (a pushing row that pulls, a row left out that
/// closes past its target by more than `slack`): all of them at once while that makes
/// fewer wrong (block principal pivoting, Judice and Pires). Where that stalls (contacts
/// that say the same leave A near singular, and its impulses come out with either sign),
/// the problem with A's diagonal a little larger (definite: one answer) is solved by an
/// interior-point method over all rows (solveInterior(): some thirty factorizations on one
/// pattern, whatever the jam), and pivoting from the rows it found to push settles those
/// it left on the fence; where the direct solves cannot (impulses below what they
/// resolve), its own impulses stand where no row is wrong with them (those it found to
/// push close past their targets by the regularization's share, as a direct solve's
/// do); where neither settles, the primal active-set method from the sweeps' impulses,
/// which lowers its objective at each solve and so ends (it takes one row at a time once
/// adding several made no progress). A's own impulses for the rows found are
/// kept where they are right too. At most `settings.rounds` direct solves in all, and that
/// one more. True, with u and the impulses set, where no row is wrong; false with neither
/// changed.
bool solveContactsExactly(const std::vector<Vec3>& u_free, const std::vector<double>& inv, std::vector<ContactRow>& rows,
                          std::vector<Vec3>& u, double slack, const ExactSettings& settings);

/// The same without a projection after each sweep.
inline ContactSolve solveContacts(std::vector<Vec3>& u, const std::vector<double>& inv_mass,
                                  std::vector<ContactRow>& rows, double tolerance, int max_sweeps)
{
  return solveContacts(u, inv_mass, rows, tolerance, max_sweeps, [](std::vector<Vec3>&) {});
}
}  // namespace ball_collision_sim::core::step
