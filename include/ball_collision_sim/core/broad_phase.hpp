#pragma once

#include "ball_collision_sim/core/step_settings.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace ball_collision_sim::core
{
/// Axis-aligned box [m].
struct Aabb
{
  Vec3 min;
  Vec3 max;
};

/// An Aabb across two of the world's axes (the step grid's: the dropped one is "up", along
/// which balls on a floor barely spread), in single precision, rounded outward so that it
/// holds the box it was made from there: 16 bytes a box, at the cost of a few more
/// candidate pairs (those apart along "up" alone, which the exact test then sets aside).
struct Box32
{
  std::array<float, 2> min;
  std::array<float, 2> max;
  /// `box` across the world's axes ax and ay.
  static Box32 around(const Aabb& box, int ax, int ay)
  {
    return {{below(box.min[ax]), below(box.min[ay])}, {above(box.max[ax]), above(box.max[ay])}};
  }
  bool overlaps(const Box32& o) const
  {
    // all four tests and one branch: whether neighbouring boxes overlap is hard to predict
    return static_cast<bool>(static_cast<int>(min[0] <= o.max[0]) & static_cast<int>(o.min[0] <= max[0]) &
                             static_cast<int>(min[1] <= o.max[1]) & static_cast<int>(o.min[1] <= max[1]));
  }
  /// The box in the world, across the axes ax and ay, and [0, 0] along the third.
  Aabb toAabb(int ax, int ay) const
  {
    Aabb out{Vec3::Zero(), Vec3::Zero()};
    out.min[ax] = min[0];
    out.min[ay] = min[1];
    out.max[ax] = max[0];
    out.max[ay] = max[1];
    return out;
  }

private:
  /// The largest float <= d (the smallest float >= d): d rounded to the nearest float,
  /// then one float further where that went past d, without branches. Beyond the floats'
  /// range that is the largest float or infinity, whichever lies on that side.
  static float below(double d) { return stepped(d, false); }
  static float above(double d) { return stepped(d, true); }
  static float stepped(double d, bool up)
  {
    const float f = static_cast<float>(d);
    const double back = f;
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    const std::uint32_t past = up ? static_cast<std::uint32_t>(back < d) : static_cast<std::uint32_t>(d < back);
    // one float on is the next bit pattern where that grows the magnitude (up from a
    // positive float, down from a negative one, -0 included), else the one before; the
    // mask (rather than a product) keeps the compiler from a branch, which would be
    // mispredicted half the time
    const std::uint32_t away = static_cast<std::uint32_t>(up) ^ (bits >> 31);
    bits += (2 * away - 1) & (0u - past);
    float out = 0;
    std::memcpy(&out, &bits, sizeof out);
    return out;
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

/// The broad phase of one step. Items (balls) are binned by the centre of their swept box
/// in a grid of square cells across the two world axes most nearly perpendicular to
/// "up", cells a little wider than the widest binned box: a binned item's box then lies
/// strictly within half a cell of its own cell, and two overlapping boxes sit in the same
/// or neighbouring cells. An item whose box leaves that reach during the step (after a
/// bounce), or that was too large to bin, is listed again in a UniformGrid of every cell
/// its box touches. The items come in a recent step's cell order, so the cell order read
/// by a scan of neighbouring cells is nearly the items' own.
class StepGrid
{
public:
  /// Starts a step of n items; `up` picks the grid's two axes. With `heights` it keeps
  /// each box's extent along the third axis too and tells boxes apart by it (for items
  /// that spread along "up" as freely as across it: balls without a floor). Then setBox()
  /// for each item, then build().
  void start(std::size_t n, const Vec3& up, const StepSettings& settings = StepSettings{}, bool heights = false);
  void setBox(std::uint32_t i, const Aabb& box)
  {
    items_[i].box = across(box);
    if (!heights_.empty())
      heights_[i] = heightOf(box);
  }
  /// A box as the grid keeps boxes: across its two axes, in floats.
  Box32 across(const Aabb& box) const { return Box32::around(box, ax_, ay_); }
  /// Bins the boxes.
  void build();
  /// Item i's current box (rounded outward).
  const Box32& box(std::uint32_t i) const { return items_[i].box; }
  /// True when the grid lists the items cell by cell, row by row.
  bool inCellOrder() const { return dense_; }
  /// Moves the grid's order of the items (cell by cell, every item once) into `order`,
  /// without a copy: the grid needs build() again after this.
  void takeCellOrder(std::vector<std::uint32_t>& order);
  /// Takes the obstacles' boxes (walls), and notes which cells binned items could reach
  /// them from.
  void markObstacles(const std::vector<Aabb>& obstacles);
  /// Whether item i's box overlaps obstacle o's, as meets() tells two items'.
  bool reaches(std::uint32_t i, std::size_t o) const
  {
    return obstacles_[o].overlaps(items_[i].box) &&
           (heights_.empty() || heightsMeet(heights_[i], obstacle_heights_[o]));
  }
  /// False when item i's box cannot overlap any of the boxes given to markObstacles().
  bool nearObstacle(std::uint32_t i) const
  {
    return moved(i) || !dense_ || nearCell(items_[i].slot);
  }
  /// Calls f(i) for every item that nearObstacle() may be true for, each once.
  template <class F>
  void forEachNearObstacle(F&& f) const;
  /// Item i's box is now `box` (its motion changed during the step).
  void update(std::uint32_t i, const Aabb& box);
  /// Calls f(j) for every other item j whose box overlaps the box of item i; j may come
  /// more than once.
  template <class F>
  void query(std::uint32_t i, F&& f) const;
  /// Calls f(i, j) for every pair of items whose boxes overlap, at least once each pair
  /// (i != j, in either order).
  template <class F>
  void forEachPair(F&& f) const;
  /// forEachPair() in parts, in its order: the binned items' pairs over [from, to) of
  /// pairScan()'s length (parts of it may run at once), then the moved items' pairs.
  std::size_t pairScan() const;
  template <class F>
  void forEachPairIn(std::size_t from, std::size_t to, F&& f) const;
  template <class F>
  void forEachMovedPair(F&& f) const;

private:
  /// A whole number of cells as an index, clamped so that far-away items cannot overflow
  /// the 32 bits an item's cell is kept in, nor reach them one cell on (they then share
  /// cells, which costs time, never a pair: indices of overlapping boxes differ by at
  /// most one, and clamping keeps that).
  static std::int64_t index(double cells) { return static_cast<std::int64_t>(std::clamp(cells, -1e9, 1e9)); }
  bool fits(std::uint32_t i, const Box32& box) const;
  /// The first and the last cell along an axis whose reach ((c - 1/2) h, (c + 3/2) h)
  /// meets a box from lo to hi along it (index()).
  std::int64_t firstReaching(float lo) const { return index(std::floor(static_cast<double>(lo) * inv_cell_ - 1.5)); }
  std::int64_t lastReaching(float hi) const { return index(std::floor(static_cast<double>(hi) * inv_cell_ + 0.5)); }
  /// The larger of a box's widths across the grid's axes [m].
  double extent(const Box32& box) const
  {
    return std::max(static_cast<double>(box.max[0]) - box.min[0], static_cast<double>(box.max[1]) - box.min[1]);
  }
  /// Sets the cell's width from the boxes; returns the widest box binned, and whether
  /// some are left out as far wider than the rest.
  double chooseCell(bool& outliers);
  /// Each item's cell, and whether the cells are a dense array; returns the slots needed.
  std::size_t assignCells();
  /// Lists item i (with its current box) among the moved items instead of in its cell.
  void moveOut(std::uint32_t i);
  /// What other items' boxes are compared with for item i: its box, and its height where
  /// the grid keeps heights (else none).
  struct Probe
  {
    Box32 box;
    const std::array<float, 2>* height;
  };
  Probe probeOf(std::uint32_t i) const { return {items_[i].box, heights_.empty() ? nullptr : &heights_[i]}; }
  /// Calls f(item) for the binned items of the cells [x0, x1] x [y0, y1] whose boxes
  /// meet the probe's.
  template <class F>
  void scanCells(std::int64_t x0, std::int64_t x1, std::int64_t y0, std::int64_t y1, const Probe& p, F&& f) const;
  /// A box's extent along the axis the grid drops, rounded outward to floats.
  std::array<float, 2> heightOf(const Aabb& box) const
  {
    const Box32 b = Box32::around(box, az_, az_);
    return {b.min[0], b.max[0]};
  }
  /// Whether item j's box overlaps the probe's: across the grid's axes, and along the
  /// third where the grid keeps heights.
  bool meets(const Probe& p, std::uint32_t j) const
  {
    // (where the grid keeps heights, both tests and one branch on the two: whether
    // neighbouring boxes overlap is hard to predict either way)
    const bool across = items_[j].box.overlaps(p.box);
    if (p.height == nullptr)
      return across;
    return static_cast<bool>(static_cast<int>(across) & static_cast<int>(heightsMeet(*p.height, heights_[j])));
  }
  static bool heightsMeet(const std::array<float, 2>& a, const std::array<float, 2>& b)
  {
    return static_cast<bool>(static_cast<int>(a[0] <= b[1]) & static_cast<int>(b[0] <= a[1]));
  }
  std::size_t bucketOf(std::int64_t cx, std::int64_t cy) const
  {
    // Fibonacci hashing of the two cell indices
    const std::uint64_t h =
        static_cast<std::uint64_t>(cx) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(cy) * 0xc2b2ae3d27d4eb4fULL;
    return static_cast<std::size_t>((h ^ (h >> 29)) >> shift_);
  }
  std::size_t slotOf(std::int64_t cx, std::int64_t cy) const
  {
    if (dense_)
      return static_cast<std::size_t>((cx - min_x_ + 1) + width_ * (cy - min_y_ + 1));
    return bucketOf(cx, cy);
  }

  int ax_ = 0;  ///< the grid's axes
  int ay_ = 1;
  int az_ = 2;  ///< the axis it drops (nearest "up")
  double cell_ = 1.0;
  double inv_cell_ = 1.0;
  int shift_ = 60;
  double outlier_ratio_ = 4.0;          ///< StepSettings::grid_outlier_ratio
  double dense_cells_per_item_ = 4.0;   ///< StepSettings::grid_dense_cells_per_item
  double dense_extra_cells_ = 1024.0;   ///< StepSettings::grid_dense_extra_cells
  double cell_margin_ = 1e-9;           ///< StepSettings::grid_cell_margin
  double cell_floor_ = 1e-12;           ///< StepSettings::grid_cell_floor [m]
  /// What the grid keeps of an item, in 20 bytes.
  struct Item
  {
    Box32 box;               ///< its current box
    /// its cell's slot (dense mode) or bucket, or kMoved once it is listed as moved
    std::uint32_t slot = 0;
  };
  static constexpr std::uint32_t kMoved = std::numeric_limits<std::uint32_t>::max();  ///< no slot is this
  /// assignCells(): a cell's offset from the first item's is kept as this plus it, in 16 bits
  static constexpr std::int64_t kOffset = 0x8000;
  bool moved(std::uint32_t i) const { return items_[i].slot == kMoved; }
  /// Item i's cell (see index()): from its slot in dense mode, else kept in cells_.
  std::array<std::int64_t, 2> cellOf(std::uint32_t i) const
  {
    if (!dense_)
      return {cells_[i][0], cells_[i][1]};
    const auto w = static_cast<std::uint32_t>(width_);
    return {static_cast<std::int64_t>(items_[i].slot % w) + min_x_ - 1,
            static_cast<std::int64_t>(items_[i].slot / w) + min_y_ - 1};
  }
  /// The cell of a box's centre, along the grid's axes.
  std::array<std::int64_t, 2> cellAt(const Box32& box) const
  {
    return {index(std::floor(0.5 * (static_cast<double>(box.min[0]) + box.max[0]) * inv_cell_)),
            index(std::floor(0.5 * (static_cast<double>(box.min[1]) + box.max[1]) * inv_cell_))};
  }
  std::vector<Item> items_;             ///< per item
  /// per item where the grid keeps heights (start()): its box's extent along az_
  std::vector<std::array<float, 2>> heights_;
  std::vector<Box32> obstacles_;  ///< markObstacles()
  std::vector<std::array<float, 2>> obstacle_heights_;  ///< where the grid keeps heights
  /// per item, hashed mode only: its cell (bucket collisions are told apart by it)
  std::vector<std::array<std::int32_t, 2>> cells_;
  std::vector<std::uint32_t> starts_;   ///< bucket b holds entries_[starts_[b] .. starts_[b + 1])
  std::vector<std::uint32_t> entries_;  ///< items in order of their buckets
  std::vector<std::uint64_t> near_obstacle_;  ///< dense mode, a bit per cell
  bool nearCell(std::size_t s) const { return ((near_obstacle_[s >> 6] >> (s & 63)) & 1) != 0; }
  /// Dense mode: cells in a row-major array over the items' cells with a border of one;
  /// otherwise hashed buckets (items spread far apart).
  bool dense_ = false;
  std::int64_t min_x_ = 0;
  std::int64_t min_y_ = 0;
  std::int64_t width_ = 0;
  std::int64_t height_ = 0;
  /// Up to this many moved items are found by a scan of the list; past it, the moved
  /// grid (filled then) holds them.
  static constexpr std::size_t kFewMoved = 32;
  UniformGrid moved_grid_;
  std::vector<std::uint32_t> moved_list_;
};

}  // namespace ball_collision_sim::core

#include "ball_collision_sim/core/broad_phase_scans.hpp"  // StepGrid's scans, as templates
