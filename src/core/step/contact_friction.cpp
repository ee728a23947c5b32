// Friction at resting contacts (contact_friction.hpp): reads the rows, the pairs and the
// bodies' inverse masses; writes the vectors, the spins and the impulses.
#include "contact_friction.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core::step
{
namespace
{
struct Bodies
{
  std::vector<Vec3>& u;
  const std::vector<double>& inv_mass;
  Spins spins;

  double slipOf(const ContactRow& n, const FrictionRow& f) const
  {
    double s = u[n.a].dot(f.push_a) + spins.w[n.a].dot(f.turn_a);
    if (n.b != ContactRow::kImmovable)
      s -= u[n.b].dot(f.push_b) + spins.w[n.b].dot(f.turn_b);
    return s;
  }
  double turnOf(std::uint32_t k) const { return inverseMassOf(spins.inv_inertia, k); }
  /// how much a unit impulse along f changes its slip
  double responseOf(const ContactRow& n, const FrictionRow& f) const
  {
    double k = inverseMassOf(inv_mass, n.a) * f.push_a.squaredNorm() + turnOf(n.a) * f.turn_a.squaredNorm();
    if (n.b != ContactRow::kImmovable)
      k += inverseMassOf(inv_mass, n.b) * f.push_b.squaredNorm() + turnOf(n.b) * f.turn_b.squaredNorm();
    return k;
  }
  void apply(const ContactRow& n, const FrictionRow& f, double d)
  {
    u[n.a] -= (d * inverseMassOf(inv_mass, n.a)) * f.push_a;
    spins.w[n.a] -= (d * turnOf(n.a)) * f.turn_a;
    if (n.b == ContactRow::kImmovable)
      return;
    u[n.b] += (d * inverseMassOf(inv_mass, n.b)) * f.push_b;
    spins.w[n.b] += (d * turnOf(n.b)) * f.turn_b;
  }
};

/// Each pair's directions, in turn, take the impulse that stops their slip, within the
/// disc its normal impulse allows where the other direction is (a pair outside its disc,
/// its normal impulse having dropped, goes back onto it first). The largest change of a
/// slip it made.
double sweepFriction(Bodies& bodies, const std::vector<ContactRow>& rows, std::vector<FrictionPair>& pairs,
                     const std::vector<std::array<double, 2>>& response)
{
  double change = 0.0;
  for (std::size_t p = 0; p < pairs.size(); ++p)
  {
    FrictionPair& pair = pairs[p];
    const ContactRow& n = rows[pair.normal];
    const double bound = pair.mu * std::max(n.impulse, 0.0);
    const double size = std::hypot(pair.rows[0].impulse, pair.rows[1].impulse);
    const double scale = size > bound ? bound / size : 1.0;
    for (std::size_t k = 0; k < 2; ++k)
    {
      FrictionRow& f = pair.rows[k];
      if (scale < 1)
      {
        const double next = scale * f.impulse;
        bodies.apply(n, f, next - f.impulse);
        change = std::max(change, std::abs(next - f.impulse) * response[p][k]);
        f.impulse = next;
      }
    }
    for (std::size_t k = 0; k < 2; ++k)
    {
      FrictionRow& f = pair.rows[k];
      if (!(response[p][k] > 0))
        continue;
      const double other = pair.rows[1 - k].impulse;
      const double reach = std::sqrt(std::max(bound * bound - other * other, 0.0));
      const double next = std::clamp(f.impulse + bodies.slipOf(n, f) / response[p][k], -reach, reach);
      const double d = next - f.impulse;
      if (d == 0)
        continue;
      bodies.apply(n, f, d);
      f.impulse = next;
      change = std::max(change, std::abs(d) * response[p][k]);
    }
  }
  return change;
}

std::vector<std::array<double, 2>> responses(const Bodies& bodies, const std::vector<ContactRow>& rows,
                                             const std::vector<FrictionPair>& pairs)
{
  std::vector<std::array<double, 2>> out(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (std::size_t k = 0; k < 2; ++k) out[p][k] = bodies.responseOf(rows[pairs[p].normal], pairs[p].rows[k]);
  return out;
}
}  // namespace

void applyFriction(std::vector<Vec3>& u, const std::vector<double>& inv_mass, const std::vector<ContactRow>& rows,
                   Spins spins, const std::vector<FrictionPair>& pairs)
{
  Bodies bodies{u, inv_mass, spins};
  for (const FrictionPair& pair : pairs)
    for (const FrictionRow& f : pair.rows) bodies.apply(rows[pair.normal], f, f.impulse);
}

ContactSolve solveWithFriction(std::vector<Vec3>& u, const std::vector<double>& inv_mass, std::vector<ContactRow>& rows,
                               Spins spins, std::vector<FrictionPair>& pairs, double tolerance, int max_sweeps)
{
  const std::vector<double> opens = startRows(u, inv_mass, rows);
  Bodies bodies{u, inv_mass, spins};
  applyFriction(u, inv_mass, rows, spins, pairs);  // (friction's warm start)
  const std::vector<std::array<double, 2>> response = responses(bodies, rows, pairs);
  ContactSolve out;
  while (out.sweeps < max_sweeps)
  {
    ++out.sweeps;
    const double change = std::max(sweepRows(u, inv_mass, rows, opens), sweepFriction(bodies, rows, pairs, response));
    out.residual = largestPastTarget(u, rows);
    if (change <= tolerance && out.residual <= tolerance)
    {
      out.converged = true;
      break;
    }
  }
  return out;
}

bool solveFrictionally(const std::vector<Vec3>& u_free, const std::vector<Vec3>& w_free, std::vector<Vec3>& u,
                       const std::vector<double>& inv_mass, std::vector<ContactRow>& rows, Spins spins,
                       std::vector<FrictionPair>& pairs, double slack, int sweeps, int passes,
                       const ExactSettings& exact)
{
  if (solveWithFriction(u, inv_mass, rows, spins, pairs, slack, sweeps).converged)
    return true;
  Bodies bodies{u, inv_mass, spins};
  const std::vector<std::array<double, 2>> response = responses(bodies, rows, pairs);
  std::vector<Vec3> held;
  for (int pass = 1;; ++pass)
  {
    // the normal rows exactly, friction held where the last solve left it ...
    held = u_free;
    spins.w = w_free;
    applyFriction(held, inv_mass, rows, spins, pairs);
    if (!solveContactsExactly(held, inv_mass, rows, u, slack, exact))
      return false;
    if (pass >= passes)
      return true;
    // ... and friction again under the normal impulses found, until it no longer changes
    bool changed = false;
    for (int sweep = 0; sweep < sweeps; ++sweep)
    {
      if (!(sweepFriction(bodies, rows, pairs, response) > slack))
        break;
      changed = true;
    }
    if (!changed)
      return true;
  }
}
}  // namespace ball_collision_sim::core::step
