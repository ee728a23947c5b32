// Square-packed jams in the world (fixtures::squareJam(): balls of 0.1 m in a floorless
// box of five walls that they fill), stepped at e = 0.5: whether every group's contacts
// were solved, the largest rise of the energy in a step (over the energy's scale, the
// kinetic energy plus the potential across the jam's height), the deepest overlap, and
// the time. CSV: balls, start, steps, unsettled_contacts, energy_rise, overlap_m, seconds.
// Usage: jams_world BASE TOP STEPS [START...]   (default starts 1 2 3 4)
#include "fixtures.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

int main(int argc, char** argv)
{
  if (argc < 4)
  {
    std::fprintf(stderr, "usage: jams_world BASE TOP STEPS [START...]\n");
    return 2;
  }
  const int base = std::atoi(argv[1]), top = std::atoi(argv[2]), steps = std::atoi(argv[3]);
  if (base < 1 || top < 1 || top > base || steps < 1)
  {
    std::fprintf(stderr, "jams_world: BASE >= TOP >= 1 and STEPS >= 1\n");
    return 2;
  }
  std::vector<std::uint64_t> starts;
  for (int a = 4; a < argc; ++a)
    starts.push_back(std::strtoull(argv[a], nullptr, 10));
  if (starts.empty())
    starts = {1, 2, 3, 4};
  std::printf("balls,start,steps,unsettled_contacts,energy_rise,overlap_m,seconds\n");
  for (const std::uint64_t start : starts)
  {
    World world(squareJam(base, top, start));
    double mass = 0.0;
    for (const Ball& b : world.balls())
      mass += b.mass;
    const double scale = world.energy().kinetic + mass * world.gravity().norm() * 0.2 * base;
    const auto t0 = std::chrono::steady_clock::now();
    const WorstOfRun worst = stepWatching(world, steps, [](int) { return true; });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%zu,%llu,%d,%llu,%.3g,%.3g,%.1f\n", world.balls().size(), static_cast<unsigned long long>(start), steps,
                static_cast<unsigned long long>(world.stats().unsettled_contacts), worst.energy_rise / scale,
                worst.overlap, seconds);
    std::fflush(stdout);
  }
}
