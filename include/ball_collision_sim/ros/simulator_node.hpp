#pragma once

#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/rate_limit.hpp"

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/Step.h>
#include <geometry_msgs/PointStamped.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <optional>
#include <vector>

namespace ball_collision_sim::bridge
{
/// The simulator on ROS: steps the core on a wall-clock timer with the scene's fixed dt,
/// publishes markers, tf, ball states, collisions and /clock (every stamp is simulated
/// time), and takes services to edit, pause, step and reset the world. Callbacks
/// convert, call the core and convert back; all run on one thread.
class SimulatorNode
{
public:
  /// Reads the scene from the private namespace; throws yaml::SceneError when it is bad.
  SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh);

  const core::World& world() const { return world_; }

private:
  void onTimer(const ros::WallTimerEvent& event);
  void onStatus(const ros::WallTimerEvent& event);
  /// One physics step and what is published every step.
  void stepOnce();
  /// Markers and tf, when their wall-clock rates allow (or always, after an edit).
  void publishView(bool force);
  void publishStatic();
  void publishBalls(const ros::Time& stamp);
  void publishTransforms(const ros::Time& stamp);
  void publishStates(const ros::Time& stamp);
  /// Restarts the wall-clock anchor that real time is kept against.
  void anchorClock();
  /// Why no ball may be added now (max_balls reached), or "".
  std::string roomForABall() const;

  bool onAddBall(AddBall::Request& req, AddBall::Response& res);
  bool onAddWall(AddWall::Request& req, AddWall::Response& res);
  bool onRemoveBall(RemoveObject::Request& req, RemoveObject::Response& res);
  bool onRemoveWall(RemoveObject::Request& req, RemoveObject::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onStep(Step::Request& req, Step::Response& res);
  void onClickedPoint(const geometry_msgs::PointStamped& msg);
  void onMarkerSubscriber(const ros::SingleSubscriberPublisher& subscriber);

  std::string scene_yaml_;  ///< the scene as read, published on ~scene
  core::World world_;
  const core::NodeSettings settings_;
  const std::string frame_id_;
  const BallColoring coloring_;  ///< from the world as loaded: the speed scale stays put
  bool paused_;
  std::uint64_t state_every_;  ///< publish ball_states every this many steps

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  ros::Publisher markers_pub_;
  ros::Publisher states_pub_;
  ros::Publisher collisions_pub_;
  ros::Publisher clock_pub_;
  ros::Publisher scene_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::vector<ros::ServiceServer> services_;
  ros::Subscriber clicked_sub_;
  ros::WallTimer timer_;
  ros::WallTimer status_timer_;
  ros::WallTime status_wall_;
  double status_time_ = 0.0;         ///< simulated time at the last status line [s]
  std::uint64_t status_events_ = 0;  ///< events counted at the last status line

  ros::WallTime anchor_wall_;
  std::uint64_t anchor_steps_ = 0;
  RateLimit markers_due_;
  RateLimit tf_due_;
  std::vector<int> shown_balls_;  ///< ball ids drawn last time, to delete the removed
  int shown_lists_ = 0;           ///< sphere lists drawn last time (many balls)
  CollisionFlashes flashes_;      ///< collisions since the last ball markers
};
}  // namespace ball_collision_sim::bridge
