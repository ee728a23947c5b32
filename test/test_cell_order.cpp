// The records' order (src/core/permutation.hpp) on its own: a permutation inverted in
// place, and records gathered in place into a new order, against the same done with a
// second list.
#include "core/permutation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace ball_collision_sim::core;

namespace
{
std::vector<std::uint32_t> randomPermutation(std::size_t n, std::mt19937_64& rng)
{
  std::vector<std::uint32_t> p(n);
  std::iota(p.begin(), p.end(), 0u);
  std::shuffle(p.begin(), p.end(), rng);
  return p;
}

/// Two lists of records moved together, as the world's balls, feet and spins are.
struct TwoLists
{
  std::vector<std::string> names;
  std::vector<double> values;
  std::string name;
  double value = 0;
  void save(std::uint32_t k)
  {
    name = names[k];
    value = values[k];
  }
  void move(std::uint32_t into, std::uint32_t out)
  {
    names[into] = names[out];
    values[into] = values[out];
  }
  void restore(std::uint32_t k)
  {
    names[k] = name;
    values[k] = value;
  }
};
}  // namespace

TEST(InvertInPlace, GivesTheInverseOfEveryPermutation)
{
  // Random permutations of 0 to 10^5 entries, one long cycle, the identity and a swap of
  // two: q[p[k]] = k, and inverting twice gives p back.
  std::mt19937_64 rng(11);
  std::vector<std::vector<std::uint32_t>> cases;
  for (const std::size_t n : {0u, 1u, 2u, 3u, 10u, 257u, 1000u, 100000u})
    cases.push_back(randomPermutation(n, rng));
  std::vector<std::uint32_t> cycle(500);
  for (std::uint32_t k = 0; k < cycle.size(); ++k)
    cycle[k] = (k + 1) % 500;
  cases.push_back(cycle);
  std::vector<std::uint32_t> identity(64);
  std::iota(identity.begin(), identity.end(), 0u);
  cases.push_back(identity);
  std::vector<std::uint32_t> swap = identity;
  std::swap(swap[3], swap[40]);
  cases.push_back(swap);
  for (const auto& p : cases)
  {
    std::vector<std::uint32_t> q = p;
    invertInPlace(q);
    for (std::uint32_t k = 0; k < p.size(); ++k)
      ASSERT_EQ(q[p[k]], k) << "size " << p.size();
    invertInPlace(q);
    EXPECT_EQ(q, p) << "size " << p.size();
  }
}

TEST(GatherInPlace, PutsEachListInTheOrderAsACopyWould)
{
  // Slot k takes what slot from[k] held, in every list at once, from[] left the identity.
  std::mt19937_64 rng(5);
  for (const std::size_t n : {0u, 1u, 2u, 7u, 100u, 4096u})
  {
    for (int trial = 0; trial < 5; ++trial)
    {
      TwoLists lists;
      for (std::size_t k = 0; k < n; ++k)
      {
        lists.names.push_back("ball " + std::to_string(k));
        lists.values.push_back(0.5 * static_cast<double>(k) - 3);
      }
      std::vector<std::uint32_t> from = randomPermutation(n, rng);
      std::vector<std::string> names(n);
      std::vector<double> values(n);
      for (std::size_t k = 0; k < n; ++k)
      {
        names[k] = lists.names[from[k]];
        values[k] = lists.values[from[k]];
      }
      gatherInPlace(from, lists);
      EXPECT_EQ(lists.names, names) << n;
      EXPECT_EQ(lists.values, values) << n;
      for (std::uint32_t k = 0; k < n; ++k)
        ASSERT_EQ(from[k], k);
    }
  }
}
