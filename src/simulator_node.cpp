// The simulator node: the scene from the parameter server, stepped on a timer.
#include "ball_collision_sim/ros/simulator_node.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "ball_sim");
  try
  {
    ball_collision_sim::bridge::SimulatorNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  }
  catch (const ball_collision_sim::yaml::SceneError& e)
  {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}
