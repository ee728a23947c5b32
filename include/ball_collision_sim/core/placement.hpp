#pragma once

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ball_collision_sim::core
{
/// How a new or moved ball meets the floor.
enum class Landing
{
  /// onto the surface point nearest its centre, which must lie between the surface and
  /// 2 r above it (scene files: a misplaced ball is an error there, not a guess)
  kNearest,
  /// onto the floor under its centre along gravity, whatever its height (services and
  /// clicks: the centre keeps its place across gravity)
  kUnder,
  /// where it is: its centre must already rest on the floor, one radius above it
  /// (within kContactTolerance)
  kExact,
  /// exactly where it is, its velocity whole (BallPlacement::kAsGiven): more than
  /// kContactTolerance above the floor it is in flight; below the surface, refused
  kAsGiven,
};

/// Puts a ball on the floor as `landing` says: its centre goes to foot + r n and its
/// velocity loses its part normal to the floor. Returns why it cannot stand there (its
/// foot is outside the floor, or its centre is not where `landing` allows), or "".
/// `flying` (where given) tells whether the ball is in flight there (Landing::kAsGiven).
std::string placeOnFloor(BallDef& ball, const std::optional<Floor>& floor, Vec2* uv = nullptr,
                         Landing landing = Landing::kNearest, bool* flying = nullptr);
/// How a scene file's ball with this placement meets the floor.
Landing landingOf(BallPlacement placement);

/// The first wall a ball overlaps by more than kContactTolerance.
struct Overlap
{
  std::size_t index = 0;  ///< into the list searched
  double depth = 0.0;     ///< [m]
};
std::optional<Overlap> wallOverlap(const BallDef& ball, const std::vector<Wall>& walls);

/// "overlaps <what> by <depth> m": how every message says that a ball overlaps something.
std::string overlapMessage(const std::string& what, double depth);

/// The placement check of scene files, services and clicks alike: puts `ball` on the
/// floor as `landing` says and checks it against the walls; why it cannot stand there
/// ("off the floor (...)", or overlapMessage() with `wall_name(k)` naming walls[k]), or "".
std::string placeAmongWalls(BallDef& ball, const std::optional<Floor>& floor, const std::vector<Wall>& walls,
                            Landing landing, Vec2* uv, const std::function<std::string(std::size_t)>& wall_name,
                            bool* flying = nullptr);

/// The floor and walls of a scene, to place balls among them.
class Placement
{
public:
  explicit Placement(const Scene& scene);
  /// placeOnFloor as the ball's placement says, then wallOverlap.
  std::string place(BallDef& ball, Vec2* uv = nullptr) const;
  const std::optional<Floor>& floor() const { return floor_; }
  const std::vector<Wall>& walls() const { return walls_; }

private:
  std::optional<Floor> floor_;
  std::vector<Wall> walls_;
};
}  // namespace ball_collision_sim::core
