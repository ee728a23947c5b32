#pragma once

#include "ball_collision_sim/core/types.hpp"

#include <cstdint>
#include <vector>

namespace ball_collision_sim::core
{
/// Axis-aligned box [m].
struct Aabb
{
  Vec3 min;
  Vec3 max;
  bool overlaps(const Aabb& o) const
  {
    return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
  }
};

/// The box swept by a sphere of radius r moving in a straight line from a to b.
inline Aabb sweptBox(const Vec3& a, const Vec3& b, double r)
{
  return {a.cwiseMin(b).array() - r, a.cwiseMax(b).array() + r};
}

/// Uniform hashed grid of boxes: an item is listed in every cell its box touches, so
/// two items can only touch when they share a cell. Items may be inserted again with a
/// new box during a step; stale entries only cost an extra exact test. Items whose box
/// spans too many cells go to a short list that every query returns.
class UniformGrid
{
public:
  /// Empties the grid and sets its cell size [m].
  void reset(double cell_size, std::size_t expected_items);
  void insert(std::uint32_t item, const Aabb& box);
  /// Calls f(item) for every item listed in a cell that `box` touches, and every
  /// oversized item; an item may come more than once.
  template <class F>
  void query(const Aabb& box, F&& f) const;
  /// True when `box` is too large to look up cell by cell (the caller then tests all).
  bool oversized(const Aabb& box) const;
  double cellSize() const { return cell_; }

private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  static constexpr std::int64_t kMaxCellsPerBox = 512;
  struct Entry
  {
    std::uint32_t item;
    std::uint32_t next;
  };
  std::uint64_t key(std::int64_t ix, std::int64_t iy, std::int64_t iz) const;
  std::uint32_t& head(std::uint64_t key);
  std::uint32_t find(std::uint64_t key) const;
  void grow();
  std::int64_t cellOf(double c) const;

  double cell_ = 1.0;
  double inv_cell_ = 1.0;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> heads_;
  std::size_t used_ = 0;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> oversized_;
};

template <class F>
void UniformGrid::query(const Aabb& box, F&& f) const
{
  for (std::uint32_t item : oversized_)
    f(item);
  const std::int64_t x0 = cellOf(box.min.x()), x1 = cellOf(box.max.x());
  const std::int64_t y0 = cellOf(box.min.y()), y1 = cellOf(box.max.y());
  const std::int64_t z0 = cellOf(box.min.z()), z1 = cellOf(box.max.z());
  for (std::int64_t ix = x0; ix <= x1; ++ix)
    for (std::int64_t iy = y0; iy <= y1; ++iy)
      for (std::int64_t iz = z0; iz <= z1; ++iz)
        for (std::uint32_t e = find(key(ix, iy, iz)); e != kEmpty; e = entries_[e].next)
          f(entries_[e].item);
}
}  // namespace ball_collision_sim::core
