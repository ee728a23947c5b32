// The contact solver's exact stage on tight jams: balls of one radius stacked in square
// packing (layers base x base down to top x top) in a box of five walls they fill, each off
// its place by up to 1e-6 of its radius and moving at random, as the test
// ContactSolver.TheExactStageSettlesAJamWhoseContactsSayTheSame builds them. Times each call
// of step::solveContactsExactly() after the sweeps, with the interior-point stage and
// without it (the primal active-set method alone), and prints CSV: balls, rows, start,
// method, ms, solved, kinetic energy after / before.
// Usage: exact_stage [BASE TOP]...   (default: 7 1, 8 1, 14 4: 140, 204 and 1001 balls)
#include "jam_rows.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::core::step;

namespace
{
double kinetic(const std::vector<Vec3>& u, const std::vector<double>& inv)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k)
    sum += u[k].squaredNorm() / inv[k];
  return sum;
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<std::pair<int, int>> sizes;
  for (int a = 1; a + 1 < argc; a += 2)
    sizes.emplace_back(std::atoi(argv[a]), std::atoi(argv[a + 1]));
  if ((argc - 1) % 2 != 0 || (argc > 1 && sizes.empty()))
  {
    std::fprintf(stderr, "usage: exact_stage [BASE TOP]...\n");
    return 2;
  }
  if (sizes.empty())
    sizes = {{7, 1}, {8, 1}, {14, 4}};
  std::printf("balls,rows,start,method,ms,solved,kinetic_after_over_before\n");
  for (const auto& [base, top] : sizes)
    for (std::uint64_t start = 1; start <= 4; ++start)
    {
      std::mt19937_64 rng(100 + start);
      const ball_collision_sim::test::JamRows jam = ball_collision_sim::test::jamRows(base, top, rng);
      // (the sweeps' guess, as the step gives it to the exact stage)
      std::vector<ContactRow> swept = jam.rows;
      std::vector<Vec3> u_swept = jam.free;
      solveContacts(u_swept, jam.inv, swept, 1e-15, 100);
      for (const bool interior : {true, false})
      {
        ExactSettings settings;
        settings.interior_iterations = interior ? settings.interior_iterations : 0;
        std::vector<ContactRow> rows = swept;
        std::vector<Vec3> u = u_swept;
        const auto t0 = std::chrono::steady_clock::now();
        const bool solved = solveContactsExactly(jam.free, jam.inv, rows, u, 1e-15, settings);
        const auto t1 = std::chrono::steady_clock::now();
        std::printf("%zu,%zu,%llu,%s,%.2f,%d,%.9g\n", jam.free.size(), jam.rows.size(),
                    static_cast<unsigned long long>(start), interior ? "interior" : "active_set",
                    std::chrono::duration<double, std::milli>(t1 - t0).count(), solved ? 1 : 0,
                    kinetic(solved ? u : jam.free, jam.inv) / kinetic(jam.free, jam.inv));
        std::fflush(stdout);
      }
    }
}
