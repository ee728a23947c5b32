// The simulator node: the scene from the parameter server, stepped on a timer.
#include "ball_collision_sim/ros/simulator_node.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <exception>
#include <iostream>
#include <string>

namespace
{
/// `simulator_node --check SCENE.yaml`: the scene file checked as load_scene checks one,
/// without ROS. The file's path on stdout and exit 0 when it is good; else its one line
/// naming the key and the reason on stderr and exit 1. launch/simulator.launch runs it
/// while roslaunch reads the launch file: a bad scene then fails roslaunch itself (exit
/// 1, before any node starts), as roslaunch does not pass on a node's exit code.
int checkScene(const std::string& path)
{
  try
  {
    ball_collision_sim::yaml::loadValidSceneFile(path);
  }
  catch (const ball_collision_sim::yaml::SceneError& e)
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  std::cout << path;  // (roslaunch keeps all it prints as the parameter's value)
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc == 3 && std::string(argv[1]) == "--check")
    return checkScene(argv[2]);
  ros::init(argc, argv, "ball_sim");
  // Held out here: when the last handle goes, roscpp shuts down and with it the logging
  // that must report a bad scene.
  ros::NodeHandle nh, pnh("~");
  try
  {
    ball_collision_sim::bridge::SimulatorNode node(nh, pnh);
    ros::spin();
  }
  catch (const ball_collision_sim::yaml::SceneError& e)
  {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  catch (const std::exception& e)
  {
    // (what the scene's checks let through and the world refused, or no memory)
    ROS_FATAL("cannot start: %s", e.what());
    return 1;
  }
  return 0;
}
