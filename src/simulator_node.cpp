// The simulator node: the scene from the parameter server, stepped on a timer.
#include "ball_collision_sim/ros/simulator_node.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <exception>

int main(int argc, char** argv)
{
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
