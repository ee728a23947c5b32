#pragma once

#include <sstream>
#include <string>

namespace ball_collision_sim::core
{
/// A number for a message: six significant digits.
inline std::string formatNumber(double value)
{
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}
}  // namespace ball_collision_sim::core
