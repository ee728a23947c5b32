// How long dissipative piles take to come to rest and sleep: S4 at rest (200 and 300
// balls, with friction) and the piles of LongRun.DissipativePilesComeToRestAndSleep (60
// and 200 balls at e = 0.5 and 0.9, in the walled bowl with friction and against the wall
// at the foot of a 10 degree slope without) from five random starts each; and without a
// floor, 60 balls dropped into a box of five walls (fixtures::floorlessBoxDrop()) at e =
// 0.5 and 0.9 from three starts each. Each is stepped until every ball sleeps, at most 60 s.
// Prints CSV: the steps it took (-1: not in 60 s), the events and stopped balls until then,
// and the largest rise of the total energy in a step [J].
//   steps_to_sleep [LABEL]
#include "fixtures.hpp"
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace
{
using namespace ball_collision_sim::core;
namespace fixtures = ball_collision_sim::test;

// (the count of balls stopped where their energy ran out: WorldStats::stopped_balls,
// held_balls in versions before it)
template <class Stats>
auto stoppedOf(const Stats& stats, int) -> decltype(stats.stopped_balls)
{
  return stats.stopped_balls;
}
template <class Stats>
auto stoppedOf(const Stats& stats, long) -> decltype(stats.held_balls)
{
  return stats.held_balls;
}

void run(const std::string& label, const std::string& name, const Scene& scene)
{
  World world(scene);
  world.recordEvents(false);
  const std::size_t n = world.balls().size();
  int slept = -1;
  double rise = 0, before = world.energy().total();
  for (int k = 1; k <= 6000; ++k)
  {
    world.step();
    const double now = world.energy().total();
    rise = std::max(rise, now - before);
    before = now;
    if (world.stats().sleeping_balls == n)
    {
      slept = k;
      break;
    }
  }
  std::printf("%s,%s,%zu,%d,%llu,%llu,%.3g\n", label.c_str(), name.c_str(), n, slept,
              static_cast<unsigned long long>(world.stats().events),
              static_cast<unsigned long long>(stoppedOf(world.stats(), 0)), rise);
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv)
{
  const std::string label = argc > 1 ? argv[1] : "this";
  std::printf("version,scene,balls,steps_to_sleep,events,stopped_balls,largest_rise_J\n");
  run(label, "S4", ball_collision_sim::bench::bowlPileAtRest(200));
  run(label, "S4", ball_collision_sim::bench::bowlPileAtRest(300));
  for (const double e : {0.5, 0.9})
    for (const int n : {60, 200})
      for (const int seed : {4, 5, 6, 7, 8})
      {
        Scene bowl;
        bowl.floor = fixtures::bowl(3, 0.3);
        fixtures::addBox(bowl, -1.5, 1.5, -1.5, 1.5, 1.0);
        bowl.restitution = e;
        bowl.random_balls = fixtures::randomBalls(n, static_cast<std::uint64_t>(seed), {0.05, 0.08}, {0.5, 2}, {0, 1});
        bowl.friction = fixtures::pileFriction();
        const std::string tail = " e=" + std::to_string(e).substr(0, 3) + " seed " + std::to_string(seed);
        run(label, "bowl" + tail, bowl);
        run(label, "slope" + tail, fixtures::slopeWithWall(n, 10, e, static_cast<std::uint64_t>(seed), n > 100 ? 3.0 : 2.0));
      }
  for (const double e : {0.5, 0.9})
    for (const int seed : {4, 5, 6})
      run(label, "box without floor e=" + std::to_string(e).substr(0, 3) + " seed " + std::to_string(seed),
          fixtures::floorlessBoxDrop(60, e, static_cast<std::uint64_t>(seed)));
  return 0;
}
