// The broad phase (include/ball_collision_sim/core/broad_phase.hpp) on its own: boxes
// rounded to floats, and the step's grid finding every overlapping pair as boxes are
// binned and then moved during a step, and giving up its cell order.
#include "ball_collision_sim/core/broad_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

using namespace ball_collision_sim::core;

TEST(Box32, HoldsTheBoxItIsRoundedFromAndIsTheTightestFloatBoxThatDoes)
{
  // The broad phase keeps its boxes in floats: a box that lost a sliver of the double box
  // it came from could miss a pair; one wider than needed costs candidate pairs.
  const float finf = std::numeric_limits<float>::infinity();
  const double inf = std::numeric_limits<double>::infinity(), fmax = std::numeric_limits<float>::max();
  const auto check = [&](double lo, double hi) {
    // (across the world's z and x axes, in that order)
    const Box32 f = Box32::around(Aabb{Vec3(-hi, 0, lo), Vec3(-lo, 0, hi)}, 2, 0);
    for (int k = 0; k < 2; ++k)
    {
      const double a = k == 1 ? -hi : lo, b = k == 1 ? -lo : hi;
      ASSERT_LE(f.min[k], a) << a;
      ASSERT_GE(f.max[k], b) << b;
      if (std::isfinite(a))
      {
        ASSERT_GT(std::nextafter(f.min[k], finf), a) << a;
      }
      if (std::isfinite(b))
      {
        ASSERT_LT(std::nextafter(f.max[k], -finf), b) << b;
      }
      if (std::abs(a) <= fmax)
      {
        ASSERT_GE(f.min[k], a - 3 * std::abs(a) * 0x1p-23 - 1e-36) << a;
      }
      if (std::abs(b) <= fmax)
      {
        ASSERT_LE(f.max[k], b + 3 * std::abs(b) * 0x1p-23 + 1e-36) << b;
      }
    }
  };
  // (fmax (1 + 2^-26) rounds to fmax, so its upper bound is the step to infinity)
  const double specials[] = {0.0, 1e-300, 1e-40, 1.0, 0.1, 3.4e38, fmax, fmax * (1 + 0x1p-26), 3.5e38, 1e300, inf};
  for (const double a : specials)
    for (const double b : specials)
    {
      check(std::min(a, b), std::max(a, b));
      check(-std::max(a, b), -std::min(a, b));
      check(-a, b);
    }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int k = 0; k < 100000; ++k)
  {
    const double a = unit(rng) * std::pow(10.0, static_cast<int>(rng() % 50) - 25);
    check(a, a + std::abs(unit(rng)) * std::abs(a) * 1e-6);
  }
  // overlap agrees with the double boxes wherever they are apart by more than the rounding
  // across the two axes it is made across (x and y here); apart along the third alone,
  // boxes overlap
  const auto xy = [](const Vec3& lo, const Vec3& hi) { return Box32::around(Aabb{lo, hi}, 0, 1); };
  const Box32 left = xy(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_TRUE(left.overlaps(xy(Vec3(1, 0.5, 0.5), Vec3(2, 2, 2))));
  EXPECT_FALSE(left.overlaps(xy(Vec3(1 + 1e-6, 0, 0), Vec3(2, 1, 1))));
  EXPECT_FALSE(left.overlaps(xy(Vec3(0, 1 + 1e-6, 0), Vec3(1, 2, 1))));
  EXPECT_TRUE(left.overlaps(xy(Vec3(0, 0, 5), Vec3(1, 1, 6))));
  // and back in the world, with the third axis at 0
  const Aabb back = xy(Vec3(0.25, -3, 7), Vec3(0.5, 2, 9)).toAabb(0, 1);
  EXPECT_EQ(back.min, Vec3(0.25, -3, 0));
  EXPECT_EQ(back.max, Vec3(0.5, 2, 0));
}

namespace
{
using Pairs = std::set<std::pair<std::uint32_t, std::uint32_t>>;

/// Every pair the grid reports, and every pair of overlapping boxes by brute force, each
/// as (lower, higher); and each item's query against brute force.
void expectGridFindsExactlyTheOverlaps(const StepGrid& grid, std::size_t n)
{
  Pairs expected;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      if (grid.box(i).overlaps(grid.box(j)))
        expected.emplace(i, j);
  Pairs found;
  grid.forEachPair([&](std::uint32_t i, std::uint32_t j) {
    ASSERT_NE(i, j);
    found.emplace(std::min(i, j), std::max(i, j));
  });
  // (a reported pair may be one whose boxes do not overlap: a candidate, never a miss)
  for (const auto& pair : expected)
    ASSERT_TRUE(found.count(pair)) << "pair " << pair.first << ", " << pair.second << " missed";
  for (std::uint32_t i = 0; i < n; ++i)
  {
    std::set<std::uint32_t> near;
    grid.query(i, [&](std::uint32_t j) {
      ASSERT_NE(i, j);
      near.insert(j);
    });
    for (std::uint32_t j = 0; j < n; ++j)
      if (j != i && grid.box(i).overlaps(grid.box(j)))
      {
        ASSERT_TRUE(near.count(j)) << "query of " << i << " missed " << j;
      }
  }
}

Aabb randomBox(std::mt19937_64& rng, double spread, double size)
{
  std::uniform_real_distribution<double> unit(0, 1);
  const Vec3 c(spread * unit(rng), spread * unit(rng), 0.1 * unit(rng));
  const Vec3 h(size * unit(rng), size * unit(rng), 0.05);
  return {c - h, c + h};
}
}  // namespace

TEST(StepGrid, FindsEveryOverlapAsBoxesAreBinnedThenMovedDuringTheStep)
{
  // Dense cells (balls packed on a floor) and hashed buckets (balls spread thin), each
  // with a few boxes far wider than the rest, then boxes replaced one by one as events
  // change motions: a few (scanned in a list) and then many (in the moved grid).
  for (const double spread : {4.0, 400.0})
    for (int seed = 1; seed <= 3; ++seed)
    {
      std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
      const std::size_t n = 600;
      StepGrid grid;
      grid.start(n, Vec3::UnitZ());
      for (std::uint32_t i = 0; i < n; ++i)
      {
        Aabb box = randomBox(rng, spread, i == 5 ? spread : i % 97 == 0 ? 1.0 : 0.08);  // one huge
        if (seed == 3 && i % 150 == 7)  // far beyond the cell indices' range, where they are clamped
          box = Aabb{box.min + Vec3(1e12, 0, 0), box.max + Vec3(1e12, 0, 0)};
        grid.setBox(i, box);
      }
      grid.build();
      SCOPED_TRACE("spread " + std::to_string(spread) + ", seed " + std::to_string(seed));
      EXPECT_EQ(grid.inCellOrder(), spread < 10 && seed != 3);  // dense cells, or hashed
      expectGridFindsExactlyTheOverlaps(grid, n);
      for (int round = 0; round < 3; ++round)
      {
        for (int k = 0; k < 30; ++k)
        {
          const auto i = static_cast<std::uint32_t>(rng() % n);
          const Aabb now = grid.box(i).toAabb(0, 1);
          // most stay close by, some leave their cell, a few go far
          const double jump = k % 10 == 0 ? spread : k % 3 == 0 ? 0.3 : 0.01;
          const Vec3 shift(jump * (2 * (rng() % 2) - 1.0), jump * (2 * (rng() % 2) - 1.0), 0);
          grid.update(i, Aabb{now.min + shift, now.max + shift});
        }
        expectGridFindsExactlyTheOverlaps(grid, n);
      }
    }
}

TEST(StepGrid, GivesUpItsCellOrderOfTheItems)
{
  std::mt19937_64 rng(3);
  const std::size_t n = 500;
  StepGrid grid;
  grid.start(n, Vec3::UnitZ());
  for (std::uint32_t i = 0; i < n; ++i)
    grid.setBox(i, randomBox(rng, 3.0, 0.06));
  grid.build();
  ASSERT_TRUE(grid.inCellOrder());
  std::vector<std::uint32_t> order{7, 7, 7};
  grid.takeCellOrder(order);
  ASSERT_EQ(order.size(), n);
  // a permutation of the items that lists them row by row of cells: the cells' rows
  // (along y) never decrease
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < n; ++i)
    ASSERT_EQ(sorted[i], i);
  std::vector<double> ys;
  for (const std::uint32_t item : order)
  {
    const Box32& box = grid.box(item);
    ys.push_back(0.5 * (static_cast<double>(box.min[1]) + box.max[1]));
  }
  int descents = 0;
  for (std::size_t k = 1; k < n; ++k)
    descents += ys[k] < ys[k - 1] - 0.2 ? 1 : 0;  // more than a cell back
  EXPECT_EQ(descents, 0);
}

// Where items spread along "up" as freely as across it (balls without a floor), the grid
// keeps heights: it reports every pair of boxes that overlap in space, and none that lie
// apart along "up" (beyond the rounding to floats), binned and then moved in the step;
// and an obstacle across the whole grid at one height (a wall's face as floor) is reached
// only by boxes at that height.
TEST(StepGrid, WithHeightsTellsBoxesApartAlongUpToo)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t n = 800;
  const auto cube = [&] {
    const Vec3 c(4 * unit(rng), 4 * unit(rng), 4 * unit(rng));
    const Vec3 h(0.02 + 0.05 * unit(rng), 0.02 + 0.05 * unit(rng), 0.02 + 0.05 * unit(rng));
    return Aabb{c - h, c + h};
  };
  std::vector<Aabb> boxes(n);
  StepGrid grid;
  grid.start(n, Vec3::UnitZ(), StepSettings{}, true);
  for (std::uint32_t i = 0; i < n; ++i)
    grid.setBox(i, boxes[i] = cube());
  grid.build();
  const std::vector<Aabb> floor{Aabb{Vec3(-1, -1, 0), Vec3(5, 5, 0.1)}};
  grid.markObstacles(floor);
  const auto apart = [](const Aabb& a, const Aabb& b, double margin) {
    return ((a.min.array() > b.max.array() + margin) || (b.min.array() > a.max.array() + margin)).any();
  };
  const auto check = [&] {
    Pairs found;
    grid.forEachPair([&](std::uint32_t i, std::uint32_t j) { found.emplace(std::min(i, j), std::max(i, j)); });
    int overlapping = 0;
    for (std::uint32_t i = 0; i < n; ++i)
    {
      std::set<std::uint32_t> near;
      grid.query(i, [&](std::uint32_t j) { near.insert(j); });
      for (std::uint32_t j = 0; j < n; ++j)
      {
        if (j == i)
          continue;
        if (!apart(boxes[i], boxes[j], 0))
        {
          ++overlapping;
          ASSERT_TRUE(near.count(j)) << "query of " << i << " missed " << j;
          ASSERT_TRUE(found.count({std::min(i, j), std::max(i, j)})) << i << ", " << j << " missed";
        }
        else if (apart(boxes[i], boxes[j], 1e-5))
        {
          ASSERT_FALSE(near.count(j)) << "query of " << i << " gave " << j << ", apart";
          ASSERT_FALSE(found.count({std::min(i, j), std::max(i, j)})) << i << ", " << j << " apart";
        }
      }
      const bool at_floor = !apart(boxes[i], floor[0], 0);
      if (at_floor || apart(boxes[i], floor[0], 1e-5))
      {
        EXPECT_EQ(grid.reaches(i, 0), at_floor) << i;
      }
    }
    EXPECT_GT(overlapping, 20);  // (a check that has pairs to find)
  };
  check();
  for (int round = 0; round < 2; ++round)
  {
    for (int k = 0; k < 40; ++k)  // some stay close by, some leave their cell, some go up or down
    {
      const auto i = static_cast<std::uint32_t>(rng() % n);
      const Vec3 shift = k % 4 == 0 ? Vec3(0, 0, 2 * unit(rng) - 1) : Vec3(0.3 * unit(rng), 0.3 * unit(rng), 0);
      boxes[i] = Aabb{boxes[i].min + shift, boxes[i].max + shift};
      grid.update(i, boxes[i]);
    }
    check();
  }
}
