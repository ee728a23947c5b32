#include "ball_collision_sim/core/state_hash.hpp"

namespace ball_collision_sim::core
{
void Fnv1a::add(const void* data, std::size_t size)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i)
  {
    hash_ ^= bytes[i];
    hash_ *= 0x100000001b3ULL;
  }
}
}  // namespace ball_collision_sim::core
