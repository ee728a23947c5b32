// The contact solver's interior-point stage: the regularized problem of every row at once,
// by a primal-dual interior-point method, whose systems keep one sparsity pattern (ordered
// and analysed once, factorized numerically at each iteration), solved through the
// bodies. Reads the free vectors and the rows; writes the impulses it finds. Knows
// nothing of the StepContext.
#pragma once

#include "contact_solver.hpp"

#include <Eigen/SparseCore>

namespace ball_collision_sim::core::step
{
/// A, the rows' W = J M^-1 J^T (its lower triangle, its diagonal a little larger:
/// `regularization` of itself), its diagonal as it is, and the right side, the rows'
/// closings past their targets at u_free; over the rows `active`.
struct PushingSystem
{
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd diagonal;
  Eigen::VectorXd rhs;
};
PushingSystem pushingSystem(const std::vector<Vec3>& u_free, const std::vector<double>& inv,
                            const std::vector<ContactRow>& rows, const std::vector<int>& active, double regularization);

/// The impulses of the problem with A's diagonal a little larger (positive definite: one
/// answer) over all `rows`: lambda >= 0, w = A lambda - (closing - target) >= 0, lambda w
/// = 0, by Mehrotra's predictor-corrector interior-point method on that linear
/// complementarity problem (Wright, Primal-Dual Interior-Point Methods, 1997, ch. 8 and
/// 10). Each iteration solves (A + W / Lambda) d = r twice, through the bodies' system
/// M + J^T (eps D + W / Lambda)^-1 J. It stops where the mean lambda w falls below 1e-30
/// of the problem's own scale (rows on the fence, where both go to zero, have them near
/// its square root: 1e-15, so that taking their impulses away moves no other row by more
/// than round-off) and the residual below 1e-13 of the closings, or after `iterations`.
/// Out: lambda, its impulses there on the rows it found to push (those its impulse closes
/// by more than they open, lambda A_ii > w; within the problem, lambda w is at most about
/// 1e-30 of the scale), 0 on the others; and true where it converged.
bool solveInterior(const std::vector<Vec3>& u_free, const std::vector<double>& inv, const std::vector<ContactRow>& rows,
                   std::vector<double>& lambda, double regularization, int iterations);
}  // namespace ball_collision_sim::core::step
