// Steps S1 (bench/scenes.hpp) on a given number of threads, for bench/threads_speedup:
//   threads_step BALLS STEPS THREADS
// One untimed step first (the grid and the threads made), then STEPS timed; prints the
// wall ns per ball-step and the state hash, which is the same for every THREADS.
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv)
{
  const int balls = argc > 1 ? std::atoi(argv[1]) : 0;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 0;
  const int threads = argc > 3 ? std::atoi(argv[3]) : -1;
  if (balls <= 0 || steps <= 0 || threads < 0)
  {
    std::fprintf(stderr, "usage: threads_step BALLS>0 STEPS>0 THREADS>=0\n");
    return 2;
  }
  ball_collision_sim::core::StepSettings settings;
  settings.threads = static_cast<unsigned>(threads);
  ball_collision_sim::core::World world(ball_collision_sim::bench::billiards(balls), settings);
  world.recordEvents(false);
  world.step();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k)
    world.step();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%.1f %016llx\n", 1e9 * seconds / (static_cast<double>(balls) * steps),
              static_cast<unsigned long long>(world.stateHash()));
  return 0;
}
