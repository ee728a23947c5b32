// The contact solver's interior-point stage (contact_interior.hpp): the regularized problem
// over every row, solved by Mehrotra's predictor-corrector method on one sparsity pattern.
#include "contact_interior.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core::step
{
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

namespace
{
/// The largest step in [0, 1] along (d_lambda, d_w) that keeps lambda and w >= 0.
double stepToBoundary(const Eigen::VectorXd& lambda, const Eigen::VectorXd& w, const Eigen::VectorXd& d_lambda,
                      const Eigen::VectorXd& d_w)
{
  double step = 1.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
  {
    if (d_lambda[i] < 0)
      step = std::min(step, -lambda[i] / d_lambda[i]);
    if (d_w[i] < 0)
      step = std::min(step, -w[i] / d_w[i]);
  }
  return step;
}

/// (A + E) d = g for the rows' A = J M^-1 J^T and a diagonal E > 0, solved through the
/// bodies (Woodbury's identity): d = E^-1 (g - J y), where (M + J^T E^-1 J) y =
/// J^T E^-1 g. That matrix has a 3 x 3 block for each body and each pair of bodies in
/// contact, where A has an entry for each pair of rows that share a body: for a jam,
/// about a tenth of the fill. Its pattern is ordered and analysed once.
class BodySystem
{
public:
  BodySystem(const std::vector<double>& inv, const std::vector<ContactRow>& rows, const std::vector<int>& movable)
      : rows_(rows), movable_(movable), index_(inv.size(), -1)
  {
    int bodies = 0;
    for (std::size_t k = 0; k < inv.size(); ++k)
      if (inv[k] > 0)
        index_[k] = bodies++;
    size_ = 3 * static_cast<Eigen::Index>(bodies);
    mass_.resize(size_);
    for (std::size_t k = 0; k < inv.size(); ++k)
      if (index_[k] >= 0)
        mass_.segment<3>(3 * index_[k]).setConstant(1 / inv[k]);
    // the pattern: each body's block and each pair's, lower triangles
    std::vector<Eigen::Triplet<double>> pattern;
    for (Eigen::Index p = 0; p < size_; ++p)
      for (Eigen::Index q = 3 * (p / 3); q <= p; ++q)
        pattern.emplace_back(p, q, 0.0);
    for (const int r : movable_)
    {
      const int a = bodyOf(rows_[static_cast<std::size_t>(r)].a), b = bodyOf(rows_[static_cast<std::size_t>(r)].b);
      if (a >= 0 && b >= 0)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            pattern.emplace_back(3 * std::max(a, b) + i, 3 * std::min(a, b) + j, 0.0);
    }
    B_.resize(size_, size_);
    B_.setFromTriplets(pattern.begin(), pattern.end());
    B_.makeCompressed();
    // each row's share of each entry, E_i^-1 c_p c_q, its coefficients c (push_a at a,
    // -push_b at b)
    for (const int r : movable_)
    {
      const ContactRow& row = rows_[static_cast<std::size_t>(r)];
      Eigen::Index at[6];
      double c[6];
      int count = 0;
      for (const auto& [body, push] : {std::pair<int, Vec3>(bodyOf(row.a), row.push_a),
                                       std::pair<int, Vec3>(bodyOf(row.b), -row.push_b)})
        if (body >= 0)
          for (int i = 0; i < 3; ++i)
          {
            at[count] = 3 * body + i;
            c[count++] = push[i];
          }
      for (int p = 0; p < count; ++p)
        for (int q = 0; q < count; ++q)
          if (at[p] >= at[q])
            shares_.push_back(Share{&B_.coeffRef(at[p], at[q]), c[p] * c[q]});
      share_ends_.push_back(shares_.size());
    }
    solver_.analyzePattern(B_);
  }

  /// Factorizes M + J^T E^-1 J for the rows' E; false where that failed.
  bool factorize(const Eigen::VectorXd& e)
  {
    e_ = e;
    std::fill(B_.valuePtr(), B_.valuePtr() + B_.nonZeros(), 0.0);
    for (Eigen::Index p = 0; p < size_; ++p)
      B_.coeffRef(p, p) += mass_[p];
    std::size_t s = 0;
    for (std::size_t i = 0; i < share_ends_.size(); ++i)
      for (const double scale = 1 / e[static_cast<Eigen::Index>(i)]; s < share_ends_[i]; ++s)
        *shares_[s].value += scale * shares_[s].coefficient;
    solver_.factorize(B_);
    return solver_.info() == Eigen::Success;
  }

  /// d with (A + E) d = g, E the last factorized's.
  Eigen::VectorXd solve(const Eigen::VectorXd& g) const
  {
    const Eigen::VectorXd s = g.cwiseQuotient(e_);
    Eigen::VectorXd t = Eigen::VectorXd::Zero(size_);
    for (std::size_t i = 0; i < movable_.size(); ++i)
      spread(movable_[i], s[static_cast<Eigen::Index>(i)], t);
    const Eigen::VectorXd y = solver_.solve(t);
    Eigen::VectorXd d(g.size());
    for (std::size_t i = 0; i < movable_.size(); ++i)
      d[static_cast<Eigen::Index>(i)] = (g[static_cast<Eigen::Index>(i)] - closing(movable_[i], y)) / e_[static_cast<Eigen::Index>(i)];
    return d;
  }

private:
  struct Share
  {
    double* value;
    double coefficient;
  };
  int bodyOf(std::uint32_t k) const { return k == ContactRow::kImmovable ? -1 : index_[k]; }
  /// t += J_r^T s
  void spread(int r, double s, Eigen::VectorXd& t) const
  {
    const ContactRow& row = rows_[static_cast<std::size_t>(r)];
    if (const int a = bodyOf(row.a); a >= 0)
      t.segment<3>(3 * a) += s * row.push_a;
    if (const int b = bodyOf(row.b); b >= 0)
      t.segment<3>(3 * b) -= s * row.push_b;
  }
  /// (J y)_r
  double closing(int r, const Eigen::VectorXd& y) const
  {
    const ContactRow& row = rows_[static_cast<std::size_t>(r)];
    double c = 0.0;
    if (const int a = bodyOf(row.a); a >= 0)
      c += y.segment<3>(3 * a).dot(row.push_a);
    if (const int b = bodyOf(row.b); b >= 0)
      c -= y.segment<3>(3 * b).dot(row.push_b);
    return c;
  }

  const std::vector<ContactRow>& rows_;
  const std::vector<int>& movable_;
  std::vector<int> index_;
  Eigen::Index size_ = 0;
  Eigen::VectorXd mass_;
  Eigen::SparseMatrix<double> B_;
  std::vector<Share> shares_;
  std::vector<std::size_t> share_ends_;
  Eigen::VectorXd e_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> solver_;
};
}  // namespace

bool solveInterior(const std::vector<Vec3>& u_free, const std::vector<double>& inv, const std::vector<ContactRow>& rows,
                   std::vector<double>& lambda, double regularization, int iterations)
{
  // (rows that no body can give way along take no impulse, and are left out)
  std::vector<int> movable;
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    const ContactRow& row = rows[r];
    const double opens = inv[row.a] * row.push_a.squaredNorm() +
                         (row.b == ContactRow::kImmovable ? 0.0 : inv[row.b] * row.push_b.squaredNorm());
    if (opens > 0)
      movable.push_back(static_cast<int>(r));
  }
  std::fill(lambda.begin(), lambda.end(), 0.0);
  const Eigen::Index n = static_cast<Eigen::Index>(movable.size());
  if (n == 0)
    return true;
  const PushingSystem system = pushingSystem(u_free, inv, rows, movable, regularization);
  const auto M = system.A.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd q = -system.rhs;
  // (the problem's scales: its closings, and the impulse that a mean row's closing takes)
  const double closing_scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  const double impulse_scale = closing_scale / (system.diagonal.mean() * (1 + regularization));
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, impulse_scale);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, closing_scale);
  // (A + E, E = eps D + W / Lambda: through the bodies)
  const Eigen::VectorXd regularized = regularization * system.diagonal;
  BodySystem newton(inv, rows, movable);
  const double mu_done = 1e-30 * closing_scale * impulse_scale, residual_done = 1e-13 * closing_scale;
  bool converged = false;
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    const Eigen::VectorXd residual = M * x + q - w;
    const double mu = x.dot(w) / static_cast<double>(n);
    if (mu <= mu_done && residual.cwiseAbs().maxCoeff() <= residual_done)
    {
      converged = true;
      break;
    }
    if (!newton.factorize(regularized + w.cwiseQuotient(x)))
      return false;
    // the predictor: the Newton step toward lambda w = 0
    const Eigen::VectorXd dx_affine = newton.solve(-residual - w);
    const Eigen::VectorXd dw_affine = -w - (w.cwiseQuotient(x)).cwiseProduct(dx_affine);
    const double step_affine = stepToBoundary(x, w, dx_affine, dw_affine);
    const double mu_affine = (x + step_affine * dx_affine).dot(w + step_affine * dw_affine) / static_cast<double>(n);
    const double sigma = std::pow(mu_affine / mu, 3);
    // the corrector: toward sigma mu, with the predictor's second-order term
    const Eigen::VectorXd target =
        (Eigen::VectorXd::Constant(n, sigma * mu) - x.cwiseProduct(w) - dx_affine.cwiseProduct(dw_affine))
            .cwiseQuotient(x);
    const Eigen::VectorXd dx = newton.solve(-residual + target);
    const Eigen::VectorXd dw = target - (w.cwiseQuotient(x)).cwiseProduct(dx);
    if (!dx.allFinite() || !dw.allFinite())
      return false;
    const double step = std::min(1.0, 0.995 * stepToBoundary(x, w, dx, dw));
    x += step * dx;
    w += step * dw;
  }
  // (a row pushes where its impulse closes it by more than it opens: lambda D > w)
  for (Eigen::Index i = 0; i < n; ++i)
    if (x[i] * system.diagonal[i] > w[i])
      lambda[static_cast<std::size_t>(movable[static_cast<std::size_t>(i)])] = x[i];
  return converged;
}
}  // namespace ball_collision_sim::core::step
