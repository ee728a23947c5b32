#pragma once

#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/node_settings.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/rate_limit.hpp"
#include "ball_collision_sim/ros/reconfigure_server.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <actionlib/server/simple_action_server.h>
#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/ApplyImpulse.h>
#include <ball_collision_sim/Strike.h>
#include <ball_collision_sim/GetState.h>
#include <ball_collision_sim/LoadScene.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/SetBallState.h>
#include <ball_collision_sim/SimulatorConfig.h>
#include <ball_collision_sim/Step.h>
#include <ball_collision_sim/StepAction.h>
#include <geometry_msgs/PointStamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/MarkerArray.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ball_collision_sim::bridge
{
class InteractivePlay;
struct PlayMove;
struct PlayStrike;

/// The simulator on ROS: steps the core on a wall-clock timer with the scene's fixed dt,
/// publishes markers, tf, ball states, collisions, lost balls and /clock (every stamp is
/// simulated time), and takes services to read, edit, pause, step, reset and reload the
/// world; its run-time settings change live through dynamic_reconfigure.
///
/// Threads: every callback runs on the global queue (ros::spin) but two: the step
/// service, on a queue of its own, and the step action, on actionlib's thread. Both
/// step in short chunks under the one lock and give it up between them, so that the
/// other services answer while a long step runs.
class SimulatorNode
{
public:
  /// Reads the scene from the private namespace; throws yaml::SceneError when it is bad.
  SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~SimulatorNode();
  SimulatorNode(const SimulatorNode&) = delete;
  SimulatorNode& operator=(const SimulatorNode&) = delete;

private:
  SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh, yaml::SceneFile file);
  using Lock = std::unique_lock<std::mutex>;
  /// The lock, taken ahead of a running step loop (which waits while anyone asks).
  Lock lock();

  // ---- wiring and publishing (simulator_node.cpp) ----
  void advertise();
  void onTimer(const ros::WallTimerEvent& event);
  void onStatus(const ros::WallTimerEvent& event);
  /// One physics step and what is published every step; lost balls are taken out.
  void stepOnce();
  void removeLostBalls();
  /// Markers and tf when their wall-clock rates allow, or (force) now.
  void publishView(bool force);
  /// After a change the clients must see: ball states (unless those of the world as it
  /// is were sent already), tf and markers now.
  void publishPresent();
  /// After an edit of the balls: their states, tf and markers now.
  void publishEdit();
  /// After a push or strike of ball `id`: its change of motion kind from `before`, if any,
  /// on motion_transitions at the world's time.
  void publishPushTransition(int id, core::MotionKind before);
  /// The motion kind of ball `id`, or kStationary without one.
  core::MotionKind kindOf(int id) const;
  void publishStatic();
  void publishBalls(const ros::Time& stamp);
  /// tf of every ball, but none twice at one stamp (tf2 drops a repeated stamp with a
  /// warning): a second call at the same time sends only frames not yet sent at it.
  void publishTransforms(const ros::Time& stamp);
  void publishStates(const ros::Time& stamp);
  /// Takes run-time settings in: timer periods, rates, colours (frame_prefix and
  /// publish_clock stay as they are).
  void applySettings(const NodeSettings& settings);
  /// Takes frame_prefix and publish_clock in: the /clock publisher is made or dropped.
  void applyWiring(const ResolvedSettings& settings);
  void startStatusTimer();
  /// Restarts the wall-clock anchor that real time is kept against.
  void anchorClock();
  /// The stepping timer's period for the world's dt and the real-time factor, from now.
  void restartTimer();
  /// After the world was rebuilt (reset, load_scene): markers cleared and sent anew.
  void redraw();
  std::string roomForABall() const;

  // ---- services (node_services.cpp) ----
  bool onAddBall(AddBall::Request& req, AddBall::Response& res);
  bool onAddWall(AddWall::Request& req, AddWall::Response& res);
  bool onRemoveBall(RemoveObject::Request& req, RemoveObject::Response& res);
  bool onRemoveWall(RemoveObject::Request& req, RemoveObject::Response& res);
  bool onSetBallState(SetBallState::Request& req, SetBallState::Response& res);
  bool onApplyImpulse(ApplyImpulse::Request& req, ApplyImpulse::Response& res);
  bool onStrike(Strike::Request& req, Strike::Response& res);
  /// The strike service's work, under the lock: the strike, its motion transition, the edit.
  void strike(const Strike::Request& req, Strike::Response& res);
  bool onGetState(GetState::Request& req, GetState::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onLoadScene(LoadScene::Request& req, LoadScene::Response& res);
  bool onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  void onClickedPoint(const geometry_msgs::PointStamped& msg);
  void onReconfigure(const SimulatorConfig& config);
  void onMarkerSubscriber(const ros::SingleSubscriberPublisher& subscriber);
  void onStatesSubscriber(const ros::SingleSubscriberPublisher& subscriber);
  void onTfSubscriber(const ros::SingleSubscriberPublisher& subscriber);
  void onClockSubscriber(const ros::SingleSubscriberPublisher& subscriber);

  // ---- playing in rviz: interactive markers (node_play.cpp) ----
  void onPlayFeedback(const visualization_msgs::InteractiveMarkerFeedback& feedback);
  void playMove(const PlayMove& move);
  void playStrike(const PlayStrike& shot);
  /// The interactive markers as the world is now.
  void syncPlay();

  // ---- long steps (step_runner.cpp) ----
  /// How a run of steps ended.
  struct StepOutcome
  {
    bool success = false;
    std::string message;
    std::uint32_t done = 0;
    double time = 0.0;  ///< [s]
  };
  /// Steps `steps` times in chunks, calling `progress` (without the lock) between them;
  /// stops early when `cancelled` says so, ~cancel_step is called, the world is
  /// resumed, reset or replaced, or ROS shuts down.
  StepOutcome runSteps(std::uint32_t steps, const std::function<void(std::uint32_t, double)>& progress,
                       const std::function<bool()>& cancelled);
  bool onStep(Step::Request& req, Step::Response& res);
  void onStepGoal(const StepGoalConstPtr& goal);
  bool onCancelStep(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  // everything below is guarded by mutex_
  std::mutex mutex_;
  std::atomic<int> waiting_{0};  ///< callbacks waiting for the lock

  core::World world_;
  ResolvedSettings settings_;
  std::string frame_id_;
  BallColoring coloring_;
  bool paused_ = false;
  std::uint64_t state_every_ = 1;  ///< publish ball_states every this many steps
  std::uint64_t lost_total_ = 0;   ///< balls removed for leaving the world since it was last built
  std::string scene_source_;       ///< where the world's scene came from, for messages

  // a run of steps
  bool running_ = false;
  bool cancel_run_ = false;
  std::uint32_t run_done_ = 0;
  std::uint32_t run_total_ = 0;

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  /// the step service's queue: before the services, so that it outlives them
  ros::CallbackQueue step_queue_;
  ros::Publisher markers_pub_;
  ros::Publisher states_pub_;
  ros::Publisher collisions_pub_;
  ros::Publisher lost_pub_;
  ros::Publisher pocketed_pub_;
  ros::Publisher transitions_pub_;
  ros::Publisher clock_pub_;
  ros::Publisher tf_pub_;
  ros::Publisher scene_pub_;
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
  bool states_sent_ = false;      ///< ball_states of the world as it is now went out
  double tf_stamp_ = -1.0;        ///< simulated time of the last tf sent [s]
  std::vector<int> tf_sent_;      ///< ids whose frames were sent at tf_stamp_ (sorted)
  std::vector<int> shown_balls_;  ///< ball ids drawn last time, to delete the removed
  int shown_lists_ = 0;           ///< sphere lists drawn last time (many balls)
  CollisionFlashes flashes_;      ///< collisions since the last ball markers
  std::unique_ptr<InteractivePlay> play_;  ///< the balls and a cue as interactive markers (~play)

  // threads other than the global queue's, started last and stopped first
  std::unique_ptr<ros::AsyncSpinner> step_spinner_;
  std::unique_ptr<actionlib::SimpleActionServer<StepAction>> step_action_;
  std::unique_ptr<ReconfigureServer> reconfigure_;
};
}  // namespace ball_collision_sim::bridge
