// The scene's checks of single values, each failing with the key's name and the reason
// (scene.cpp's validate() and check() are made of them).
#pragma once

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/scene.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace ball_collision_sim::core::scene_checks
{
inline std::string index(const std::string& key, std::size_t i)
{
  return key + "[" + std::to_string(i) + "]";
}

/// Collects issues; each check returns whether the value passed.
class Checker
{
public:
  explicit Checker(std::vector<SceneIssue>& issues) : issues_(issues) {}

  void fail(const std::string& key, const std::string& reason) { issues_.push_back({key, reason}); }

  bool finite(const std::string& key, double value)
  {
    if (std::isfinite(value))
      return true;
    fail(key, "must be finite (got " + formatNumber(value) + ")");
    return false;
  }
  bool finite(const std::string& key, const Vec3& value)
  {
    if (value.allFinite())
      return true;
    fail(key, "must be finite (got [" + formatNumber(value.x()) + ", " + formatNumber(value.y()) + ", " + formatNumber(value.z()) + "])");
    return false;
  }
  /// finite and |value| <= limit
  bool bounded(const std::string& key, const Vec3& value, double limit, const char* unit)
  {
    if (!finite(key, value))
      return false;
    // stableNorm: 1e300 must read as 1e300, not overflow to inf
    if (value.stableNorm() <= limit)
      return true;
    fail(key, "length must be <= " + formatNumber(limit) + " " + unit + " (got " + formatNumber(value.stableNorm()) + ")");
    return false;
  }
  /// finite and in [least, limit], least > 0
  bool positive(const std::string& key, double value, double least, double limit, const char* unit)
  {
    if (!finite(key, value))
      return false;
    if (!(value > 0))
    {
      fail(key, "must be > 0 (got " + formatNumber(value) + ")");
      return false;
    }
    if (value < least)
    {
      fail(key, "must be >= " + formatNumber(least) + " " + unit + " (got " + formatNumber(value) + ")");
      return false;
    }
    if (value > limit)
    {
      fail(key, "must be <= " + formatNumber(limit) + " " + unit + " (got " + formatNumber(value) + ")");
      return false;
    }
    return true;
  }
  /// k in I = k m r^2: in [kMinInertia, 1]
  bool inertia(const std::string& key, double value)
  {
    if (!finite(key, value))
      return false;
    if (value >= kMinInertia && value <= 1)
      return true;
    fail(key, "must be solid, hollow or a number k in [" + formatNumber(kMinInertia) + ", 1] (got " +
                  formatNumber(value) + ")");
    return false;
  }
  /// finite and in [0, limit]
  bool nonNegative(const std::string& key, double value, double limit)
  {
    if (!finite(key, value))
      return false;
    if (value >= 0 && value <= limit)
      return true;
    fail(key, "must be in [0, " + formatNumber(limit) + "] (got " + formatNumber(value) + ")");
    return false;
  }
  bool unitInterval(const std::string& key, double value)
  {
    if (!finite(key, value))
      return false;
    if (value >= 0 && value <= 1)
      return true;
    fail(key, "must be in [0, 1] (got " + formatNumber(value) + ")");
    return false;
  }
  /// Two edge vectors spanning a parallelogram: non-zero, bounded, not parallel.
  bool edges(const std::string& prefix, const Vec3& u, const Vec3& v)
  {
    bool ok = bounded(prefix + "u", u, kMaxLength, "m");
    ok = bounded(prefix + "v", v, kMaxLength, "m") && ok;
    if (!ok)
      return false;
    for (const auto& [name, edge] : {std::pair{"u", &u}, std::pair{"v", &v}})
    {
      const double length = edge->stableNorm();
      if (length == 0)
      {
        fail(prefix + name, "must be non-zero");
        return false;
      }
      if (length < kMinLength)
      {
        fail(prefix + name, "length must be >= " + formatNumber(kMinLength) + " m (got " + formatNumber(length) + ")");
        return false;
      }
    }
    if (u.cross(v).norm() <= 1e-9 * u.norm() * v.norm())
    {
      fail(prefix + "v", "parallel to " + prefix + "u (they must span a parallelogram)");
      return false;
    }
    return true;
  }
  bool range(const std::string& key, const Range& r, double lowest, bool strict, double limit)
  {
    if (!finite(key + ".min", r.min) || !finite(key + ".max", r.max))
      return false;
    if (strict ? !(r.min > lowest) : !(r.min >= lowest))
    {
      fail(key, std::string("minimum must be ") + (strict ? "> " : ">= ") + formatNumber(lowest) + " (got " + formatNumber(r.min) + ")");
      return false;
    }
    if (r.max < r.min)
    {
      fail(key, "maximum " + formatNumber(r.max) + " is below minimum " + formatNumber(r.min));
      return false;
    }
    if (r.max > limit)
    {
      fail(key, "maximum must be <= " + formatNumber(limit) + " (got " + formatNumber(r.max) + ")");
      return false;
    }
    return true;
  }

private:
  std::vector<SceneIssue>& issues_;
};
}  // namespace ball_collision_sim::core::scene_checks
