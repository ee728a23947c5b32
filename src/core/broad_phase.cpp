#include "ball_collision_sim/core/broad_phase.hpp"

#include <algorithm>
#include <cmath>

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
}  // namespace ball_collision_sim::core
