#pragma once
// The checks behind the two fuzz targets (test/fuzz/fuzz_*.cpp, built with clang and
// libFuzzer by `make fuzz`) and behind test_fuzz_replay (built with the package's compiler,
// part of `make test`), which runs every input kept under test/fuzz/ through them again.
// Each returns "" when the input was handled correctly, or what went wrong.

#include "ball_collision_sim/core/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ball_collision_sim::fuzz
{
/// parseScene() on arbitrary bytes: either a SceneError whose message is one printable
/// line starting with the source name, or a scene. A scene's validate() issues must each
/// name a key and a reason; a scene without issues must build a World with finite states.
std::string checkSceneReader(const std::uint8_t* data, std::size_t size);

/// A small scene decoded from fuzz bytes, and how long to run it.
struct StepCase
{
  core::Scene scene;
  int steps = 0;
  /// walls[0 .. box_walls) enclose the floor: every ball must stay inside each of them.
  std::size_t box_walls = 0;
};

/// On a curved floor a ball starts slow enough to cross at most this fraction of the floor
/// in a step: a step's motion is a straight chord between points on the surface, which
/// breaks down when one step spans much of the floor's curvature (at half the floor per
/// step, 5 of 40,000 decoded scenes let a ball out of its box; see the README).
constexpr double kCurvedFloorStepFraction = 0.05;

/// Decodes any bytes into a scene of a few balls (plane or biquadratic floor, a closed box
/// of walls or none, a few walls inside, restitution in [0, 1], dt, gravity). The scene
/// may still fail validate(); the caller skips it then.
StepCase decodeStepCase(const std::uint8_t* data, std::size_t size);

/// Energy may rise by at most this fraction of the energies involved per step (sum of
/// kinetic energies and of |potential| energies) ...
constexpr double kEnergyRelativeTolerance = 1e-9;
/// ... plus this [J].
constexpr double kEnergyAbsoluteTolerance = 1e-12;
/// Deepest overlap allowed between two balls or a ball and a wall [m].
constexpr double kOverlapTolerance = 1e-9;

/// Steps the decoded scene (when validate() accepts it) and checks after every step: no
/// NaN or inf, no overlap deeper than kOverlapTolerance between balls or with a wall, no
/// ball outside the box or lost from a walled floor, the same balls, and kinetic plus
/// potential energy never rising beyond the tolerances above; then takes out the balls
/// lost from a floor without walls, as the node does.
std::string checkStepping(const std::uint8_t* data, std::size_t size);

/// Every regular file under `dir`, sorted by name.
std::vector<std::string> filesIn(const std::string& dir);
/// The bytes of a file.
std::vector<std::uint8_t> readBytes(const std::string& path);
}  // namespace ball_collision_sim::fuzz
