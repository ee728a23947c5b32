#pragma once

#include <optional>
#include <string>

namespace ball_collision_sim
{
/// How the node draws its balls.
enum class BallColor
{
  kSpeed,   ///< by speed, on a scale up to NodeSettings::speed_color_max
  kId,      ///< a fixed colour per id
  kMotion,  ///< by motion state: sliding, rolling, spinning, stationary
};

/// "speed", "id", "motion"
inline const char* ballColorName(BallColor color)
{
  return color == BallColor::kSpeed ? "speed" : color == BallColor::kId ? "id" : "motion";
}

/// The colour mode of a name, or none.
inline std::optional<BallColor> ballColorNamed(const std::string& name)
{
  for (const BallColor color : {BallColor::kSpeed, BallColor::kId, BallColor::kMotion})
    if (name == ballColorName(color))
      return color;
  return std::nullopt;
}

/// The shortest period of the status line [s]: a period of nearly 0 (a denormal rounds to
/// 0 ns) would fire its timer without pause and flood the log.
constexpr double kMinStatusPeriod = 0.01;

/// Settings read only by the ROS node: what it publishes and how, not physics. They may
/// sit in a scene file beside the scene; the offline tool reads, checks and ignores them.
struct NodeSettings
{
  double real_time_factor = 1.0;  ///< simulated / wall time; 0 = as fast as possible
  double marker_rate = 30.0;      ///< markers per second of wall time [Hz]; 0 = none
  double tf_rate = 30.0;          ///< tf frames per second of wall time [Hz]; 0 = none
  int tf_max_balls = 500;         ///< only the first this many balls get a tf frame
  double state_rate = 0.0;        ///< ball_states per simulated second [Hz]; 0 = every step
  bool publish_collisions = true; ///< one message per handled collision
  bool start_paused = false;      ///< wait for ~pause false (or ~step) before moving
  /// radius and mass of balls added from rviz clicks [m, kg]; a scene file that does not
  /// set them gives its most common ball's (yaml::parseSceneFile())
  double click_radius = 0.1;
  double click_mass = 1.0;
  double status_period = 0.0;     ///< a status line every this many wall seconds [s], >= kMinStatusPeriod; 0 = none
  int max_balls = 100000;         ///< add_ball and clicks are refused past this many balls
  int marker_list_threshold = 1000;  ///< past this many balls, one sphere list per radius
  /// past this many balls, none has an interactive marker (~play) to drag or choose as the
  /// cue ball: rviz draws each with its controls, and slows down with hundreds
  int play_max_balls = 100;
  int threads = 1;                ///< threads the step runs on (the same bits for any); 0 = every core
  BallColor ball_color = BallColor::kSpeed;  ///< how balls are coloured
  double speed_color_max = 0.0;  ///< speed at the top of the colour scale [m/s]; 0 = the fastest ball at the start
  bool collision_flashes = true;  ///< a short-lived marker at each collision's contact point
  /// whether this node publishes /clock; unset: only a node in the root namespace does,
  /// so that of several simulators in namespaces none does unless asked
  std::optional<bool> publish_clock;
  /// put before each ball's tf frame name (ball_<id>); unset: the node's namespace
  /// ("a/" in /a, "" in the root namespace), so that simulators side by side share no frame
  std::optional<std::string> frame_prefix;
};

}  // namespace ball_collision_sim
