#include "ball_collision_sim/core/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
namespace
{
std::uint64_t mix(std::uint64_t h)
{
  // splitmix64 finaliser: spreads nearby cell coordinates over the table
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  h ^= h >> 31;
  return h;
}
constexpr std::uint64_t kNoKey = ~0ULL;
}  // namespace

void UniformGrid::reset(double cell_size, std::size_t expected_items)
{
  cell_ = cell_size;
  inv_cell_ = 1.0 / cell_size;
  std::size_t capacity = 64;
  while (capacity < 4 * expected_items)
    capacity *= 2;
  keys_.assign(capacity, kNoKey);
  heads_.assign(capacity, kEmpty);
  used_ = 0;
  entries_.clear();
  entries_.reserve(2 * expected_items);
  oversized_.clear();
}

std::int64_t UniformGrid::cellOf(double c) const
{
  // Clamped so that far-away coordinates cannot overflow; distinct far cells then share
  // a key, which costs extra candidates but never a missed pair.
  const double f = std::floor(c * inv_cell_);
  return static_cast<std::int64_t>(std::clamp(f, -1e15, 1e15));
}

std::uint64_t UniformGrid::key(std::int64_t ix, std::int64_t iy, std::int64_t iz) const
{
  const auto ux = static_cast<std::uint64_t>(ix) & 0x1fffff;
  const auto uy = static_cast<std::uint64_t>(iy) & 0x1fffff;
  const auto uz = static_cast<std::uint64_t>(iz) & 0x1fffff;
  return (ux << 42) | (uy << 21) | uz;
}

std::uint32_t UniformGrid::find(std::uint64_t k) const
{
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t slot = mix(k) & mask;; slot = (slot + 1) & mask)
  {
    if (keys_[slot] == k)
      return heads_[slot];
    if (keys_[slot] == kNoKey)
      return kEmpty;
  }
}

std::uint32_t& UniformGrid::head(std::uint64_t k)
{
  if (2 * (used_ + 1) > keys_.size())
    grow();
  const std::size_t mask = keys_.size() - 1;
  std::size_t slot = mix(k) & mask;
  while (keys_[slot] != k && keys_[slot] != kNoKey)
    slot = (slot + 1) & mask;
  if (keys_[slot] == kNoKey)
  {
    keys_[slot] = k;
    ++used_;
  }
  return heads_[slot];
}

void UniformGrid::grow()
{
  std::vector<std::uint64_t> old_keys(keys_.size() * 2, kNoKey);
  std::vector<std::uint32_t> old_heads(heads_.size() * 2, kEmpty);
  old_keys.swap(keys_);
  old_heads.swap(heads_);
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t i = 0; i < old_keys.size(); ++i)
  {
    if (old_keys[i] == kNoKey)
      continue;
    std::size_t slot = mix(old_keys[i]) & mask;
    while (keys_[slot] != kNoKey)
      slot = (slot + 1) & mask;
    keys_[slot] = old_keys[i];
    heads_[slot] = old_heads[i];
  }
}

bool UniformGrid::oversized(const Aabb& box) const
{
  const Vec3 span = (box.max - box.min) * inv_cell_;
  const double cells = (std::floor(span.x()) + 2) * (std::floor(span.y()) + 2) * (std::floor(span.z()) + 2);
  return !(cells <= static_cast<double>(kMaxCellsPerBox));
}

void UniformGrid::insert(std::uint32_t item, const Aabb& box)
{
  if (oversized(box))
  {
    if (std::find(oversized_.begin(), oversized_.end(), item) == oversized_.end())
      oversized_.push_back(item);
    return;
  }
  const std::int64_t x0 = cellOf(box.min.x()), x1 = cellOf(box.max.x());
  const std::int64_t y0 = cellOf(box.min.y()), y1 = cellOf(box.max.y());
  const std::int64_t z0 = cellOf(box.min.z()), z1 = cellOf(box.max.z());
  for (std::int64_t ix = x0; ix <= x1; ++ix)
    for (std::int64_t iy = y0; iy <= y1; ++iy)
      for (std::int64_t iz = z0; iz <= z1; ++iz)
      {
        std::uint32_t& h = head(key(ix, iy, iz));
        entries_.push_back({item, h});
        h = static_cast<std::uint32_t>(entries_.size() - 1);
      }
}

void StepGrid::start(std::size_t n, const Vec3& up, const StepSettings& settings, bool heights)
{
  static_assert(sizeof(Item) == 20, "a grid item is its box and its slot");
  // Grid axes: drop the one most nearly along "up", where balls on a floor barely spread.
  int drop = 0;
  up.cwiseAbs().maxCoeff(&drop);
  ax_ = drop == 0 ? 1 : 0;
  ay_ = drop == 2 ? 1 : 2;
  az_ = drop;
  items_.resize(n);
  heights_.resize(heights ? n : 0);
  outlier_ratio_ = settings.grid_outlier_ratio;
  dense_cells_per_item_ = settings.grid_dense_cells_per_item;
  dense_extra_cells_ = settings.grid_dense_extra_cells;
  cell_margin_ = settings.grid_cell_margin;
  cell_floor_ = settings.grid_cell_floor;
}

void StepGrid::build()
{
  const std::size_t n = items_.size();
  moved_list_.clear();
  entries_.resize(n);
  dense_ = false;
  if (n == 0)
  {
    starts_.assign(2, 0);
    shift_ = 63;
    return;
  }
  bool outliers = false;
  const double widest = chooseCell(outliers);
  const std::size_t slots = assignCells();
  // Counting sort by slot: starts_[b] counts slot b, then (summed) is where slot b ends,
  // then (each item put in front of its slot's, last item first) where it starts.
  starts_.assign(slots + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    ++starts_[items_[i].slot];
  for (std::size_t b = 0; b < slots; ++b)
    starts_[b + 1] += starts_[b];
  for (std::size_t i = n; i-- > 0;)
    entries_[--starts_[items_[i].slot]] = static_cast<std::uint32_t>(i);
  // the boxes left out of the cell's width are listed as moved
  if (outliers)
    for (std::size_t i = 0; i < n; ++i)
      if (extent(items_[i].box) > widest && !fits(static_cast<std::uint32_t>(i), items_[i].box))
        moveOut(static_cast<std::uint32_t>(i));
}

double StepGrid::chooseCell(bool& outliers)
{
  // Cells a little wider than the widest box, leaving out boxes far wider than the
  // mean (a rare fast or large ball): they are listed as moved instead of making
  // every cell huge.
  double sum = 0, widest = 0;
  for (const Item& item : items_)
  {
    const double e = extent(item.box);
    sum += e;
    widest = std::max(widest, e);
  }
  const double outlier = outlier_ratio_ * sum / static_cast<double>(items_.size());
  outliers = widest > outlier;
  if (outliers)
  {
    widest = 0;
    for (const Item& item : items_)
      if (const double e = extent(item.box); e <= outlier)
        widest = std::max(widest, e);
  }
  // (wider by round-off of the boxes' bounds, and not zero where every box is a point)
  cell_ = widest * (1 + cell_margin_) + cell_floor_;
  inv_cell_ = 1.0 / cell_;
  return widest;
}

std::size_t StepGrid::assignCells()
{
  // Each item's cell, kept in its slot for now as two 16-bit offsets from the first
  // item's cell where they fit (rows of a dense array rarely span more): the slots are
  // then found with integers alone, once the array's bounds are known.
  const std::size_t n = items_.size();
  const auto [x_ref, y_ref] = cellAt(items_[0].box);
  std::int64_t max_x = x_ref, max_y = y_ref;
  min_x_ = x_ref;
  min_y_ = y_ref;
  bool packed = true;
  for (Item& item : items_)
  {
    const auto [x, y] = cellAt(item.box);
    min_x_ = std::min(min_x_, x);
    min_y_ = std::min(min_y_, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
    const std::int64_t dx = x - x_ref + kOffset, dy = y - y_ref + kOffset;
    packed = packed && dx >= 0 && dx <= 0xffff && dy >= 0 && dy <= 0xffff;
    item.slot = static_cast<std::uint32_t>(dx & 0xffff) | static_cast<std::uint32_t>((dy & 0xffff) << 16);
  }
  const auto cellOfPacked = [&, x_ref = x_ref, y_ref = y_ref](const Item& item) -> std::array<std::int64_t, 2> {
    if (!packed)
      return cellAt(item.box);
    return {static_cast<std::int64_t>(item.slot & 0xffff) - kOffset + x_ref,
            static_cast<std::int64_t>(item.slot >> 16) - kOffset + y_ref};
  };
  // A dense array of cells (with a border of one) when the items are not spread too
  // thin, else hashed buckets, at least twice as many as items.
  width_ = max_x - min_x_ + 3;
  height_ = max_y - min_y_ + 3;
  // (an item keeps its cell's slot in 32 bits)
  const double cells = static_cast<double>(width_) * static_cast<double>(height_);
  dense_ = cells <= dense_cells_per_item_ * static_cast<double>(n) + dense_extra_cells_ && cells < kMoved;
  if (dense_)
  {
    cells_.clear();
    for (Item& item : items_)
    {
      const auto [x, y] = cellOfPacked(item);
      item.slot = static_cast<std::uint32_t>(slotOf(x, y));
    }
    return static_cast<std::size_t>(width_ * height_);
  }
  std::size_t slots = 16;
  shift_ = 60;
  while (slots < 2 * n)
  {
    slots *= 2;
    --shift_;
  }
  cells_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto [x, y] = cellOfPacked(items_[i]);
    cells_[i] = {static_cast<std::int32_t>(x), static_cast<std::int32_t>(y)};
    items_[i].slot = static_cast<std::uint32_t>(bucketOf(x, y));
  }
  return slots;
}

void StepGrid::takeCellOrder(std::vector<std::uint32_t>& order)
{
  order.swap(entries_);
  entries_.clear();
}

void StepGrid::markObstacles(const std::vector<Aabb>& obstacles)
{
  obstacles_.resize(obstacles.size());
  obstacle_heights_.resize(heights_.empty() ? 0 : obstacles.size());
  for (std::size_t o = 0; o < obstacles.size(); ++o)
  {
    obstacles_[o] = across(obstacles[o]);
    if (!heights_.empty())
      obstacle_heights_[o] = heightOf(obstacles[o]);
  }
  if (!dense_)
    return;
  near_obstacle_.assign((starts_.size() - 1 + 63) / 64, 0);
  for (const Box32& box : obstacles_)
  {
    // (within the array)
    const std::int64_t x0 = std::max(firstReaching(box.min[0]), min_x_ - 1);
    const std::int64_t x1 = std::min(lastReaching(box.max[0]), min_x_ + width_ - 2);
    const std::int64_t y0 = std::max(firstReaching(box.min[1]), min_y_ - 1);
    const std::int64_t y1 = std::min(lastReaching(box.max[1]), min_y_ + height_ - 2);
    for (std::int64_t iy = y0; iy <= y1; ++iy)
      for (std::int64_t ix = x0; ix <= x1; ++ix)
      {
        const std::size_t s = slotOf(ix, iy);
        near_obstacle_[s >> 6] |= std::uint64_t{1} << (s & 63);
      }
  }
}

bool StepGrid::fits(std::uint32_t i, const Box32& box) const
{
  // strictly within half a cell of the item's own cell
  const auto [cx, cy] = cellOf(i);
  const double lo_x = (static_cast<double>(cx) - 0.5) * cell_, hi_x = (static_cast<double>(cx) + 1.5) * cell_;
  const double lo_y = (static_cast<double>(cy) - 0.5) * cell_, hi_y = (static_cast<double>(cy) + 1.5) * cell_;
  return box.min[0] > lo_x && box.max[0] < hi_x && box.min[1] > lo_y && box.max[1] < hi_y;
}

void StepGrid::update(std::uint32_t i, const Aabb& box)
{
  setBox(i, box);
  if (!moved(i) && fits(i, items_[i].box))
    return;
  moveOut(i);
}

void StepGrid::moveOut(std::uint32_t i)
{
  if (!moved(i))
  {
    items_[i].slot = kMoved;
    moved_list_.push_back(i);  // (scans of the cells pass it by from now on)
    if (moved_list_.size() == kFewMoved + 1)
    {
      // too many to scan from now on: the moved grid takes over, with the boxes so far
      // (sized for a few times as many: it grows as more move, and most steps move few)
      moved_grid_.reset(cell_, 4 * moved_list_.size());
      for (std::uint32_t j : moved_list_)
        moved_grid_.insert(j, items_[j].box.toAabb(ax_, ay_));
      return;
    }
  }
  if (moved_list_.size() > kFewMoved)
    moved_grid_.insert(i, items_[i].box.toAabb(ax_, ay_));
}
}  // namespace ball_collision_sim::core
