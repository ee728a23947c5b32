// The contact solver's exact stage (contact_solver.hpp): reads the free vectors and the
// rows' first guess of which push; writes the vectors and the impulses.
#include "contact_solver.hpp"
#include "contact_interior.hpp"

#include <Eigen/SparseCholesky>

namespace ball_collision_sim::core::step
{
namespace
{
/// The impulses of the rows `active` (taken to push) that take their closings to their
/// targets from u_free, solved directly, into lambda (pushedBy() gives the vectors they
/// leave); false where A could not be factorized. Refined `refinements` times, the impulses
/// are those of A itself; not refined, those of A with its diagonal a little larger.
bool solvePushing(const std::vector<Vec3>& u_free, const std::vector<double>& inv, const std::vector<ContactRow>& rows,
                  const std::vector<int>& active, std::vector<double>& lambda, const ExactSettings& settings,
                  int refinements)
{
  const int n = static_cast<int>(active.size());
  const PushingSystem system = pushingSystem(u_free, inv, rows, active, settings.regularization);
  const Eigen::SparseMatrix<double>& A = system.A;
  const Eigen::VectorXd& rhs = system.rhs;
  const Eigen::VectorXd& diagonal = system.diagonal;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> solver(A);
  if (solver.info() != Eigen::Success)
    return false;
  Eigen::VectorXd x = solver.solve(rhs);
  for (int pass = 0; pass < refinements; ++pass)
  {
    const Eigen::VectorXd residual =
        rhs - (A.selfadjointView<Eigen::Lower>() * x - settings.regularization * diagonal.cwiseProduct(x));
    x += solver.solve(residual);
  }
  if (solver.info() != Eigen::Success || !x.allFinite())
    return false;
  for (int p = 0; p < n; ++p)
    lambda[static_cast<std::size_t>(active[static_cast<std::size_t>(p)])] = x[p];
  return true;
}

/// The rows that are wrong where those in_active push with the impulses lambda and leave
/// the vectors trial: a pushing row whose impulse came out below zero, a row left out that
/// closes past its target by more than `slack`.
std::vector<int> wrongRows(const std::vector<ContactRow>& rows, const std::vector<char>& in_active,
                           const std::vector<Vec3>& trial, const std::vector<double>& lambda, double slack)
{
  std::vector<int> wrong;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (in_active[r] ? lambda[r] < 0 : closingOf(trial, rows[r]) - rows[r].target > slack)
      wrong.push_back(static_cast<int>(r));
  return wrong;
}

/// The vectors that u_free leaves where the rows push with the impulses lambda.
std::vector<Vec3> pushedBy(const std::vector<Vec3>& u_free, const std::vector<double>& inv,
                           const std::vector<ContactRow>& rows, const std::vector<double>& lambda)
{
  std::vector<Vec3> u = u_free;
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    const ContactRow& row = rows[r];
    u[row.a] -= (lambda[r] * inv[row.a]) * row.push_a;
    if (row.b != ContactRow::kImmovable)
      u[row.b] += (lambda[r] * inv[row.b]) * row.push_b;
  }
  return u;
}

/// The impulses with A's diagonal a little larger (a positive definite problem, with one
/// answer), by the primal active-set method on its quadratic program (minimize
/// lambda^T A lambda / 2 - lambda^T (closing - target) over lambda >= 0; Nocedal and
/// Wright, Numerical Optimization, 16.5). From lambda (>= 0; out, the answer) it solves
/// the pushing rows directly and steps toward that solve as far as every impulse stays
/// >= 0; the rows that reach zero stop pushing. Once a solve needs no step back, the rows
/// left out that close past their targets by more than `slack` start pushing. Each solve
/// lowers the objective, so no set of pushing rows comes back and the method ends, near
/// singular or not. Takes at most `solves` solves from the count; true where it ended.
bool solveRegularized(const std::vector<Vec3>& u_free, const std::vector<double>& inv,
                      const std::vector<ContactRow>& rows, std::vector<double>& lambda, double slack,
                      const ExactSettings& settings, int& solves)
{
  std::vector<int> pushing;
  std::vector<double> x(rows.size());
  // (all the rows that close past their targets start pushing together, until that makes
  // a step stop at once; from then on only the one that closes most: that one always
  // ends up pushing and lowers the objective, so no set of rows comes back)
  bool one_at_a_time = false;
  for (; solves > 0; --solves)
  {
    pushing.clear();
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (lambda[r] > 0 || x[r] > 0)
        pushing.push_back(static_cast<int>(r));
    std::fill(x.begin(), x.end(), 0.0);
    if (!pushing.empty() && !solvePushing(u_free, inv, rows, pushing, x, settings, 0))
      return false;
    double step = 1.0;
    bool blocked = false;
    for (const int r : pushing)
      if (x[r] < 0)
      {
        blocked = true;
        step = std::min(step, lambda[r] / (lambda[r] - x[r]));
      }
    if (blocked)
    {
      // (one row started alone always pushes: where it does not, round-off has taken
      // over, and the method would only go round)
      if (step == 0 && one_at_a_time)
        return false;
      one_at_a_time = one_at_a_time || step == 0;
      for (const int r : pushing)
      {
        const bool stops = x[r] < 0 && lambda[r] / (lambda[r] - x[r]) <= step;
        lambda[r] = stops ? 0.0 : lambda[r] + step * (x[r] - lambda[r]);
        x[r] = 0.0;
      }
      continue;
    }
    for (const int r : pushing)
      lambda[r] = x[r];
    const std::vector<Vec3> trial = pushedBy(u_free, inv, rows, lambda);
    int closes_most = -1;
    double most = slack;
    for (std::size_t r = 0; r < rows.size(); ++r)
    {
      const double past = lambda[r] > 0 ? 0.0 : closingOf(trial, rows[r]) - rows[r].target;
      if (past > slack && !one_at_a_time)
        x[r] = 1.0;  // (taken to push in the next solve)
      if (past > most)
      {
        most = past;
        closes_most = static_cast<int>(r);
      }
    }
    if (closes_most < 0)
      return true;
    x[static_cast<std::size_t>(closes_most)] = 1.0;
  }
  return false;
}

/// Block principal pivoting (Judice and Pires) from the rows whose impulses are > 0: every
/// row that is wrong changes side, as long as that makes fewer wrong ones within
/// `pivot_tries` rounds. True, with the impulses and the vectors they leave, where no row
/// is left wrong within `solves` (counted down).
bool pivotBlocks(const std::vector<Vec3>& u_free, const std::vector<double>& inv, const std::vector<ContactRow>& rows,
                 const std::vector<double>& start, std::vector<double>& lambda, std::vector<Vec3>& trial, double slack,
                 const ExactSettings& settings, int refinements, int& solves)
{
  std::vector<int> active;
  std::vector<char> in_active(rows.size(), 0);
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (start[r] > 0)
      in_active[r] = 1;
  std::size_t fewest = rows.size() + 1;
  int tries = settings.pivot_tries;
  for (; solves > 0; --solves)
  {
    active.clear();
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (in_active[r])
        active.push_back(static_cast<int>(r));
    std::fill(lambda.begin(), lambda.end(), 0.0);
    if (!active.empty() && !solvePushing(u_free, inv, rows, active, lambda, settings, refinements))
      return false;
    trial = pushedBy(u_free, inv, rows, lambda);
    const std::vector<int> wrong = wrongRows(rows, in_active, trial, lambda, slack);
    if (wrong.empty())
      return true;
    if (wrong.size() < fewest)
    {
      fewest = wrong.size();
      tries = settings.pivot_tries;
    }
    else if (tries-- == 0)
    {
      --solves;
      return false;
    }
    for (const int r : wrong)
      in_active[static_cast<std::size_t>(r)] ^= 1;
  }
  return false;
}
}  // namespace

bool solveContactsExactly(const std::vector<Vec3>& u_free, const std::vector<double>& inv, std::vector<ContactRow>& rows,
                          std::vector<Vec3>& u, double slack, const ExactSettings& settings)
{
  std::vector<double> lambda(rows.size());
  std::vector<Vec3> trial;
  int solves = settings.rounds;
  std::vector<double> sweeps(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    sweeps[r] = rows[r].impulse;
  if (!pivotBlocks(u_free, inv, rows, sweeps, lambda, trial, slack, settings, settings.refinements, solves))
  {
    // Where that does not settle, the problem with A's diagonal a little larger: the
    // interior-point method finds which rows push, and pivoting from there settles
    // which of those it left on the fence push. Where the direct solves cannot tell
    // (rows whose impulses are below what they resolve, in a jam's near singular
    // matrix), the interior-point method's own impulses stand where no row is wrong with
    // them; else the primal active-set method, which ends, from its impulses.
    // Then A's own impulses with the rows found, where they are right too.
    std::vector<double> interior(rows.size());
    const bool ipm = solveInterior(u_free, inv, rows, interior, settings.regularization, settings.interior_iterations);
    bool okr = ipm && pivotBlocks(u_free, inv, rows, interior, lambda, trial, slack, settings, 0, solves);
    if (!okr && ipm)
    {
      // (its rows that push close past their targets by the regularization's share, as
      // a direct solve's do; those it found not to push push nothing, and may not close
      // past theirs)
      std::vector<char> pushes(rows.size());
      for (std::size_t r = 0; r < rows.size(); ++r)
        pushes[r] = interior[r] > 0 ? 1 : 0;
      std::vector<Vec3> within = pushedBy(u_free, inv, rows, interior);
      if (wrongRows(rows, pushes, within, interior, slack).empty())
      {
        u.swap(within);
        for (std::size_t r = 0; r < rows.size(); ++r)
          rows[r].impulse = interior[r];
        return true;
      }
    }
    if (!okr)
    {
      // (from the interior-point method's impulses where it ended: all >= 0, and all but
      // the answer of the same problem; else from the sweeps')
      for (std::size_t r = 0; r < rows.size(); ++r)
        lambda[r] = ipm ? interior[r] : std::max(rows[r].impulse, 0.0);
      okr = solveRegularized(u_free, inv, rows, lambda, slack, settings, solves);
    }
    if (!okr)
      return false;
    std::vector<int> active;
    std::vector<char> in_active(rows.size(), 0);
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (lambda[r] > 0)
      {
        in_active[r] = 1;
        active.push_back(static_cast<int>(r));
      }
    std::vector<double> own(rows.size(), 0.0);
    if (!active.empty() && solvePushing(u_free, inv, rows, active, own, settings, settings.refinements) &&
        wrongRows(rows, in_active, pushedBy(u_free, inv, rows, own), own, slack).empty())
      lambda.swap(own);
    trial = pushedBy(u_free, inv, rows, lambda);
  }
  u.swap(trial);
  for (std::size_t r = 0; r < rows.size(); ++r)
    rows[r].impulse = lambda[r];
  return true;
}
}  // namespace ball_collision_sim::core::step
