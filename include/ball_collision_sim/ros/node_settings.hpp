#pragma once

#include "ball_collision_sim/core/step_settings.hpp"
#include "ball_collision_sim/node_settings.hpp"

#include <ball_collision_sim/SimulatorConfig.h>
#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace ball_collision_sim::bridge
{
/// The node's settings with what depends on where it runs made definite.
struct ResolvedSettings
{
  NodeSettings node;
  std::string frame_prefix;   ///< before each ball's tf frame name
  bool publish_clock = true;  ///< whether this node publishes /clock
};

/// The tf frame prefix a node in namespace `ns` takes by default: the namespace without
/// its leading '/', and a '/' after it ("/a/b" -> "a/b/"); "" in the root namespace.
std::string defaultFramePrefix(const std::string& ns);

/// Fills in frame_prefix and publish_clock where the settings leave them unset: by
/// default only a node in the root namespace publishes /clock.
ResolvedSettings resolve(const NodeSettings& node, const std::string& ns);

/// The step's settings the node's ask for (its threads), the rest the core's defaults.
core::StepSettings stepSettingsOf(const NodeSettings& node);

/// Copies the settings named by `keys` (node keys, e.g. "marker_rate") from `from` to `to`.
void copyKeys(const std::vector<std::string>& keys, const NodeSettings& from, NodeSettings& to);

/// The run-time settings as dynamic_reconfigure's config.
SimulatorConfig toConfig(const NodeSettings& node);

/// Every value of `config` that the node does not take, one "key: reason" each: a number
/// outside its range in cfg/Simulator.cfg (the scene's bounds) or not finite, a ball colour
/// other than speed, id or motion.
std::vector<std::string> checkConfig(const SimulatorConfig& config);

/// The settings of a config that checkConfig() passes.
void applyConfig(const SimulatorConfig& config, NodeSettings& node);
}  // namespace ball_collision_sim::bridge
