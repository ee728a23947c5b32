#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <string>

namespace ball_collision_sim::bridge
{
/// A parameter tree as YAML text (flow style), so that the parameter server and YAML
/// files go through one reader: the same keys, types, defaults and messages. Reals keep
/// a decimal point so that they stay reals; strings that rosparam's YAML 1.1 left as
/// strings but YAML 1.2 reads as numbers (`1e-3`) go back to numbers.
std::string toYaml(XmlRpc::XmlRpcValue& value);

/// The scene and the node's settings under the namespace of `nh` (where the launch
/// file's <rosparam command="load"> put them), read and validated. Throws
/// yaml::SceneError with one line naming the parameter and the reason.
yaml::SceneFile loadSceneParams(const ros::NodeHandle& nh);

/// YAML text (block or flow) as a parameter tree: quoted scalars are strings, true and
/// false booleans, integers that fit ints, other numbers doubles.
XmlRpc::XmlRpcValue toXmlRpc(const std::string& yaml_text);

/// Replaces everything under the namespace of `nh` with `scene`, every key with the
/// value in use (defaults included), so that `rosparam get` shows what the node runs.
void writeSceneParams(const ros::NodeHandle& nh, const core::Scene& scene, const NodeSettings& node);
}  // namespace ball_collision_sim::bridge
