// The directions balls may not move along for the rest of a step: toward a wall a ball
// leans on, or toward a ball that cannot give way. A ball in a corner or in a pile at
// rest has several; most balls have none, and no set. All sets of a step share one pool,
// emptied at the step's start, so that a set grows as far as its contacts take it and the
// step allocates only as the largest step so far did. Reads and writes only itself. Not
// part of the public interface; tested on its own (test/test_contact_solver.cpp).
#pragma once

#include "contact_solver.hpp"

#include <cstdint>
#include <vector>

namespace ball_collision_sim::core::step
{
class BlockedDirections
{
public:
  /// No sets, as at a step's start (the pool keeps its room).
  void clear()
  {
    sets_.clear();
    directions_.clear();
    sources_.clear();
  }
  bool empty() const { return sets_.empty(); }
  /// A new, empty set; its index.
  std::int32_t open()
  {
    sets_.emplace_back();
    return static_cast<std::int32_t>(sets_.size() - 1);
  }
  /// Blocks `direction` (unit) in set s. Each comes from a source (a wall's direction
  /// along the floor, a wall's own normal, another ball: World::wallSource(),
  /// World::ballSource()), and a source's latest contact replaces its direction: the ball
  /// has moved since, and on a curved floor, or around a wall's edge or corner, the
  /// direction has turned with it. A direction within `same_direction` (1 - cosine) of
  /// one the set has is that one.
  void add(std::int32_t s, Vec3 direction, std::uint64_t source, double same_direction)
  {
    Set& set = sets_[static_cast<std::size_t>(s)];
    for (std::uint32_t k = set.first; k < set.first + set.count; ++k)
      if (sources_[k] == source)
      {
        directions_[k] = direction;
        return;
      }
    for (std::uint32_t k = set.first; k < set.first + set.count; ++k)
      if (directions_[k].dot(direction) > 1 - same_direction)
        return;
    if (set.count == set.room)
      grow(set);
    directions_[set.first + set.count] = direction;
    sources_[set.first + set.count] = source;
    ++set.count;
  }
  /// Whether every contact that blocks set s is elastic (e = 1): it turns the ball's
  /// velocity and takes none of its speed. An inelastic one takes the part of the
  /// velocity into it, the sum of the bounces that a resting contact stands for.
  bool elastic(std::int32_t s) const { return sets_[static_cast<std::size_t>(s)].elastic; }
  void markInelastic(std::int32_t s) { sets_[static_cast<std::size_t>(s)].elastic = false; }

  std::size_t count(std::int32_t s) const { return sets_[static_cast<std::size_t>(s)].count; }
  const Vec3& direction(std::int32_t s, std::size_t k) const
  {
    return directions_[sets_[static_cast<std::size_t>(s)].first + k];
  }
  std::uint64_t source(std::int32_t s, std::size_t k) const
  {
    return sources_[sets_[static_cast<std::size_t>(s)].first + k];
  }

  /// The nearest vector to `w` with <u, d> <= 0 for every direction d of set s
  /// (keptOut(), which lets through `slack` of |w| as round-off).
  Vec3 allowed(std::int32_t s, const Vec3& w, double slack) const
  {
    const Set& set = sets_[static_cast<std::size_t>(s)];
    return keptOut(w, directions_.data() + set.first, set.count, slack);
  }

private:
  struct Set
  {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::uint32_t room = 0;
    bool elastic = true;
  };
  /// Set's directions moved to the pool's end, with room for 4 at first and twice as many
  /// at each move after (most sets hold one to four; the room they leave behind is reused
  /// at the next step).
  void grow(Set& set)
  {
    const std::uint32_t first = static_cast<std::uint32_t>(directions_.size());
    const std::uint32_t room = set.room == 0 ? 4 : 2 * set.room;
    directions_.resize(first + room);
    sources_.resize(first + room);
    for (std::uint32_t k = 0; k < set.count; ++k)
    {
      directions_[first + k] = directions_[set.first + k];
      sources_[first + k] = sources_[set.first + k];
    }
    set.first = first;
    set.room = room;
  }

  std::vector<Set> sets_;
  std::vector<Vec3> directions_;
  std::vector<std::uint64_t> sources_;
};
}  // namespace ball_collision_sim::core::step
