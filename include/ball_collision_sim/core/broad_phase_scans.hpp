// StepGrid's scans over its cells (broad_phase.hpp), templates on what they call for each
// item or pair, so that the step's detection inlines into them.
#pragma once

#include "ball_collision_sim/core/broad_phase.hpp"

#include <algorithm>
#include <cstdint>

namespace ball_collision_sim::core
{
template <class F>
void StepGrid::scanCells(std::int64_t x0, std::int64_t x1, std::int64_t y0, std::int64_t y1, const Probe& p,
                         F&& f) const
{
  if (dense_)
  {
    // rows of neighbouring cells are runs of the sorted entries
    x0 = std::max(x0, min_x_ - 1);
    x1 = std::min(x1, min_x_ + width_ - 2);
    y0 = std::max(y0, min_y_ - 1);
    y1 = std::min(y1, min_y_ + height_ - 2);
    if (x0 > x1)
      return;
    for (std::int64_t iy = y0; iy <= y1; ++iy)
    {
      const std::size_t first = slotOf(x0, iy);
      const std::size_t last = first + static_cast<std::size_t>(x1 - x0) + 1;
      for (std::uint32_t k = starts_[first]; k < starts_[last]; ++k)
        if (const std::uint32_t j = entries_[k]; meets(p, j) && !moved(j))
          f(j);
    }
    return;
  }
  for (std::int64_t ix = x0; ix <= x1; ++ix)
    for (std::int64_t iy = y0; iy <= y1; ++iy)
    {
      const std::size_t b = bucketOf(ix, iy);
      for (std::uint32_t k = starts_[b]; k < starts_[b + 1]; ++k)
      {
        const std::uint32_t j = entries_[k];
        if (cells_[j][0] == ix && cells_[j][1] == iy && meets(p, j) && !moved(j))
          f(j);
      }
    }
}

template <class F>
void StepGrid::query(std::uint32_t i, F&& f) const
{
  const Probe p = probeOf(i);
  const Box32& box = p.box;
  if (!moved_list_.empty())
  {
    const auto other_moved = [&](std::uint32_t j) {
      if (j != i && meets(p, j))
        f(j);
    };
    if (moved_list_.size() <= kFewMoved || moved_grid_.oversized(box.toAabb(ax_, ay_)))
      for (std::uint32_t j : moved_list_)  // few, or too many cells to look up: all that moved
        other_moved(j);
    else
      moved_grid_.query(box.toAabb(ax_, ay_), other_moved);
  }
  const auto binned = [&](std::uint32_t j) {
    if (j != i)
      f(j);
  };
  if (!moved(i) && dense_)
  {
    // the 3 x 3 cells around its own, rows of the array (the border keeps them in it)
    const auto w = static_cast<std::size_t>(width_);
    for (std::size_t first = items_[i].slot - w - 1; first <= items_[i].slot + w - 1; first += w)
      for (std::uint32_t k = starts_[first]; k < starts_[first + 3]; ++k)
        if (const std::uint32_t j = entries_[k]; meets(p, j) && !moved(j))
          binned(j);
    return;
  }
  if (!moved(i))
  {
    const auto [cx, cy] = cellOf(i);
    scanCells(cx - 1, cx + 1, cy - 1, cy + 1, p, binned);
    return;
  }
  const std::int64_t x0 = firstReaching(box.min[0]), x1 = lastReaching(box.max[0]);
  const std::int64_t y0 = firstReaching(box.min[1]), y1 = lastReaching(box.max[1]);
  if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) > static_cast<double>(items_.size()) + 16)
  {
    for (const std::uint32_t j : entries_)  // a huge box: every binned item
      if (meets(p, j) && !moved(j))
        binned(j);
    return;
  }
  scanCells(x0, x1, y0, y1, p, binned);
}

template <class F>
void StepGrid::forEachNearObstacle(F&& f) const
{
  if (!dense_)
  {
    for (std::uint32_t i = 0; i < items_.size(); ++i)
      f(i);
    return;
  }
  for (std::size_t s = 0; s + 1 < starts_.size(); ++s)
    if (nearCell(s))
      for (std::uint32_t k = starts_[s]; k < starts_[s + 1]; ++k)
        if (!moved(entries_[k]))
          f(entries_[k]);
  for (std::uint32_t i : moved_list_)
    f(i);
}

template <class F>
void StepGrid::forEachPair(F&& f) const
{
  forEachPairIn(0, pairScan(), f);
  forEachMovedPair(f);
}

inline std::size_t StepGrid::pairScan() const
{
  // dense: the slots whose cell has its east and upper neighbours in the array; hashed:
  // the binned items
  const std::size_t slots = starts_.size() - 1, w = static_cast<std::size_t>(width_);
  return dense_ ? (slots >= w + 2 ? slots - w - 1 : 0) : entries_.size();
}

template <class F>
void StepGrid::forEachPairIn(std::size_t from, std::size_t to, F&& f) const
{
  if (dense_)
  {
    // Each cell with itself and with the four neighbours after it in row-major order
    // (east, and the row above): every pair of neighbouring cells once.
    const auto w = static_cast<std::size_t>(width_);
    for (std::size_t s = from; s < to; ++s)
    {
      const std::uint32_t begin = starts_[s], end = starts_[s + 1];
      for (std::uint32_t k = begin; k < end; ++k)
      {
        const std::uint32_t item = entries_[k];
        if (moved(item))
          continue;
        const Probe p = probeOf(item);
        const auto pair = [&](std::uint32_t l) {
          if (const std::uint32_t j = entries_[l]; meets(p, j) && !moved(j))
            f(item, j);
        };
        for (std::uint32_t l = k + 1; l < starts_[s + 2]; ++l)  // the rest of this cell, then east
          pair(l);
        for (std::uint32_t l = starts_[s + w - 1]; l < starts_[s + w + 2]; ++l)  // the row above
          pair(l);
      }
    }
    return;
  }
  for (std::size_t k = from; k < to; ++k)
  {
    const std::uint32_t i = entries_[k];
    if (moved(i))
      continue;
    const auto [cx, cy] = cellOf(i);
    scanCells(cx - 1, cx + 1, cy - 1, cy + 1, probeOf(i), [&](std::uint32_t j) {
      if (j > i)
        f(i, j);
    });
  }
}

template <class F>
void StepGrid::forEachMovedPair(F&& f) const
{
  // Items that moved out find all their pairs themselves; a pair of two such is found
  // from the lower one's side.
  for (std::uint32_t i : moved_list_)
    query(i, [&](std::uint32_t j) {
      if (!moved(j) || j > i)
        f(i, j);
    });
}
}  // namespace ball_collision_sim::core
