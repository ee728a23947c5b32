// The node's wiring and what it publishes; its services are in node_services.cpp and
// its long steps in step_runner.cpp.
#include "ball_collision_sim/ros/simulator_node.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/interactive_play.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/requests.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <ball_collision_sim/CollisionEvent.h>
#include <ball_collision_sim/LostBall.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <utility>
#include <cmath>

namespace ball_collision_sim::bridge
{
namespace
{
/// Wall time one timer callback may spend stepping before it lets services in [s].
constexpr double kStepBudget = 0.05;

/// The wake-up period of the stepping timer for a real-time factor [s]: a step's worth
/// of wall time, between 1 ms and kStepBudget.
double timerPeriod(double dt, double factor)
{
  return factor > 0 ? std::clamp(dt / factor, 1e-3, kStepBudget) : 1e-3;
}

}  // namespace

SimulatorNode::SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh) : SimulatorNode(nh, pnh, loadSceneParams(pnh))
{
}

SimulatorNode::SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh, yaml::SceneFile file)
    : world_(file.scene, std::move(file.checked), stepSettingsOf(file.node))
    , settings_(resolve(file.node, nh.getNamespace()))
    , frame_id_(world_.scene().frame_id)
    , coloring_(ballColoring(world_, settings_.node))
    , paused_(settings_.node.start_paused)
    , scene_source_("the parameter server (" + pnh.getNamespace() + ")")
    , nh_(nh)
    , pnh_(pnh)
{
  state_every_ = stepsPer(settings_.node.state_rate, world_.dt());
  // What the node runs, every default spelled out, back where the scene came from.
  writeSceneParams(pnh_, world_.scene(), settings_.node);
  advertise();
  play_ = std::make_unique<InteractivePlay>(
      pnh_.resolveName("play"), frame_id_,
      [this](const visualization_msgs::InteractiveMarkerFeedback& feedback) { onPlayFeedback(feedback); });

  anchorClock();
  // The timer only wakes the loop; how many steps are due comes from the wall clock,
  // and each step is the scene's fixed dt whatever the timer's jitter.
  timer_ = nh_.createWallTimer(ros::WallDuration(timerPeriod(world_.dt(), settings_.node.real_time_factor)),
                               &SimulatorNode::onTimer, this);
  startStatusTimer();
  publishStatic();
  publishPresent();

  // The settings in use are the first configuration.
  reconfigure_ = std::make_unique<ReconfigureServer>(pnh_, toConfig(settings_.node),
                                                     [this](const SimulatorConfig& config) { onReconfigure(config); });

  ROS_INFO("ball_sim: %zu balls, %zu walls, dt = %s s, real time factor %s%s; tf frames %sball_<id>%s",
           world_.balls().size(), world_.walls().size(), core::formatNumber(world_.dt()).c_str(),
           core::formatNumber(settings_.node.real_time_factor).c_str(),
           paused_ ? ", paused" : "", settings_.frame_prefix.c_str(),
           settings_.publish_clock ? ", publishing /clock" : ", not publishing /clock (publish_clock is false)");

  // Two threads: a second step call is answered (refused) while the first runs.
  ros::NodeHandle step_nh(pnh_);
  step_nh.setCallbackQueue(&step_queue_);
  services_.push_back(step_nh.advertiseService("step", &SimulatorNode::onStep, this));
  step_spinner_ = std::make_unique<ros::AsyncSpinner>(2, &step_queue_);
  step_spinner_->start();
  step_action_ = std::make_unique<actionlib::SimpleActionServer<StepAction>>(
      pnh_, "step", [this](const StepGoalConstPtr& goal) { onStepGoal(goal); }, false);
  step_action_->start();
}

SimulatorNode::~SimulatorNode()
{
  {
    const Lock guard(mutex_);
    cancel_run_ = true;
  }
  if (step_action_)
    step_action_->shutdown();
  if (step_spinner_)
    step_spinner_->stop();
}

SimulatorNode::Lock SimulatorNode::lock()
{
  ++waiting_;
  Lock guard(mutex_);
  --waiting_;
  return guard;
}

void SimulatorNode::advertise()
{
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>(
      "markers", 10, [this](const ros::SingleSubscriberPublisher& s) { onMarkerSubscriber(s); });
  states_pub_ = pnh_.advertise<BallStateArray>(
      "ball_states", 100, [this](const ros::SingleSubscriberPublisher& s) { onStatesSubscriber(s); });
  collisions_pub_ = pnh_.advertise<ball_collision_sim::CollisionEvent>("collisions", 1000);
  lost_pub_ = pnh_.advertise<ball_collision_sim::LostBall>("lost_balls", 100);
  pocketed_pub_ = pnh_.advertise<ball_collision_sim::PocketedBall>("pocketed", 100);
  transitions_pub_ = pnh_.advertise<ball_collision_sim::MotionTransition>("motion_transitions", 1000);
  tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100,
                                               [this](const ros::SingleSubscriberPublisher& s) { onTfSubscriber(s); });
  applyWiring(settings_);
  scene_pub_ = pnh_.advertise<std_msgs::String>("scene", 1, true);
  std_msgs::String scene;
  scene.data = yaml::writeScene(world_.scene(), settings_.node);
  scene_pub_.publish(scene);

  services_.push_back(pnh_.advertiseService("get_state", &SimulatorNode::onGetState, this));
  services_.push_back(pnh_.advertiseService("add_ball", &SimulatorNode::onAddBall, this));
  services_.push_back(pnh_.advertiseService("add_wall", &SimulatorNode::onAddWall, this));
  services_.push_back(pnh_.advertiseService("remove_ball", &SimulatorNode::onRemoveBall, this));
  services_.push_back(pnh_.advertiseService("remove_wall", &SimulatorNode::onRemoveWall, this));
  services_.push_back(pnh_.advertiseService("set_ball_state", &SimulatorNode::onSetBallState, this));
  services_.push_back(pnh_.advertiseService("apply_impulse", &SimulatorNode::onApplyImpulse, this));
  services_.push_back(pnh_.advertiseService("strike", &SimulatorNode::onStrike, this));
  services_.push_back(pnh_.advertiseService("reset", &SimulatorNode::onReset, this));
  services_.push_back(pnh_.advertiseService("load_scene", &SimulatorNode::onLoadScene, this));
  services_.push_back(pnh_.advertiseService("pause", &SimulatorNode::onPause, this));
  services_.push_back(pnh_.advertiseService("cancel_step", &SimulatorNode::onCancelStep, this));
  // relative: in a namespace, rviz's clicks reach the simulator of that namespace only
  clicked_sub_ = nh_.subscribe("clicked_point", 10, &SimulatorNode::onClickedPoint, this);
}

void SimulatorNode::anchorClock()
{
  anchor_wall_ = ros::WallTime::now();
  anchor_steps_ = world_.stats().steps;
}

void SimulatorNode::restartTimer()
{
  timer_.setPeriod(ros::WallDuration(timerPeriod(world_.dt(), settings_.node.real_time_factor)));
  anchorClock();
}

void SimulatorNode::onTimer(const ros::WallTimerEvent&)
{
  const Lock guard = lock();
  if (paused_ || running_)
    return;
  const ros::WallTime start = ros::WallTime::now();
  const double factor = settings_.node.real_time_factor;
  if (factor > 0)
  {
    const double due_time = (start - anchor_wall_).toSec() * factor;
    // clamped: a huge factor or a tiny dt must not overflow the count (it then lags and says so)
    const double due_steps = std::min(std::floor(due_time / world_.dt() + 1e-9), 1e15);
    const auto due = anchor_steps_ + static_cast<std::uint64_t>(due_steps);
    // More than a second of wall time behind: give up on catching up and say so.
    const double behind = static_cast<double>(due - std::min(due, world_.stats().steps)) * world_.dt() / factor;
    if (behind > 1.0)
    {
      ROS_WARN_THROTTLE(5.0, "ball_sim: %.1f s behind real time; the scene is too heavy for real time factor %s",
                        behind, core::formatNumber(factor).c_str());
      anchorClock();
    }
    // (the view after each step where it is due: a tick that runs several steps to catch
    // up still draws at the marker and tf rates)
    while (world_.stats().steps < due && (ros::WallTime::now() - start).toSec() < kStepBudget)
    {
      stepOnce();
      publishView(false);
    }
  }
  else
  {
    do
    {
      stepOnce();
      publishView(false);
    } while ((ros::WallTime::now() - start).toSec() < kStepBudget);
  }
  publishView(false);
}

void SimulatorNode::onStatus(const ros::WallTimerEvent&)
{
  const Lock guard = lock();
  const ros::WallTime now = ros::WallTime::now();
  const double wall = (now - status_wall_).toSec();
  const double simulated = world_.time() - status_time_;
  // events count since the last reset; after one, start over
  const std::uint64_t events = world_.stats().events >= status_events_ ? world_.stats().events - status_events_ : 0;
  const std::string lost = lost_total_ > 0 ? " | " + std::to_string(lost_total_) + " lost" : "";
  const std::string stepping = running_ ? " | stepping " + std::to_string(run_done_) + " of " + std::to_string(run_total_) : "";
  // (the simulated time as it is; the rates measured on the wall clock, to the digits they have)
  ROS_INFO("t = %s s | real-time factor %.2f | %zu balls | %.1f collisions/s%s%s%s",
           core::formatNumber(world_.time()).c_str(),
           wall > 0 ? std::max(0.0, simulated) / wall : 0.0, world_.balls().size(),
           simulated > 0 ? static_cast<double>(events) / simulated : 0.0, lost.c_str(), stepping.c_str(),
           paused_ && !running_ ? " | paused" : "");
  status_wall_ = now;
  status_time_ = world_.time();
  status_events_ = world_.stats().events;
}

void SimulatorNode::startStatusTimer()
{
  status_timer_.stop();
  if (settings_.node.status_period > 0)
  {
    status_wall_ = ros::WallTime::now();
    status_time_ = world_.time();
    status_events_ = world_.stats().events;
    status_timer_ =
        nh_.createWallTimer(ros::WallDuration(settings_.node.status_period), &SimulatorNode::onStatus, this);
  }
}

void SimulatorNode::stepOnce()
{
  world_.step();
  states_sent_ = false;
  const ros::Time stamp(world_.time());
  if (settings_.publish_clock)
    clock_pub_.publish(clockMessage(stamp));
  if (settings_.node.publish_collisions && collisions_pub_.getNumSubscribers() > 0)
    for (const core::CollisionEvent& event : world_.lastEvents())
      collisions_pub_.publish(toMsg(event, frame_id_));
  if (transitions_pub_.getNumSubscribers() > 0)
    for (const core::MotionTransition& transition : world_.lastTransitions())
      transitions_pub_.publish(toMsg(transition, frame_id_));
  for (const core::PocketedBall& dropped : world_.lastPocketed())
  {
    ROS_INFO("ball_sim: ball %d dropped into pocket %d at t = %s s", dropped.ball.id, dropped.pocket,
             core::formatNumber(dropped.time).c_str());
    pocketed_pub_.publish(pocketedMessage(dropped, frame_id_));
  }
  removeLostBalls();
  if (world_.stats().steps % state_every_ == 0 && states_pub_.getNumSubscribers() > 0)
    publishStates(stamp);
  if (settings_.node.collision_flashes && settings_.node.marker_rate > 0)
    flashes_.add(world_.lastEvents());
}

void SimulatorNode::removeLostBalls()
{
  const std::vector<core::LostBall> lost = world_.removeLostBalls();
  for (const core::LostBall& gone : lost)
  {
    const core::Vec3& p = gone.ball.position;
    ROS_WARN("ball_sim: ball %d %s at (%s, %s, %s) m, t = %s s; removed from the world", gone.ball.id,
             gone.reason.c_str(), core::formatNumber(p.x()).c_str(), core::formatNumber(p.y()).c_str(),
             core::formatNumber(p.z()).c_str(), core::formatNumber(world_.time()).c_str());
    lost_pub_.publish(lostBallMessage(gone, frame_id_, world_.time()));
  }
  lost_total_ += lost.size();
}

void SimulatorNode::publishStates(const ros::Time& stamp)
{
  states_pub_.publish(statesMessage(world_, frame_id_, stamp));
  states_sent_ = true;
}

void SimulatorNode::publishView(bool force)
{
  const double now = ros::WallTime::now().toSec();
  const ros::Time stamp(world_.time());
  if (markers_due_.due(settings_.node.marker_rate, now, force))
  {
    publishBalls(stamp);
    syncPlay();
  }
  if (tf_due_.due(settings_.node.tf_rate, now, force))
    publishTransforms(stamp);
}

void SimulatorNode::publishPresent()
{
  if (!states_sent_)
    publishStates(ros::Time(world_.time()));
  publishView(true);
}

void SimulatorNode::publishEdit()
{
  states_sent_ = false;
  publishPresent();
}

void SimulatorNode::publishBalls(const ros::Time& stamp)
{
  if (markers_pub_.getNumSubscribers() == 0)
  {
    flashes_.clear();
    return;
  }
  visualization_msgs::MarkerArray msg;
  const auto threshold = static_cast<std::size_t>(settings_.node.marker_list_threshold);
  const bool lists = world_.balls().size() > threshold;
  std::vector<int> ids;
  if (!lists)
  {
    ids.reserve(world_.balls().size());
    for (const core::Ball& ball : world_.balls())
      ids.push_back(ball.id);
  }
  // Delete what is no longer drawn: removed balls (ids are sorted: balls keep their order
  // and new ones come last), and the markers of the other way of drawing.
  for (const int id : shown_balls_)
    if (!std::binary_search(ids.begin(), ids.end(), id))
      msg.markers.push_back(deleteMarker(kBallsNs, id, frame_id_));
  const visualization_msgs::MarkerArray balls = ballMarkers(world_, frame_id_, stamp, threshold, coloring_);
  for (int k = lists ? static_cast<int>(balls.markers.size()) : 0; k < shown_lists_; ++k)
    msg.markers.push_back(deleteMarker(kBallListsNs, k, frame_id_));
  msg.markers.insert(msg.markers.end(), balls.markers.begin(), balls.markers.end());
  const std::vector<visualization_msgs::Marker> flashes = flashes_.take(frame_id_, stamp);
  msg.markers.insert(msg.markers.end(), flashes.begin(), flashes.end());
  shown_balls_ = std::move(ids);
  shown_lists_ = lists ? static_cast<int>(balls.markers.size()) : 0;
  markers_pub_.publish(msg);
}

void SimulatorNode::publishTransforms(const ros::Time& stamp)
{
  tf2_msgs::TFMessage msg = transformsMessage(world_, frame_id_, stamp,
                                              static_cast<std::size_t>(settings_.node.tf_max_balls),
                                              settings_.frame_prefix);
  const bool again = stamp.toSec() == tf_stamp_;
  std::vector<int> sent;
  sent.reserve(msg.transforms.size());
  std::size_t kept = 0;
  for (std::size_t k = 0; k < msg.transforms.size(); ++k)
  {
    const int id = world_.balls()[k].id;
    sent.push_back(id);
    if (again && std::binary_search(tf_sent_.begin(), tf_sent_.end(), id))
      continue;
    msg.transforms[kept++] = msg.transforms[k];
  }
  msg.transforms.resize(kept);
  if (again)
  {
    sent.insert(sent.end(), tf_sent_.begin(), tf_sent_.end());
    std::sort(sent.begin(), sent.end());
    sent.erase(std::unique(sent.begin(), sent.end()), sent.end());
  }
  tf_sent_ = std::move(sent);
  tf_stamp_ = stamp.toSec();
  if (!msg.transforms.empty())
    tf_pub_.publish(msg);
}

void SimulatorNode::publishStatic()
{
  const visualization_msgs::MarkerArray msg = staticMarkers(world_, frame_id_);
  if (!msg.markers.empty())
    markers_pub_.publish(msg);
}

void SimulatorNode::redraw()
{
  states_sent_ = false;
  visualization_msgs::MarkerArray clear;
  clear.markers.push_back(deleteAllMarker(frame_id_));
  markers_pub_.publish(clear);
  shown_balls_.clear();
  shown_lists_ = 0;
  flashes_.clear();
  play_->restart(frame_id_);
  publishStatic();
  if (settings_.publish_clock)
    clock_pub_.publish(clockMessage(ros::Time(world_.time())));
  publishPresent();
}

void SimulatorNode::onMarkerSubscriber(const ros::SingleSubscriberPublisher& subscriber)
{
  const Lock guard = lock();
  // A newcomer gets the floor and walls, which are otherwise sent only when they change.
  visualization_msgs::MarkerArray msg = staticMarkers(world_, frame_id_);
  const visualization_msgs::MarkerArray balls =
      ballMarkers(world_, frame_id_, ros::Time(world_.time()),
                  static_cast<std::size_t>(settings_.node.marker_list_threshold), coloring_);
  msg.markers.insert(msg.markers.end(), balls.markers.begin(), balls.markers.end());
  subscriber.publish(msg);
}

// A late subscriber sees the present at once, paused or not.
void SimulatorNode::onStatesSubscriber(const ros::SingleSubscriberPublisher& subscriber)
{
  const Lock guard = lock();
  subscriber.publish(statesMessage(world_, frame_id_, ros::Time(world_.time())));
}

void SimulatorNode::onTfSubscriber(const ros::SingleSubscriberPublisher& subscriber)
{
  const Lock guard = lock();
  // Only while nothing moves: a running world sends tf within 1 / tf_rate anyway, and the
  // newcomer may already have had this stamp from it (tf2 warns of a repeated stamp).
  if (!paused_ || running_)
    return;
  const tf2_msgs::TFMessage msg =
      transformsMessage(world_, frame_id_, ros::Time(world_.time()),
                        static_cast<std::size_t>(settings_.node.tf_max_balls), settings_.frame_prefix);
  if (!msg.transforms.empty())
    subscriber.publish(msg);
}

void SimulatorNode::onClockSubscriber(const ros::SingleSubscriberPublisher& subscriber)
{
  const Lock guard = lock();
  subscriber.publish(clockMessage(ros::Time(world_.time())));
}

void SimulatorNode::applyWiring(const ResolvedSettings& settings)
{
  if (settings.frame_prefix != settings_.frame_prefix)
    tf_sent_.clear();  // frames of other names: none of them sent yet
  settings_.frame_prefix = settings.frame_prefix;
  settings_.node.frame_prefix = settings.frame_prefix;
  if (settings.publish_clock && !clock_pub_)
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>(
        "/clock", 10, [this](const ros::SingleSubscriberPublisher& s) { onClockSubscriber(s); });
  if (!settings.publish_clock)
    clock_pub_.shutdown();
  settings_.publish_clock = settings.publish_clock;
  settings_.node.publish_clock = settings.publish_clock;
}

void SimulatorNode::applySettings(const NodeSettings& node)
{
  const NodeSettings old = settings_.node;
  settings_.node = node;
  settings_.node.frame_prefix = settings_.frame_prefix;
  settings_.node.publish_clock = settings_.publish_clock;
  if (node.real_time_factor != old.real_time_factor)
    restartTimer();
  if (node.status_period != old.status_period)
    startStatusTimer();
  state_every_ = stepsPer(node.state_rate, world_.dt());
  if (node.ball_color != old.ball_color || node.speed_color_max != old.speed_color_max)
    coloring_ = ballColoring(world_, node);
  if (!node.collision_flashes)
    flashes_.clear();
  if (node.play_max_balls != old.play_max_balls)
    syncPlay();
}

std::string SimulatorNode::roomForABall() const
{
  return bridge::roomForABall(world_, settings_.node.max_balls);
}
}  // namespace ball_collision_sim::bridge
