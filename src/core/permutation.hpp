// Permutations applied in place, cycle by cycle, so that putting the records in a new
// order (the step's cell order, or id order after an edit) takes no second copy of them
// nor of the permutation. Reads and writes only its arguments. Not part of the public
// interface; tested on its own (test/test_cell_order.cpp).
#pragma once

#include <cstdint>
#include <vector>

namespace ball_collision_sim::core
{
/// p becomes its inverse permutation (q[p[k]] = k), in place; p.size() below 2^31.
inline void invertInPlace(std::vector<std::uint32_t>& p)
{
  // Cycle by cycle: along k -> p[k] -> p[p[k]] -> ..., each entry takes the index before
  // it, marked done in its top bit (free: indices are below 2^31).
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

/// Slot k of the records takes the record that was in slot from[k], in place, for every
/// k; `from` is left as the identity. `records` moves them: records.save(k) keeps slot
/// k's record aside, records.move(into, out) copies slot out's into slot into, and
/// records.restore(k) puts the one kept aside into slot k.
template <class Records>
void gatherInPlace(std::vector<std::uint32_t>& from, Records& records)
{
  // (one record aside per cycle; from[k] = k marks slot k done)
  for (std::uint32_t k = 0; k < from.size(); ++k)
  {
    if (from[k] == k)
      continue;
    records.save(k);
    std::uint32_t at = k;
    while (from[at] != k)
    {
      const std::uint32_t next = from[at];
      records.move(at, next);
      from[at] = at;
      at = next;
    }
    from[at] = at;
    records.restore(at);
  }
}
}  // namespace ball_collision_sim::core
