#include "ball_collision_sim/ros/node_settings.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <boost/any.hpp>

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::bridge
{
std::string defaultFramePrefix(const std::string& ns)
{
  std::string prefix = ns;
  while (!prefix.empty() && prefix.front() == '/')
    prefix.erase(prefix.begin());
  while (!prefix.empty() && prefix.back() == '/')
    prefix.pop_back();
  return prefix.empty() ? prefix : prefix + "/";
}

ResolvedSettings resolve(const NodeSettings& node, const std::string& ns)
{
  ResolvedSettings out;
  out.node = node;
  out.frame_prefix = node.frame_prefix ? *node.frame_prefix : defaultFramePrefix(ns);
  out.publish_clock = node.publish_clock ? *node.publish_clock : defaultFramePrefix(ns).empty();
  out.node.frame_prefix = out.frame_prefix;
  out.node.publish_clock = out.publish_clock;
  return out;
}

core::StepSettings stepSettingsOf(const NodeSettings& node)
{
  core::StepSettings settings;
  settings.threads = static_cast<unsigned>(node.threads);  // (validateNodeSettings(): in [0, kMaxThreads])
  return settings;
}

void copyKeys(const std::vector<std::string>& keys, const NodeSettings& from, NodeSettings& to)
{
  for (const std::string& key : keys)
  {
    if (key == "real_time_factor")
      to.real_time_factor = from.real_time_factor;
    else if (key == "marker_rate")
      to.marker_rate = from.marker_rate;
    else if (key == "tf_rate")
      to.tf_rate = from.tf_rate;
    else if (key == "tf_max_balls")
      to.tf_max_balls = from.tf_max_balls;
    else if (key == "state_rate")
      to.state_rate = from.state_rate;
    else if (key == "publish_collisions")
      to.publish_collisions = from.publish_collisions;
    else if (key == "start_paused")
      to.start_paused = from.start_paused;
    else if (key == "click_radius")
      to.click_radius = from.click_radius;
    else if (key == "click_mass")
      to.click_mass = from.click_mass;
    else if (key == "status_period")
      to.status_period = from.status_period;
    else if (key == "max_balls")
      to.max_balls = from.max_balls;
    else if (key == "marker_list_threshold")
      to.marker_list_threshold = from.marker_list_threshold;
    else if (key == "play_max_balls")
      to.play_max_balls = from.play_max_balls;
    else if (key == "ball_color")
      to.ball_color = from.ball_color;
    else if (key == "speed_color_max")
      to.speed_color_max = from.speed_color_max;
    else if (key == "collision_flashes")
      to.collision_flashes = from.collision_flashes;
    else if (key == "publish_clock")
      to.publish_clock = from.publish_clock;
    else if (key == "frame_prefix")
      to.frame_prefix = from.frame_prefix;
    else if (key == "threads")
      to.threads = from.threads;
  }
}

SimulatorConfig toConfig(const NodeSettings& node)
{
  SimulatorConfig config = SimulatorConfig::__getDefault__();
  config.real_time_factor = node.real_time_factor;
  config.marker_rate = node.marker_rate;
  config.tf_rate = node.tf_rate;
  config.tf_max_balls = node.tf_max_balls;
  config.state_rate = node.state_rate;
  config.publish_collisions = node.publish_collisions;
  config.click_radius = node.click_radius;
  config.click_mass = node.click_mass;
  config.status_period = node.status_period;
  config.max_balls = node.max_balls;
  config.marker_list_threshold = node.marker_list_threshold;
  config.play_max_balls = node.play_max_balls;
  config.ball_color = ballColorName(node.ball_color);
  config.speed_color_max = node.speed_color_max;
  config.collision_flashes = node.collision_flashes;
  return config;
}

namespace
{
/// Why `value` is not in [low, high], or "".
template <typename Number>
std::string outOfRange(const std::string& key, Number value, Number low, Number high)
{
  const auto text = [](Number x) { return core::formatNumber(static_cast<double>(x)); };
  if (!std::isfinite(static_cast<double>(value)))
    return key + ": must be finite (got " + text(value) + ")";
  if (value < low)
    return key + ": must be >= " + text(low) + " (got " + text(value) + ")";
  if (value > high)
    return key + ": must be <= " + text(high) + " (got " + text(value) + ")";
  return "";
}
}  // namespace

std::vector<std::string> checkConfig(const SimulatorConfig& config)
{
  std::vector<std::string> issues;
  const SimulatorConfig& low = SimulatorConfig::__getMin__();
  const SimulatorConfig& high = SimulatorConfig::__getMax__();
  for (const auto& param : SimulatorConfig::__getParamDescriptions__())
  {
    boost::any value, min, max;
    param->getValue(config, value);
    param->getValue(low, min);
    param->getValue(high, max);
    std::string why;
    if (param->type == "double")
      why = outOfRange(param->name, boost::any_cast<double>(value), boost::any_cast<double>(min),
                       boost::any_cast<double>(max));
    else if (param->type == "int")
      why = outOfRange(param->name, boost::any_cast<int>(value), boost::any_cast<int>(min), boost::any_cast<int>(max));
    if (!why.empty())
      issues.push_back(why);
  }
  // (an enum of strings dynamic_reconfigure does not check)
  if (!ballColorNamed(config.ball_color))
  {
    issues.push_back("ball_color: expected speed, id or motion, got \"" + config.ball_color + "\"");
    return issues;
  }
  // what the scene's validation says besides the ranges (a status period of nearly 0), of
  // the settings no range above refused
  NodeSettings node;  // (the defaults, good, for the settings a config does not hold)
  applyConfig(config, node);
  for (const core::SceneIssue& issue : yaml::validateNodeSettings(node))
    if (std::none_of(issues.begin(), issues.end(),
                     [&](const std::string& seen) { return seen.rfind(issue.key + ": ", 0) == 0; }))
      issues.push_back(issue.str());
  return issues;
}

void applyConfig(const SimulatorConfig& config, NodeSettings& node)
{
  node.real_time_factor = config.real_time_factor;
  node.marker_rate = config.marker_rate;
  node.tf_rate = config.tf_rate;
  node.state_rate = config.state_rate;
  node.click_radius = config.click_radius;
  node.click_mass = config.click_mass;
  node.status_period = config.status_period;
  node.speed_color_max = config.speed_color_max;
  node.tf_max_balls = config.tf_max_balls;
  node.max_balls = config.max_balls;
  node.marker_list_threshold = config.marker_list_threshold;
  node.play_max_balls = config.play_max_balls;
  node.publish_collisions = config.publish_collisions;
  node.collision_flashes = config.collision_flashes;
  node.ball_color = *ballColorNamed(config.ball_color);  // (checkConfig(): a colour's name)
}
}  // namespace ball_collision_sim::bridge
