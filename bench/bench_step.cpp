// Google Benchmark of the core's step on the benchmark scenes. Reports ns per ball-step;
// run through bench/run_bench, which keeps the results as CSV per machine.
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <utility>

namespace
{
using ball_collision_sim::core::World;

/// Steps the world once per iteration after a warm-up (a short one by default).
void runSteps(benchmark::State& state, World world, int warm_up = 10)
{
  for (int k = 0; k < warm_up; ++k)
    world.step();
  const double balls = static_cast<double>(world.balls().size());
  const double k0 = world.energy().kinetic;
  const double e0 = world.energy().total();
  const auto events0 = world.stats().events;
  const auto steps0 = world.stats().steps;
  for (auto _ : state)
    world.step();
  // items are ball-steps: ns per ball-step = 1e9 / items_per_second
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(balls));
  // (the steps measured only, not the warm-up's)
  state.counters["events_per_ball_step"] =
      static_cast<double>(world.stats().events - events0) / (static_cast<double>(world.stats().steps - steps0) * balls);
  // (a pile asleep at the start and the end has no kinetic energy: nothing changed)
  const double k1 = world.energy().kinetic;
  state.counters["kinetic_end_over_start"] = k0 > 0 ? k1 / k0 : k1 == 0 ? 1.0 : HUGE_VAL;
  state.counters["energy_end_over_start"] = world.energy().total() / e0;
  state.counters["balls_lost"] = world.lostBalls();
}

void BM_S1Billiards(benchmark::State& state)
{
  runSteps(state, World(ball_collision_sim::bench::billiards(static_cast<int>(state.range(0)))));
}
BENCHMARK(BM_S1Billiards)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// The first 10 s of the table with friction (1000 steps), while its balls slide, roll
/// and stop; later it is all at rest and costs next to nothing.
void BM_S1Friction(benchmark::State& state)
{
  runSteps(state, World(ball_collision_sim::bench::billiardsFriction(static_cast<int>(state.range(0)))));
}
BENCHMARK(BM_S1Friction)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1000);

void BM_S2Bullets(benchmark::State& state)
{
  runSteps(state, World(ball_collision_sim::bench::bullets()));
}
BENCHMARK(BM_S2Bullets)->Unit(benchmark::kMillisecond)->MinTime(1.0);

void BM_S3Bowl(benchmark::State& state)
{
  runSteps(state, World(ball_collision_sim::bench::bowl(static_cast<int>(state.range(0)))));
}
BENCHMARK(BM_S3Bowl)->Arg(1000)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// The pile at rest (with friction, bench::bowlPileAtRest()): stepped until every ball
/// sleeps (at most 60 s), asleep on a curved floor; its label says how many did, after how
/// many steps.
void BM_S4BowlPile(benchmark::State& state)
{
  World world(ball_collision_sim::bench::bowlPileAtRest(static_cast<int>(state.range(0))));
  for (int k = 0; k < 6000 && world.stats().sleeping_balls < world.balls().size(); ++k)
    world.step();
  // (a label, not counters: the CSV report wants every benchmark to have the same counters)
  state.SetLabel(std::to_string(world.stats().sleeping_balls) + " asleep after " + std::to_string(world.stats().steps) +
                 " steps");
  runSteps(state, std::move(world), 0);
}
BENCHMARK(BM_S4BowlPile)->Arg(200)->Unit(benchmark::kMillisecond)->MinTime(2.0);
}  // namespace

BENCHMARK_MAIN();
