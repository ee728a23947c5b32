// A tight jam as the contact solver sees it: balls of radius 1 stacked in square packing
// (layers base x base, then (base - 1)^2 on their hollows, down to top x top) in a box of
// five walls that they fill, each off its place by up to 1e-6 of its radius; each body's
// inverse mass in [1/2.5, 2] and free vector pushed down and sideways at random; a row for
// each pair and wall within 3e-6 of touching, its target round-off of its gap. Shared by
// test_contact_solver and bench/exact_stage.
#pragma once

#include "core/step/contact_solver.hpp"

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace ball_collision_sim::test
{
struct JamRows
{
  std::vector<core::Vec3> free;
  std::vector<double> inv;
  std::vector<core::step::ContactRow> rows;
};

inline JamRows jamRows(int base, int top, std::mt19937_64& rng)
{
  using core::Vec3;
  using core::step::ContactRow;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double r = 1, side = 2 * r * base, jiggle = 1e-6, near = 3 * jiggle;
  std::vector<Vec3> at;
  for (int layer = 0; base - layer >= top; ++layer)
    for (int i = 0; i < base - layer; ++i)
      for (int j = 0; j < base - layer; ++j)
        at.push_back(Vec3((2 * i + 1 + layer) * r, (2 * j + 1 + layer) * r, (1 + layer * std::sqrt(2.0)) * r) +
                     jiggle * Vec3(unit(rng), unit(rng), unit(rng)));
  JamRows jam;
  const std::size_t n = at.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    jam.inv.push_back(1 / (1.5 + unit(rng)));
    jam.free.push_back(Vec3(unit(rng), unit(rng), unit(rng) - 1));
  }
  const std::array<Vec3, 5> walls = {Vec3(0, 0, -1), Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0)};
  for (std::uint32_t a = 0; a < n; ++a)
  {
    for (std::uint32_t b = a + 1; b < n; ++b)
      if ((at[b] - at[a]).norm() < 2 * r + near)
      {
        ContactRow row;
        row.a = a;
        row.b = b;
        row.push_a = row.push_b = (at[b] - at[a]).normalized();
        row.target = 1e-16 * unit(rng);  // (round-off of the gap)
        jam.rows.push_back(row);
      }
    const std::array<double, 5> gaps = {at[a].z(), at[a].x(), side - at[a].x(), at[a].y(), side - at[a].y()};
    for (std::size_t w = 0; w < walls.size(); ++w)
      if (gaps[w] < r + near)
      {
        ContactRow row;
        row.a = a;
        row.push_a = row.push_b = walls[w];
        row.target = 1e-16 * unit(rng);
        jam.rows.push_back(row);
      }
  }
  return jam;
}
}  // namespace ball_collision_sim::test
