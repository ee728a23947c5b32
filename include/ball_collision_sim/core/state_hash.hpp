#pragma once

#include <cstdint>
#include <cstring>

namespace ball_collision_sim::core
{
/// 64-bit FNV-1a over exact bit patterns: equal hashes mean (almost surely) equal bits.
class Fnv1a
{
public:
  void add(const void* data, std::size_t size);
  template <class T>
  void add(const T& value)
  {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    add(bytes, sizeof(T));
  }
  std::uint64_t value() const { return hash_; }

private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};
}  // namespace ball_collision_sim::core
