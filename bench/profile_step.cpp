// Steps one benchmark scene a given number of times and prints what it did: a small,
// deterministic program to run under a profiler (valgrind --tool=callgrind, perf record).
//   profile_step s1|s2|s3|s4|s5 [balls] [steps]
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
  using ball_collision_sim::core::World;
  namespace bench = ball_collision_sim::bench;
  const std::string scene = argc > 1 ? argv[1] : "s1";
  const int balls = argc > 2 ? std::atoi(argv[2]) : 10000;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 100;
  if ((scene != "s1" && scene != "s2" && scene != "s3" && scene != "s4" && scene != "s5") || balls <= 0 ||
      steps <= 0)
  {
    std::fprintf(stderr, "usage: profile_step s1|s2|s3|s4|s5 [balls > 0] [steps > 0]\n");
    return 2;
  }
  World world(scene == "s1"   ? bench::billiards(balls)
              : scene == "s2" ? bench::bullets()
              : scene == "s3" ? bench::bowl(balls)
              : scene == "s4" ? bench::bowlPile(balls)
                              : bench::gasInFlight(balls));
  const double n = static_cast<double>(world.balls().size());
  const double k0 = world.energy().kinetic;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k)
    world.step();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %.0f balls, %d steps, %.1f ns per ball-step, %.4f events per ball-step, kinetic end/start %.15f, "
              "lost %d, state hash %016llx\n",
              scene.c_str(), n, steps, 1e9 * seconds / (n * steps),
              static_cast<double>(world.stats().events) / (n * steps), world.energy().kinetic / k0,
              world.lostBalls(), static_cast<unsigned long long>(world.stateHash()));
  return 0;
}
