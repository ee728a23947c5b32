// The scene's sections read from YAML: the floor, walls, balls, friction, random balls
// and the node's settings, each failing with the key's path and the reason.
#pragma once

#include "yaml_values.hpp"

#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <string>

namespace ball_collision_sim::yaml::sections
{
core::FloorDef readFloor(const YAML::Node& node, const std::string& key);
core::WallDef readWall(const YAML::Node& node, const std::string& key);
core::PocketDef readPocket(const YAML::Node& node, const std::string& key);
core::FrictionDef readFriction(const YAML::Node& node, const std::string& key);
core::BallDef readBall(const YAML::Node& node, const std::string& key);
core::RandomBallsDef readRandomBalls(const YAML::Node& node, const std::string& key);
/// The node's keys of the scene's top level into `node`.
void readNodeSettings(const values::MapFields& fields, NodeSettings& node);
}  // namespace ball_collision_sim::yaml::sections
