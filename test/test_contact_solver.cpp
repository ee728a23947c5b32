// The contact solver (src/core/step/contact_solver.hpp) on its own: closed forms of
// jams at rest, and the unique solution of a linear complementarity problem found by
// trying every set of active contacts, by its sweeps and by its exact stage.
#include "core/step/contact_solver.hpp"
#include "jam_rows.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

using namespace ball_collision_sim::core;
using step::ContactRow;
using step::solveContacts;
using ball_collision_sim::test::JamRows;
using ball_collision_sim::test::jamRows;

namespace
{
Vec3 along(const Vec3& d, const Vec3& n) { return d - d.dot(n) * n; }

ContactRow pair(std::uint32_t a, std::uint32_t b, const Vec3& normal, const Vec3& na, const Vec3& nb)
{
  ContactRow row;
  row.a = a;
  row.b = b;
  row.push_a = along(normal, na);
  row.push_b = along(normal, nb);
  return row;
}
}  // namespace

// Three equal balls at the bottom of the bowl z = a (x^2 + y^2), their feet on a circle
// of radius f, each touching the other two, each pulled along the floor by a step's worth
// of gravity, dt g_t. Held by each other, none moves: the solver takes every velocity to
// zero along the floor, with the same impulse at each contact, 2 a f m g dt / sqrt(3)
// (each ball's two contacts push it out along the floor as hard as gravity pulls it in).
TEST(ContactSolver, JamOfThreeInTheBowl)
{
  const double a = 0.125, r = 0.1, m = 0.7, g = 9.81, dt = 0.01;
  // feet at f: the centres, r along the normals, are 2 r apart
  double f = 0.1;
  for (int k = 0; k < 100; ++k)
  {
    const double s = std::sqrt(1 + 4 * a * a * f * f);
    f = 2 * r / std::sqrt(3.0) + r * 2 * a * f / s;  // centre radius = f - r 2 a f / s
  }
  std::array<Vec3, 3> centre, normal;
  std::vector<Vec3> u(3);
  for (int k = 0; k < 3; ++k)
  {
    const double phi = 2 * M_PI * k / 3 + 0.4;
    const Vec3 er(std::cos(phi), std::sin(phi), 0);
    normal[k] = (Vec3(0, 0, 1) - 2 * a * f * er).normalized();
    centre[k] = f * er + Vec3(0, 0, a * f * f) + r * normal[k];
    u[k] = dt * along(Vec3(0, 0, -g), normal[k]);
  }
  ASSERT_NEAR((centre[0] - centre[1]).norm(), 2 * r, 1e-12);
  std::vector<ContactRow> rows;
  for (const auto& [i, j] : {std::pair{0u, 1u}, std::pair{0u, 2u}, std::pair{1u, 2u}})
    rows.push_back(pair(i, j, (centre[j] - centre[i]).normalized(), normal[i], normal[j]));
  const std::vector<double> inv(3, 1 / m);
  const auto onFloor = [&](std::vector<Vec3>& w) {
    for (int k = 0; k < 3; ++k)
      w[k] = along(w[k], normal[k]);
  };
  const auto solve = solveContacts(u, inv, rows, 1e-16 * g * dt, 500, onFloor);
  EXPECT_TRUE(solve.converged);
  const double expected = 2 * a * f * m * g * dt / std::sqrt(3.0);
  for (const ContactRow& row : rows)
    EXPECT_NEAR(row.impulse, expected, 1e-12 * expected);
  for (const Vec3& w : u)
    EXPECT_LT(w.norm(), 1e-12 * g * dt);

  // warm started with what it found, one sweep does
  std::vector<Vec3> again(3);
  for (int k = 0; k < 3; ++k)
    again[k] = dt * along(Vec3(0, 0, -g), normal[k]);
  const auto warm = solveContacts(again, inv, rows, 1e-16 * g * dt, 500, onFloor);
  EXPECT_TRUE(warm.converged);
  EXPECT_EQ(warm.sweeps, 1);
}

// Three balls of different masses in a triangle on a plane, pulled every which way: the
// solver's impulses are the linear complementarity problem's unique solution (W lambda =
// closing on the active contacts, lambda >= 0, no closing left on the others), found
// here by trying every set of active contacts.
TEST(ContactSolver, MatchesTheExactSolutionOfAnOffCentreJam)
{
  const std::array<Vec3, 3> centre = {Vec3(0, 0, 0), Vec3(0.2, 0, 0), Vec3(0.1, 0.17320508075688773, 0)};
  const std::vector<double> inv = {1 / 0.5, 1 / 2.0, 1 / 1.3};
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 3> pairs = {{{0, 1}, {0, 2}, {1, 2}}};
  const Vec3 up(0, 0, 1);
  for (const Vec3& pull : {Vec3(0.3, 0.1, 0), Vec3(-0.2, 0.5, 0), Vec3(0.05, -0.4, 0)})
  {
    // every ball pulled toward the triangle's middle, and each along `pull` by its own part
    const Vec3 middle = (centre[0] + centre[1] + centre[2]) / 3;
    std::vector<Vec3> free(3);
    for (int k = 0; k < 3; ++k)
      free[k] = (middle - centre[k]) * (1.0 + k) + (3.0 * k - 2.0) * pull;
    std::vector<ContactRow> rows;
    for (const auto& [i, j] : pairs)
      rows.push_back(pair(i, j, (centre[j] - centre[i]).normalized(), up, up));
    // W and the free closings
    Eigen::Matrix3d W;
    Eigen::Vector3d c;
    for (int p = 0; p < 3; ++p)
    {
      c(p) = free[rows[p].a].dot(rows[p].push_a) - free[rows[p].b].dot(rows[p].push_b);
      for (int q = 0; q < 3; ++q)
      {
        double w = 0;
        if (rows[q].a == rows[p].a)
          w += inv[rows[p].a] * rows[q].push_a.dot(rows[p].push_a);
        if (rows[q].b == rows[p].a)
          w -= inv[rows[p].a] * rows[q].push_b.dot(rows[p].push_a);
        if (rows[q].a == rows[p].b)
          w -= inv[rows[p].b] * rows[q].push_a.dot(rows[p].push_b);
        if (rows[q].b == rows[p].b)
          w += inv[rows[p].b] * rows[q].push_b.dot(rows[p].push_b);
        W(p, q) = w;
      }
    }
    Eigen::Vector3d exact = Eigen::Vector3d::Constant(-1);
    for (int set = 0; set < 8; ++set)
    {
      Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
      std::vector<int> active;
      for (int p = 0; p < 3; ++p)
        if (set & (1 << p))
          active.push_back(p);
      Eigen::MatrixXd Wa(active.size(), active.size());
      Eigen::VectorXd ca(active.size());
      for (std::size_t p = 0; p < active.size(); ++p)
      {
        ca(p) = c(active[p]);
        for (std::size_t q = 0; q < active.size(); ++q)
          Wa(p, q) = W(active[p], active[q]);
      }
      if (!active.empty())
      {
        const Eigen::VectorXd la = Wa.ldlt().solve(ca);
        for (std::size_t p = 0; p < active.size(); ++p)
          lambda(active[p]) = la(p);
      }
      const Eigen::Vector3d left = c - W * lambda;  // closing after the impulses
      if (lambda.minCoeff() >= -1e-14 && left.maxCoeff() <= 1e-14)
        exact = lambda;
    }
    ASSERT_GE(exact.minCoeff(), -1e-14) << "no solution found: " << pull.transpose();
    std::vector<Vec3> u = free;
    const auto solve = solveContacts(u, inv, rows, 1e-15, 1000);
    EXPECT_TRUE(solve.converged) << pull.transpose();
    for (int p = 0; p < 3; ++p)
      EXPECT_NEAR(rows[p].impulse, exact(p), 1e-12) << pull.transpose() << " contact " << p;
    // and the velocities are the free ones plus those impulses
    std::vector<Vec3> expected = free;
    for (int p = 0; p < 3; ++p)
    {
      expected[rows[p].a] -= exact(p) * inv[rows[p].a] * rows[p].push_a;
      expected[rows[p].b] += exact(p) * inv[rows[p].b] * rows[p].push_b;
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_LT((u[k] - expected[k]).norm(), 1e-12) << pull.transpose() << " ball " << k;
  }
}

// The exact stage (step::solveContactsExactly()) on its own, from no guess of which
// contacts push: six balls on a plane, eight contacts among them and with two walls, each
// allowed to close by a gap of its own; random masses and free motions. Its impulses and
// motions are those of the unique solution found by trying all 256 sets of pushing
// contacts, to 1e-12.
TEST(ContactSolver, TheExactStageFindsWhichContactsPush)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 up(0, 0, 1);
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 8> pairs = {
      {{0, 1}, {1, 2}, {0, 2}, {2, 3}, {3, 4}, {4, 5}, {3, 5}, {0, ContactRow::kImmovable}}};
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<double> inv(6);
    std::vector<Vec3> free(6);
    for (int k = 0; k < 6; ++k)
    {
      inv[k] = 1 / (1.5 + unit(rng));
      free[k] = Vec3(unit(rng), unit(rng), 0);
    }
    std::vector<ContactRow> rows;
    for (const auto& [i, j] : pairs)
    {
      const Vec3 normal = Vec3(unit(rng), unit(rng), 0).normalized();
      ContactRow row = pair(i, j, normal, up, up);
      row.target = 0.2 * (unit(rng) + 1);  // (the gap it may close by)
      rows.push_back(row);
    }
    const auto closings = [&](const std::vector<Vec3>& u) {
      Eigen::VectorXd c(rows.size());
      for (std::size_t p = 0; p < rows.size(); ++p)
        c(static_cast<int>(p)) = step::closingOf(u, rows[p]) - rows[p].target;
      return c;
    };
    const auto apply = [&](const Eigen::VectorXd& lambda) {
      std::vector<Vec3> u = free;
      for (std::size_t p = 0; p < rows.size(); ++p)
      {
        u[rows[p].a] -= lambda(static_cast<int>(p)) * inv[rows[p].a] * rows[p].push_a;
        if (rows[p].b != ContactRow::kImmovable)
          u[rows[p].b] += lambda(static_cast<int>(p)) * inv[rows[p].b] * rows[p].push_b;
      }
      return u;
    };
    // W column by column: what a unit impulse at each contact does to every closing
    Eigen::MatrixXd W(8, 8);
    const Eigen::VectorXd c0 = closings(free);
    for (int q = 0; q < 8; ++q)
      W.col(q) = c0 - closings(apply(Eigen::VectorXd::Unit(8, q)));
    Eigen::VectorXd exact = Eigen::VectorXd::Constant(8, -1);
    for (int set = 0; set < 256; ++set)
    {
      std::vector<int> active;
      for (int p = 0; p < 8; ++p)
        if (set & (1 << p))
          active.push_back(p);
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(8);
      if (!active.empty())
      {
        Eigen::MatrixXd Wa(active.size(), active.size());
        Eigen::VectorXd ca(active.size());
        for (std::size_t p = 0; p < active.size(); ++p)
        {
          ca(static_cast<int>(p)) = c0(active[p]);
          for (std::size_t q = 0; q < active.size(); ++q)
            Wa(static_cast<int>(p), static_cast<int>(q)) = W(active[p], active[q]);
        }
        const Eigen::VectorXd la = Wa.ldlt().solve(ca);
        for (std::size_t p = 0; p < active.size(); ++p)
          lambda(active[p]) = la(static_cast<int>(p));
      }
      if (lambda.minCoeff() >= -1e-13 && (c0 - W * lambda).maxCoeff() <= 1e-13)
        exact = lambda;
    }
    ASSERT_GE(exact.minCoeff(), -1e-13) << "trial " << trial;
    std::vector<Vec3> u = free;
    step::ExactSettings stage;
    stage.rounds = 64;
    ASSERT_TRUE(step::solveContactsExactly(free, inv, rows, u, 1e-13, stage)) << "trial " << trial;
    const std::vector<Vec3> expected = apply(exact);
    for (int p = 0; p < 8; ++p)
      EXPECT_NEAR(rows[static_cast<std::size_t>(p)].impulse, exact(p), 1e-12) << "trial " << trial << " contact " << p;
    for (int k = 0; k < 6; ++k)
      EXPECT_LT((u[static_cast<std::size_t>(k)] - expected[static_cast<std::size_t>(k)]).norm(), 1e-12)
          << "trial " << trial << " ball " << k;
  }
}

// A jam whose contacts say the same: balls stacked four layers deep in square packing
// (each on four below it) between the five walls of a box they fill, their places off by
// up to 1e-6 of a radius, each pushed down and sideways at random. The exact stage's
// matrix is near singular and its impulses come out with either sign, so that pivoting
// alone goes round without settling; the exact stage still finds the answer, from the
// sweeps' guess or from none: no impulse pulls, no contact closes past its target, those
// that push close to it within the regularization's share (1e-10 of their push), the
// motions are the same from either start (the answer's motions are unique), and no
// kinetic energy is made.
TEST(ContactSolver, TheExactStageSettlesAJamWhoseContactsSayTheSame)
{
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 10; ++trial)
  {
    const JamRows jam = jamRows(4, 1, rng);
    const std::vector<Vec3>& free = jam.free;
    const std::vector<double>& inv = jam.inv;
    const std::vector<ContactRow>& rows = jam.rows;
    const std::size_t n = free.size();
    ASSERT_GT(rows.size(), 3 * n) << "trial " << trial;  // (more contacts than the balls can move along)
    std::vector<std::vector<Vec3>> answers;
    for (const bool guess : {true, false})
    {
      std::vector<ContactRow> solved = rows;
      std::vector<Vec3> u = free;
      if (guess)
        solveContacts(u, inv, solved, 1e-15, 20);
      ASSERT_TRUE(step::solveContactsExactly(free, inv, solved, u, 1e-15, step::ExactSettings{}))
          << "trial " << trial << " guess " << guess;
      double kinetic_free = 0, kinetic = 0;
      for (std::size_t k = 0; k < n; ++k)
      {
        kinetic_free += free[k].squaredNorm() / inv[k];
        kinetic += u[k].squaredNorm() / inv[k];
      }
      EXPECT_LE(kinetic, kinetic_free) << "trial " << trial;
      for (const ContactRow& row : solved)
      {
        // (a pushing row closes past its target by at most the regularization's share,
        // 1e-10 of what its own impulse opens it by, twice over for round-off)
        const double opens = inv[row.a] + (row.b == ContactRow::kImmovable ? 0.0 : inv[row.b]);
        const double share = 2 * step::ExactSettings{}.regularization * opens * row.impulse + 1e-14;
        const double past = step::closingOf(u, row) - row.target;
        EXPECT_GE(row.impulse, 0.0) << "trial " << trial;
        EXPECT_LE(past, row.impulse > 0 ? share : 1e-14) << "trial " << trial;
        if (row.impulse > 0)
        {
          EXPECT_GE(past, -share) << "trial " << trial;
        }
      }
      answers.push_back(u);
    }
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_LT((answers[0][k] - answers[1][k]).norm(), 1e-8) << "trial " << trial << " ball " << k;
  }
}

// A ball pressed against a wall by another: both stop, and the wall takes the second
// ball's whole momentum through the first.
TEST(ContactSolver, ChainAgainstAWall)
{
  const double mb = 3.0, s = 0.25;
  std::vector<Vec3> u = {Vec3::Zero(), Vec3(-s, 0, 0)};
  const std::vector<double> inv = {1 / 1.0, 1 / mb};
  ContactRow wall;
  wall.a = 0;
  wall.push_a = Vec3(-1, 0, 0);  // the wall lies to the left of ball 0
  const ContactRow between = pair(0, 1, Vec3(1, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
  std::vector<ContactRow> rows = {wall, between};
  const auto solve = solveContacts(u, inv, rows, 1e-15, 200);
  EXPECT_TRUE(solve.converged);
  EXPECT_LT(u[0].norm(), 1e-15);
  EXPECT_LT(u[1].norm(), 1e-15);
  EXPECT_NEAR(rows[0].impulse, mb * s, 1e-14);
  EXPECT_NEAR(rows[1].impulse, mb * s, 1e-14);
}

// Contacts that open push nothing: the bodies' vectors are left bit for bit.
TEST(ContactSolver, OpeningContactsPushNothing)
{
  std::vector<Vec3> u = {Vec3(-0.3, 0.1, 0), Vec3(0.2, 0.7, 0)};
  const std::vector<Vec3> before = u;
  std::vector<ContactRow> rows = {pair(0, 1, Vec3(1, 0, 0), Vec3::UnitZ(), Vec3::UnitZ())};
  const auto solve = solveContacts(u, {1.0, 1.0}, rows, 1e-15, 10);
  EXPECT_TRUE(solve.converged);
  EXPECT_EQ(solve.sweeps, 1);
  EXPECT_EQ(rows[0].impulse, 0.0);
  EXPECT_EQ(u[0], before[0]);
  EXPECT_EQ(u[1], before[1]);
}

// A contact neither body can give way along stays closing, and the solve says so.
TEST(ContactSolver, ContactNoBodyCanGiveIsReported)
{
  std::vector<Vec3> u = {Vec3(0.5, 0, 0)};
  ContactRow wall;
  wall.push_a = Vec3(1, 0, 0);
  std::vector<ContactRow> rows = {wall};
  const auto solve = solveContacts(u, {0.0}, rows, 1e-15, 10);
  EXPECT_FALSE(solve.converged);
  EXPECT_EQ(solve.sweeps, 10);
  EXPECT_DOUBLE_EQ(solve.residual, 0.5);
  EXPECT_EQ(u[0], Vec3(0.5, 0, 0));
}

// A bounce: a row's target below zero separates the bodies at that speed.
TEST(ContactSolver, TargetOfABounce)
{
  const double e = 0.5, v = 2.0;
  std::vector<Vec3> u = {Vec3(v, 0, 0), Vec3::Zero()};
  ContactRow row = pair(0, 1, Vec3(1, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
  row.target = -e * v;
  std::vector<ContactRow> rows = {row};
  solveContacts(u, {1.0, 1.0}, rows, 1e-15, 10);
  // equal masses: the closed form of a collision at restitution e
  EXPECT_NEAR(u[0].x(), 0.5 * (1 - e) * v, 1e-15);
  EXPECT_NEAR(u[1].x(), 0.5 * (1 + e) * v, 1e-15);
  EXPECT_NEAR(rows[0].impulse, 0.5 * (1 + e) * v, 1e-15);
}

// Whatever the vectors and the pushes (velocities off the floor, pushes of any length
// and direction, walls and bodies at rest among the contacts), no sweep adds kinetic energy: each update
// of one contact changes it by -c^2 / 2K. Checked after every number of sweeps from 1.
TEST(ContactSolver, NoSweepAddsKineticEnergy)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-1.0, 1.0);
  const auto vec = [&] { return Vec3(any(rng), any(rng), any(rng)); };
  for (int trial = 0; trial < 200; ++trial)
  {
    const std::uint32_t n = 2 + static_cast<std::uint32_t>(rng() % 6);
    std::vector<Vec3> start(n);
    std::vector<double> inv(n);
    for (std::uint32_t k = 0; k < n; ++k)
    {
      // (a body that does not give way is at rest: a moving one could add energy)
      inv[k] = rng() % 5 == 0 ? 0.0 : 0.1 + 2 * std::abs(any(rng));
      start[k] = inv[k] > 0 ? vec() : Vec3::Zero();
    }
    std::vector<ContactRow> rows;
    for (int r = 0; r < 2 * static_cast<int>(n); ++r)
    {
      ContactRow row;
      row.a = static_cast<std::uint32_t>(rng() % n);
      row.b = rng() % 4 == 0 ? ContactRow::kImmovable : static_cast<std::uint32_t>(rng() % n);
      if (row.b == row.a)
        row.b = ContactRow::kImmovable;
      row.push_a = vec();
      row.push_b = vec();
      rows.push_back(row);
    }
    const auto kinetic = [&](const std::vector<Vec3>& u) {
      double e = 0;
      for (std::uint32_t k = 0; k < n; ++k)
        if (inv[k] > 0)
          e += 0.5 * u[k].squaredNorm() / inv[k];
      return e;
    };
    const double before = kinetic(start);
    for (int sweeps = 1; sweeps <= 8; ++sweeps)
    {
      std::vector<Vec3> u = start;
      std::vector<ContactRow> mine = rows;
      solveContacts(u, inv, mine, 0.0, sweeps);
      EXPECT_LE(kinetic(u), before * (1 + 1e-14) + 1e-300) << "trial " << trial << ", " << sweeps << " sweeps";
      for (const ContactRow& row : mine)
        EXPECT_GE(row.impulse, 0.0);
    }
  }
}
