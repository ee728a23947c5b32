#include "ball_collision_sim/ros/simulator_node.hpp"

#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/requests.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <ball_collision_sim/CollisionEvent.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::bridge
{
namespace
{
/// Wall time one timer callback may spend stepping before it lets services in [s].
constexpr double kStepBudget = 0.05;
}  // namespace

SimulatorNode::SimulatorNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : world_(loadSceneParams(pnh, &scene_yaml_))
    , settings_(world_.scene().node)
    , frame_id_(world_.scene().frame_id)
    , coloring_(ballColoring(world_))
    , paused_(settings_.start_paused)
    , nh_(nh)
    , pnh_(pnh)
{
  const double dt = world_.dt();
  state_every_ = stepsPer(settings_.state_rate, dt);

  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>(
      "markers", 10, [this](const ros::SingleSubscriberPublisher& s) { onMarkerSubscriber(s); });
  states_pub_ = pnh_.advertise<BallStateArray>("ball_states", 100);
  collisions_pub_ = pnh_.advertise<ball_collision_sim::CollisionEvent>("collisions", 1000);
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  scene_pub_ = pnh_.advertise<std_msgs::String>("scene", 1, true);
  std_msgs::String scene;
  scene.data = scene_yaml_;
  scene_pub_.publish(scene);

  services_.push_back(pnh_.advertiseService("add_ball", &SimulatorNode::onAddBall, this));
  services_.push_back(pnh_.advertiseService("add_wall", &SimulatorNode::onAddWall, this));
  services_.push_back(pnh_.advertiseService("remove_ball", &SimulatorNode::onRemoveBall, this));
  services_.push_back(pnh_.advertiseService("remove_wall", &SimulatorNode::onRemoveWall, this));
  services_.push_back(pnh_.advertiseService("reset", &SimulatorNode::onReset, this));
  services_.push_back(pnh_.advertiseService("pause", &SimulatorNode::onPause, this));
  services_.push_back(pnh_.advertiseService("step", &SimulatorNode::onStep, this));
  clicked_sub_ = nh_.subscribe("/clicked_point", 10, &SimulatorNode::onClickedPoint, this);

  clock_pub_.publish(clockMessage(ros::Time(world_.time())));
  anchorClock();
  // The timer only wakes the loop; how many steps are due comes from the wall clock,
  // and each step is the scene's fixed dt whatever the timer's jitter.
  const double factor = settings_.real_time_factor;
  const double period = factor > 0 ? std::clamp(dt / factor, 1e-3, 0.05) : 1e-3;
  timer_ = nh_.createWallTimer(ros::WallDuration(period), &SimulatorNode::onTimer, this);
  if (settings_.status_period > 0)
  {
    status_wall_ = ros::WallTime::now();
    status_timer_ =
        nh_.createWallTimer(ros::WallDuration(settings_.status_period), &SimulatorNode::onStatus, this);
  }
  ROS_INFO("ball_sim: %zu balls, %zu walls, dt = %g s, real time factor %g%s", world_.balls().size(),
           world_.walls().size(), dt, factor, paused_ ? ", paused" : "");
}

void SimulatorNode::anchorClock()
{
  anchor_wall_ = ros::WallTime::now();
  anchor_steps_ = world_.stats().steps;
}

void SimulatorNode::onTimer(const ros::WallTimerEvent&)
{
  if (paused_)
    return;
  const ros::WallTime start = ros::WallTime::now();
  const double factor = settings_.real_time_factor;
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
      ROS_WARN_THROTTLE(5.0, "ball_sim: %.1f s behind real time; the scene is too heavy for real time factor %g",
                        behind, factor);
      anchorClock();
    }
    while (world_.stats().steps < due && (ros::WallTime::now() - start).toSec() < kStepBudget)
      stepOnce();
  }
  else
  {
    do
      stepOnce();
    while ((ros::WallTime::now() - start).toSec() < kStepBudget);
  }
  publishView(false);
}

void SimulatorNode::onStatus(const ros::WallTimerEvent&)
{
  const ros::WallTime now = ros::WallTime::now();
  const double wall = (now - status_wall_).toSec();
  const double simulated = world_.time() - status_time_;
  // events count since the last reset; after one, start over
  const std::uint64_t events = world_.stats().events >= status_events_ ? world_.stats().events - status_events_ : 0;
  ROS_INFO("t = %.2f s | real-time factor %.2f | %zu balls | %.1f collisions/s%s", world_.time(),
           wall > 0 ? std::max(0.0, simulated) / wall : 0.0, world_.balls().size(),
           simulated > 0 ? static_cast<double>(events) / simulated : 0.0, paused_ ? " | paused" : "");
  status_wall_ = now;
  status_time_ = world_.time();
  status_events_ = world_.stats().events;
}

void SimulatorNode::stepOnce()
{
  world_.step();
  const ros::Time stamp(world_.time());
  clock_pub_.publish(clockMessage(stamp));
  if (settings_.publish_collisions && collisions_pub_.getNumSubscribers() > 0)
    for (const core::CollisionEvent& event : world_.lastEvents())
      collisions_pub_.publish(toMsg(event, frame_id_));
  if (world_.stats().steps % state_every_ == 0 && states_pub_.getNumSubscribers() > 0)
    publishStates(stamp);
  if (settings_.collision_flashes && settings_.marker_rate > 0)
    flashes_.add(world_.lastEvents());
}

void SimulatorNode::publishStates(const ros::Time& stamp)
{
  states_pub_.publish(statesMessage(world_, frame_id_, stamp));
}

void SimulatorNode::publishView(bool force)
{
  const double now = ros::WallTime::now().toSec();
  const ros::Time stamp(world_.time());
  if (markers_due_.due(settings_.marker_rate, now, force))
    publishBalls(stamp);
  if (tf_due_.due(settings_.tf_rate, now, force))
    publishTransforms(stamp);
}

void SimulatorNode::publishBalls(const ros::Time& stamp)
{
  if (markers_pub_.getNumSubscribers() == 0)
  {
    flashes_.clear();
    return;
  }
  visualization_msgs::MarkerArray msg;
  const auto threshold = static_cast<std::size_t>(settings_.marker_list_threshold);
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
  const tf2_msgs::TFMessage msg =
      transformsMessage(world_, frame_id_, stamp, static_cast<std::size_t>(settings_.tf_max_balls));
  if (!msg.transforms.empty())
    tf_broadcaster_.sendTransform(msg.transforms);
}

void SimulatorNode::publishStatic()
{
  const visualization_msgs::MarkerArray msg = staticMarkers(world_, frame_id_);
  if (!msg.markers.empty())
    markers_pub_.publish(msg);
}

void SimulatorNode::onMarkerSubscriber(const ros::SingleSubscriberPublisher& subscriber)
{
  // A newcomer gets the floor and walls, which are otherwise sent only when they change.
  visualization_msgs::MarkerArray msg = staticMarkers(world_, frame_id_);
  const visualization_msgs::MarkerArray balls =
      ballMarkers(world_, frame_id_, ros::Time(world_.time()),
                  static_cast<std::size_t>(settings_.marker_list_threshold), coloring_);
  msg.markers.insert(msg.markers.end(), balls.markers.begin(), balls.markers.end());
  subscriber.publish(msg);
}

// ---- services ------------------------------------------------------------------------

std::string SimulatorNode::roomForABall() const
{
  return bridge::roomForABall(world_, settings_.max_balls);
}

bool SimulatorNode::onAddBall(AddBall::Request& req, AddBall::Response& res)
{
  answerAddBall(world_, settings_.max_balls, req, res);
  if (res.success)
    publishView(true);
  return true;
}

bool SimulatorNode::onAddWall(AddWall::Request& req, AddWall::Response& res)
{
  answerAddWall(world_, req, res);
  if (res.success)
    publishStatic();
  return true;
}

bool SimulatorNode::onRemoveBall(RemoveObject::Request& req, RemoveObject::Response& res)
{
  answerRemoveBall(world_, req, res);
  if (res.success)
    publishView(true);
  return true;
}

bool SimulatorNode::onRemoveWall(RemoveObject::Request& req, RemoveObject::Response& res)
{
  answerRemoveWall(world_, req, res);
  if (res.success)
  {
    visualization_msgs::MarkerArray msg;
    msg.markers.push_back(deleteMarker(kWallsNs, req.id, frame_id_));
    markers_pub_.publish(msg);
  }
  return true;
}

bool SimulatorNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  world_.reset();
  anchorClock();
  visualization_msgs::MarkerArray clear;
  clear.markers.push_back(deleteAllMarker(frame_id_));
  markers_pub_.publish(clear);
  shown_balls_.clear();
  shown_lists_ = 0;
  flashes_.clear();
  publishStatic();
  const ros::Time start(world_.time());
  clock_pub_.publish(clockMessage(start));
  publishView(true);
  if (states_pub_.getNumSubscribers() > 0)
    publishStates(start);
  res.success = true;
  res.message = "back to the scene as loaded: " + std::to_string(world_.balls().size()) + " balls, " +
                std::to_string(world_.walls().size()) + " walls";
  return true;
}

bool SimulatorNode::onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
{
  if (paused_ && !req.data)
    anchorClock();  // resume from now, without catching up the paused time
  paused_ = req.data;
  res.success = true;
  res.message = (paused_ ? "paused at t = " : "running from t = ") + std::to_string(world_.time()) + " s";
  return true;
}

bool SimulatorNode::onStep(Step::Request& req, Step::Response& res)
{
  if (!acceptStep(world_, paused_, req, res))
    return true;
  for (std::uint32_t k = 0; k < req.steps; ++k)
    stepOnce();
  publishView(true);
  res.success = true;
  res.time = world_.time();
  res.message = "at t = " + std::to_string(res.time) + " s";
  return true;
}

void SimulatorNode::onClickedPoint(const geometry_msgs::PointStamped& msg)
{
  if (!msg.header.frame_id.empty() && msg.header.frame_id != frame_id_)
  {
    ROS_WARN("ball_sim: clicked point in frame '%s' ignored: set rviz's fixed frame to '%s'",
             msg.header.frame_id.c_str(), frame_id_.c_str());
    return;
  }
  core::BallDef def;
  def.position = toVec3(msg.point);
  def.radius = settings_.click_radius;
  def.mass = settings_.click_mass;
  // The click lands on the drawn floor (or, without one, on the grid): lift the centre
  // by a radius; with a floor the core then puts it exactly on the surface.
  const double g = world_.gravity().norm();
  def.position += def.radius * (g > 0 ? core::Vec3(-world_.gravity() / g) : core::Vec3::UnitZ());
  const std::string full = roomForABall();
  const core::AddResult result = full.empty() ? world_.addBall(def) : core::AddResult{false, -1, full};
  if (!result.ok)
  {
    ROS_WARN("ball_sim: no ball added at the clicked point: %s", result.error.c_str());
    return;
  }
  ROS_INFO("ball_sim: added ball %d at the clicked point", result.id);
  publishView(true);
}
}  // namespace ball_collision_sim::bridge
