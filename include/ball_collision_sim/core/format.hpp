#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace ball_collision_sim::core
{
/// A number as messages and outputs print it: the shortest text that reads back to the
/// same double (std::to_chars; 0.1, not 0.10000000000000001 nor 0.100000), NaN as "nan"
/// whatever its sign bit, infinities as "inf" and "-inf".
inline std::string formatNumber(double value)
{
  if (std::isnan(value))
    return "nan";
  char buffer[32];
  const std::to_chars_result out = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, out.ptr);
}
}  // namespace ball_collision_sim::core
