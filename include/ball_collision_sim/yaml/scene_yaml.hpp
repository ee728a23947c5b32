#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/node_settings.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ball_collision_sim::yaml
{
/// A scene that cannot be read. what() is the whole one-line message, prefixed by the
/// source: "scene.yaml: balls[3].radus: unknown key (expected one of: ...)", or
/// "scene.yaml:12:5: <parser message>" for malformed YAML.
struct SceneError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Top-level keys that only the ROS node uses (NodeSettings); the offline tool reads and
/// checks them like every other key, and ignores them.
inline constexpr std::array<std::string_view, 19> kNodeOnlyKeys{
  "real_time_factor", "marker_rate", "tf_rate", "tf_max_balls", "state_rate", "publish_collisions",
  "start_paused", "click_radius", "click_mass", "status_period", "max_balls", "marker_list_threshold",
  "play_max_balls", "ball_color", "speed_color_max", "collision_flashes", "publish_clock", "frame_prefix", "threads",
};

/// A scene file: the scene, and the node's settings beside it.
struct SceneFile
{
  core::Scene scene;
  NodeSettings node;
  std::vector<std::string> node_keys;  ///< the node keys the text sets, in the order written
  core::SceneCheck checked;            ///< what check() found: build a World from it
};

/// Reads a scene file from YAML text: parseScene() and the node's settings. Their values
/// are checked as they are read (types, ball_color, frame_prefix); their ranges by
/// validateNodeSettings().
SceneFile parseSceneFile(const std::string& yaml_text, const std::string& source_name = "<string>");

/// Every problem of the node's settings (a negative rate, a radius out of range, ...),
/// keyed by the setting's name.
std::vector<core::SceneIssue> validateNodeSettings(const NodeSettings& node);

/// core::check() of the scene (kept in file.checked), then validateNodeSettings():
/// every issue of the file.
std::vector<core::SceneIssue> check(SceneFile& file);

/// parseSceneFile() of a file, then check(): when it finds issues, throws SceneError
/// "path: " + every issue.
SceneFile loadValidSceneFile(const std::string& path);

/// Reads a scene from YAML text (design.md section 5). Every key is checked: an unknown
/// key, a value of the wrong type or a missing required key throws SceneError naming
/// the key path as written in the YAML ("balls[3].radius",
/// "floor.control_points[1][2]"). Integers are accepted where reals are expected; strings
/// and booleans are not. `.nan` and `.inf` are read as numbers: rejecting them is the job
/// of core::validate(), which this function does not call. An empty (null) `floor`,
/// `walls`, `balls`, `random_balls` or `region` means the section is absent.
/// @param source_name prefixes every error message (a file path, or "<string>")
core::Scene parseScene(const std::string& yaml_text, const std::string& source_name = "<string>");

/// A file's text; throws SceneError "path: cannot open file (...)" or "cannot read file".
std::string readTextFile(const std::string& path);

/// parseScene() of a file's contents; errors are prefixed by `path`. An unreadable file
/// throws SceneError "path: cannot open file (No such file or directory)".
core::Scene loadSceneFile(const std::string& path);

/// The scene and settings as YAML text that parseSceneFile() reads back to the same: block style,
/// every key with its value (defaults included; random_balls as given, not expanded),
/// each real in the fewest digits that read back to the same double, written so that
/// YAML 1.1 readers (rosparam) take them as reals too.
std::string writeScene(const core::Scene& scene, const NodeSettings& node);

/// loadValidSceneFile()'s scene: it can build a core::World.
core::Scene loadValidScene(const std::string& path);
}  // namespace ball_collision_sim::yaml
