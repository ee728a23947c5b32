// soak: a long run of S1 billiards (bench/scenes.hpp: balls of 0.05 m on a flat floor in a
// closed square box, restitution 1) checked as it goes: no NaN, no ball out of the box,
// no overlap deeper than 1e-9 m, total energy within 1e-9 of the
// starting kinetic energy. Run by
// scripts/soak; prints progress on stderr and one summary line on stdout; exits 1 when a
// check failed.
//   soak [--balls N] [--steps S] [--check-every K] [--seed SEED]
#include "fixtures.hpp"
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
using ball_collision_sim::core::Ball;
using ball_collision_sim::core::World;

constexpr double kEnergyTolerance = 1e-9;   // relative
constexpr double kOverlapTolerance = 1e-9;  // [m]
}  // namespace

int main(int argc, char** argv)
{
  int balls = 1000;
  long long steps = 1000000;
  long long check_every = 100;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string flag = argv[i];
    if (flag == "--balls")
      balls = std::atoi(argv[i + 1]);
    else if (flag == "--steps")
      steps = std::atoll(argv[i + 1]);
    else if (flag == "--check-every")
      check_every = std::max(1LL, std::atoll(argv[i + 1]));
    else if (flag == "--seed")
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    else
    {
      std::fprintf(stderr, "soak: unknown option %s\n", argv[i]);
      return 2;
    }
  }

  const ball_collision_sim::core::Scene scene = ball_collision_sim::bench::billiards(balls, seed);
  const double side = scene.floor->u.norm();
  World world(scene);
  const double e0 = world.energy().total();
  const double k0 = world.energy().kinetic;
  double worst_drift = 0, worst_overlap = -1e300;
  long long escaped = 0, non_finite = 0, checks = 0;
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  double last_report = 0;

  for (long long k = 1; k <= steps; ++k)
  {
    world.step();
    if (k % check_every != 0 && k != steps)
      continue;
    ++checks;
    for (const Ball& b : world.balls())
    {
      if (!b.position.allFinite() || !b.velocity.allFinite())
        ++non_finite;
      else if (b.position.x() < b.radius - kOverlapTolerance || b.position.x() > side - b.radius + kOverlapTolerance ||
               b.position.y() < b.radius - kOverlapTolerance || b.position.y() > side - b.radius + kOverlapTolerance)
        ++escaped;
    }
    escaped += world.lostBalls();
    // measured against the kinetic energy: the potential one is a constant on the flat floor
    worst_drift = std::max(worst_drift, std::abs(world.energy().total() - e0) / k0);
    worst_overlap = std::max(worst_overlap, ball_collision_sim::test::deepestOverlap(world.balls()));
    if (seconds() - last_report > 30 || k == steps)
    {
      last_report = seconds();
      std::fprintf(stderr, "soak: step %lld of %lld (%.0f%%), %.0f s, ETA %.0f s, drift %.2e, deepest overlap %.2e m\n", k,
                   steps, 100.0 * k / steps, last_report, last_report * (steps - k) / k, worst_drift, worst_overlap);
    }
  }
  const bool pass = non_finite == 0 && escaped == 0 && worst_drift <= kEnergyTolerance &&
                    worst_overlap <= kOverlapTolerance && world.balls().size() == static_cast<std::size_t>(balls);
  std::printf("soak: balls=%d steps=%lld simulated_s=%.0f wall_s=%.1f ns_per_ball_step=%.0f events=%llu "
              "frozen=%llu checks=%lld energy_start=%.12g energy_end=%.12g kinetic_start=%.12g "
              "energy_drift_max=%.3g deepest_overlap_m=%.3g escaped=%lld non_finite=%lld result=%s\n",
              balls, steps, steps * world.dt(), seconds(), 1e9 * seconds() / (static_cast<double>(steps) * balls),
              static_cast<unsigned long long>(world.stats().events),
              static_cast<unsigned long long>(world.stats().frozen_balls), checks, e0, world.energy().total(), k0,
              worst_drift, worst_overlap, escaped, non_finite, pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}
