// The records in the step's cell order: the step visits balls_ in the order of the grid's
// cells, so that neighbours in space are neighbours in memory; an edit puts them back in
// id order. Reads and writes balls_, feet_, spins_ and by_id_ (the slot of each ball by
// its place in id order).
#include "ball_collision_sim/core/world.hpp"

namespace ball_collision_sim::core
{
void World::sortById()
{
  bool sorted = true;
  for (std::size_t k = 0; k < by_id_.size() && sorted; ++k)
    sorted = by_id_[k] == k;
  if (sorted)
    return;
  std::vector<std::uint32_t> from = by_id_;  // slot k takes the k-th by id
  permute(from);
}

void World::invertInPlace(std::vector<std::uint32_t>& p)
{
  // Cycle by cycle: along k -> p[k] -> p[p[k]] -> ..., each entry takes the index before
  // it, marked done in its top bit (free: slots are below 2^31).
  constexpr std::uint32_t kDone = 0x80000000u;
  for (std::uint32_t start = 0; start < p.size(); ++start)
  {
    if (p[start] & kDone)
      continue;
    std::uint32_t before = start;
    std::uint32_t at = p[start];
    while (at != start)
    {
      const std::uint32_t next = p[at];
      p[at] = before | kDone;
      before = at;
      at = next;
    }
    p[start] = before | kDone;
  }
  for (std::uint32_t& k : p)
    k &= ~kDone;
}

void World::permute(std::vector<std::uint32_t>& from)
{
  // Where each slot's record goes, for by_id_: slot from[k] -> slot k (the inverse of
  // `from`, turned in place and back, so that no second list is needed).
  invertInPlace(from);
  for (std::uint32_t& slot : by_id_)
    slot = from[slot];
  invertInPlace(from);
  // In place, cycle by cycle: slot k takes from[k]'s record, and from[k] = k marks it done.
  const auto move = [&](std::uint32_t into, std::uint32_t out) {
    balls_[into] = balls_[out];
    if (!feet_.empty())
      feet_[into] = feet_[out];
    if (!spins_.empty())
      spins_[into] = spins_[out];
  };
  for (std::uint32_t k = 0; k < from.size(); ++k)
  {
    if (from[k] == k)
      continue;
    const Ball ball = balls_[k];
    const Vec2 foot = feet_.empty() ? no_foot_ : feet_[k];
    const BallSpin spin = spins_.empty() ? BallSpin{} : spins_[k];
    std::uint32_t at = k;
    while (from[at] != k)
    {
      const std::uint32_t next = from[at];
      move(at, next);
      from[at] = at;
      at = next;
    }
    from[at] = at;
    balls_[at] = ball;
    if (!feet_.empty())
      feet_[at] = foot;
    if (!spins_.empty())
      spins_[at] = spin;
  }
}
}  // namespace ball_collision_sim::core
