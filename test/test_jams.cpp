// Tight jams come to rest: balls stacked in square packing in a box they fill (their
// contacts say the same, and the exact stage's matrix is near singular) have every group's
// contacts solved in every step, make no energy in any step, and do not overlap. 140 and
// 204 balls, four starts each (one under the sanitizers, BCS_SLOWDOWN, which run the
// core about 30 times slower and look for what it does to memory, not for one more start).
#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
std::vector<std::uint64_t> starts()
{
  if (std::getenv("BCS_SLOWDOWN") != nullptr)
    return {1};
  return {1, 2, 3, 4};
}

void expectSettles(int base, std::uint64_t seed, int steps)
{
  World world(squareJam(base, 1, seed));
  const std::string what = std::to_string(world.balls().size()) + " balls, start " + std::to_string(seed);
  double mass = 0.0;
  for (const Ball& b : world.balls())
    mass += b.mass;
  // (the scale of the energy: the kinetic energy, and the potential across the jam's height)
  const double scale = world.energy().kinetic + mass * world.gravity().norm() * 0.2 * base;
  const WorstOfRun worst = stepWatching(world, steps, [](int) { return true; });
  EXPECT_EQ(world.stats().unsettled_contacts, 0u) << what;
  EXPECT_LE(worst.energy_rise / scale, 1e-9) << what;
  EXPECT_LT(worst.overlap, 1e-9) << what;
  EXPECT_EQ(world.lostBalls(), 0) << what;
  EXPECT_GT(world.stats().resting_contacts, 0u) << what;  // (a jam: its contacts rest)
}
}  // namespace

TEST(Jams, OfHundredFortyBallsSettle)
{
  for (const std::uint64_t seed : starts())
    expectSettles(7, seed, 30);
}

TEST(Jams, OfTwoHundredFourBallsSettle)
{
  for (const std::uint64_t seed : starts())
    expectSettles(8, seed, 30);
}
