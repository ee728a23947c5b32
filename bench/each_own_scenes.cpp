// Steps one scene as a version's own bench/scenes.hpp defines it, for
// bench/side_by_side_own_scenes, which builds this file against each version's core and
// scenes (the scenes' API changes between versions; this file uses only what they have
// had since before the step's stages: billiards, bullets, bowl and bowlPile).
//   each_own_scenes s1|s2|s3|s4rest BALLS STEPS
// s4rest: S4, the pile in the bowl, settled for 1,000 steps (10 s), untimed, then timed:
// with friction where the version's scenes have it (bowlPileAtRest; built with
// -DBCS_PILE_AT_REST), else without. Prints ns per ball-step, events per ball-step and the
// state hash.
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
  namespace bench = ball_collision_sim::bench;
  using ball_collision_sim::core::Scene;
  const std::string scene = argc > 1 ? argv[1] : "";
  const int balls = argc > 2 ? std::atoi(argv[2]) : 0;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 0;
  if ((scene != "s1" && scene != "s2" && scene != "s3" && scene != "s4rest") || balls <= 0 || steps <= 0)
  {
    std::fprintf(stderr, "usage: each_own_scenes s1|s2|s3|s4rest BALLS>0 STEPS>0\n");
    return 2;
  }
#ifdef BCS_PILE_AT_REST
  const auto pile = [](int n) { return bench::bowlPileAtRest(n); };
#else
  const auto pile = [](int n) { return bench::bowlPile(n); };
#endif
  const Scene s = scene == "s1"   ? bench::billiards(balls)
                  : scene == "s2" ? bench::bullets()
                  : scene == "s3" ? bench::bowl(balls)
                                  : pile(balls);
  ball_collision_sim::core::World world(s);
  for (int k = 0; scene == "s4rest" && k < 1000; ++k)
    world.step();
  const std::uint64_t events = world.stats().events;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k)
    world.step();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double n = static_cast<double>(world.balls().size());
  std::printf("%.1f %.4f %016llx\n", 1e9 * seconds / (n * steps),
              static_cast<double>(world.stats().events - events) / (n * steps),
              static_cast<unsigned long long>(world.stateHash()));
  return 0;
}
