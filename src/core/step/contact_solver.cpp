// The contact solver's exact stage (contact_solver.hpp): reads the free vectors and the
// rows' first guess of which push; writes the vectors and the impulses.
#include "contact_solver.hpp"

#include <Eigen/SparseCholesky>

namespace ball_collision_sim::core::step
{
namespace
{
/// A, the pushing rows' W = J M^-1 J^T (its lower triangle, its diagonal a little larger),
/// its diagonal as it is, and the right side, their closings past their targets at u_free.
struct PushingSystem
{
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd diagonal;
  Eigen::VectorXd rhs;
};

PushingSystem pushingSystem(const std::vector<Vec3>& u_free, const std::vector<double>& inv,
                            const std::vector<ContactRow>& rows, const std::vector<int>& active, double regularization)
{
  const int n = static_cast<int>(active.size());
  const auto coefficient = [&](const ContactRow& row, std::uint32_t k) {
    Vec3 c = Vec3::Zero();
    if (row.a == k)
      c += row.push_a;
    if (row.b == k)
      c -= row.push_b;
    return c;
  };
  // (A's entries: rows that share a body, found through each body's rows)
  std::vector<Eigen::Triplet<double>> entries;
  PushingSystem out;
  Eigen::VectorXd& rhs = out.rhs;
  rhs.resize(n);
  std::vector<std::vector<int>> of_body(u_free.size());
  for (int p = 0; p < n; ++p)
  {
    const ContactRow& r = rows[static_cast<std::size_t>(active[static_cast<std::size_t>(p)])];
    rhs[p] = closingOf(u_free, r) - r.target;
    of_body[r.a].push_back(p);
    if (r.b != ContactRow::kImmovable)
      of_body[r.b].push_back(p);
  }
  Eigen::VectorXd& diagonal = out.diagonal;
  diagonal = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < of_body.size(); ++k)
  {
    if (inv[k] == 0)
      continue;
    for (const int p : of_body[k])
      for (const int q : of_body[k])
      {
        if (q > p)
          continue;  // (the solver reads the lower triangle)
        const ContactRow& r = rows[static_cast<std::size_t>(active[static_cast<std::size_t>(p)])];
        const ContactRow& t = rows[static_cast<std::size_t>(active[static_cast<std::size_t>(q)])];
        const auto body = static_cast<std::uint32_t>(k);
        const double a = inv[k] * coefficient(r, body).dot(coefficient(t, body));
        if (p == q)
          diagonal[p] += a;
        entries.emplace_back(p, q, a);
      }
  }
  // (contacts that say the same, in a jam, leave A singular: it is factorized with its
  // diagonal a little larger, and the solution refined against A itself)
  for (int p = 0; p < n; ++p)
    entries.emplace_back(p, p, regularization * diagonal[p]);
  out.A.resize(n, n);
  out.A.setFromTriplets(entries.begin(), entries.end());
  return out;
}

/// The impulses of the rows `active` (taken to push) that take their closings to their
/// targets from u_free, solved directly, into lambda, and the vectors they leave, into
/// trial; false where A could not be factorized. Refined `refinements` times, the impulses
/// are those of A itself; not refined, those of A with its diagonal a little larger.
bool solvePushing(const std::vector<Vec3>& u_free, const std::vector<double>& inv, const std::vector<ContactRow>& rows,
                  const std::vector<int>& active, std::vector<Vec3>& trial, std::vector<double>& lambda,
                  const ExactSettings& settings, int refinements)
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
  {
    const ContactRow& r = rows[static_cast<std::size_t>(active[static_cast<std::size_t>(p)])];
    lambda[static_cast<std::size_t>(active[static_cast<std::size_t>(p)])] = x[p];
    trial[r.a] -= (x[p] * inv[r.a]) * r.push_a;
    if (r.b != ContactRow::kImmovable)
      trial[r.b] += (x[p] * inv[r.b]) * r.push_b;
  }
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
}  // namespace

bool solveContactsExactly(const std::vector<Vec3>& u_free, const std::vector<double>& inv, std::vector<ContactRow>& rows,
                          std::vector<Vec3>& u, double slack, const ExactSettings& settings)
{
  std::vector<int> active;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (rows[r].impulse > 0)
      active.push_back(static_cast<int>(r));
  std::vector<char> in_active;
  std::size_t fewest = rows.size() + 1;
  int tries = settings.pivot_tries;
  // (Murty's rule ends for a positive definite A; where contacts say the same, A itself
  // is only semidefinite, and one row after another can go round in a cycle: from then
  // on the rows are judged by the regularized A, which is definite; near singular, its
  // solves' round-off can still keep it from settling within `rounds`)
  bool refine = true;
  for (int round = 0; round < settings.rounds; ++round)
  {
    const int n = static_cast<int>(active.size());
    std::vector<Vec3> trial = u_free;
    std::vector<double> lambda(rows.size(), 0.0);
    if (n > 0 && !solvePushing(u_free, inv, rows, active, trial, lambda, settings, refine ? settings.refinements : 0))
      return false;
    // Block principal pivoting (Judice and Pires): every row that is wrong changes side,
    // as long as that makes fewer wrong ones within a few rounds; else only the first
    // wrong row does (Murty's rule, which ends for a positive definite A).
    in_active.assign(rows.size(), 0);
    for (const int r : active)
      in_active[static_cast<std::size_t>(r)] = 1;
    std::vector<int> wrong = wrongRows(rows, in_active, trial, lambda, slack);
    if (wrong.empty())
    {
      // (found by the regularized A: A's own impulses where they are right too)
      std::vector<Vec3> refined = u_free;
      std::vector<double> refined_lambda(rows.size(), 0.0);
      if (!refine && solvePushing(u_free, inv, rows, active, refined, refined_lambda, settings, settings.refinements) &&
          wrongRows(rows, in_active, refined, refined_lambda, slack).empty())
      {
        trial.swap(refined);
        lambda.swap(refined_lambda);
      }
      u = trial;
      for (std::size_t r = 0; r < rows.size(); ++r)
        rows[r].impulse = lambda[r];
      return true;
    }
    if (wrong.size() < fewest)
    {
      fewest = wrong.size();
      tries = settings.pivot_tries;
    }
    else if (tries > 0)
      --tries;
    else
    {
      wrong.resize(1);
      refine = false;
    }
    for (const int r : wrong)
      in_active[static_cast<std::size_t>(r)] ^= 1;
    active.clear();
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (in_active[r])
        active.push_back(static_cast<int>(r));
  }
  return false;
}
}  // namespace ball_collision_sim::core::step
