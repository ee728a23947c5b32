#pragma once

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <optional>
#include <string>
#include <vector>

namespace ball_collision_sim::core
{
/// Puts a ball on the floor: its centre goes to foot + r n and its velocity loses its
/// part normal to the floor. Returns why it cannot stand there (its foot is outside the
/// floor, or its centre is below the surface or more than 2 r above it), or "".
std::string placeOnFloor(BallDef& ball, const std::optional<Floor>& floor, Vec2* uv = nullptr);

/// The first wall a ball overlaps by more than kContactTolerance.
struct Overlap
{
  std::size_t index = 0;  ///< into the list searched
  double depth = 0.0;     ///< [m]
};
std::optional<Overlap> wallOverlap(const BallDef& ball, const std::vector<Wall>& walls);

/// The floor and walls of a scene, to place balls among them.
class Placement
{
public:
  explicit Placement(const Scene& scene);
  /// placeOnFloor, then wallOverlap.
  std::string place(BallDef& ball, Vec2* uv = nullptr) const;
  const std::optional<Floor>& floor() const { return floor_; }
  const std::vector<Wall>& walls() const { return walls_; }

private:
  std::optional<Floor> floor_;
  std::vector<Wall> walls_;
};
}  // namespace ball_collision_sim::core
