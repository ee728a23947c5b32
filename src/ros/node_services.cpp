// The node's services and subscriptions: each takes the lock, answers through
// requests.hpp (which does the checking), and publishes what changed.
#include "ball_collision_sim/ros/simulator_node.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/requests.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <std_msgs/String.h>

#include <algorithm>
#include <optional>
#include <utility>

namespace ball_collision_sim::bridge
{
bool SimulatorNode::onGetState(GetState::Request&, GetState::Response& res)
{
  const Lock guard = lock();
  answerGetState(world_, paused_, settings_.frame_prefix, res);
  return true;
}

bool SimulatorNode::onAddBall(AddBall::Request& req, AddBall::Response& res)
{
  const Lock guard = lock();
  answerAddBall(world_, settings_.node.max_balls, req, res);
  if (res.success)
    publishEdit();
  return true;
}

bool SimulatorNode::onAddWall(AddWall::Request& req, AddWall::Response& res)
{
  const Lock guard = lock();
  answerAddWall(world_, req, res);
  if (res.success)
    publishStatic();
  return true;
}

bool SimulatorNode::onRemoveBall(RemoveObject::Request& req, RemoveObject::Response& res)
{
  const Lock guard = lock();
  answerRemoveBall(world_, req, res);
  if (res.success)
    publishEdit();
  return true;
}

bool SimulatorNode::onRemoveWall(RemoveObject::Request& req, RemoveObject::Response& res)
{
  const Lock guard = lock();
  answerRemoveWall(world_, req, res);
  if (res.success)
  {
    visualization_msgs::MarkerArray msg;
    msg.markers.push_back(deleteMarker(kWallsNs, req.id, frame_id_));
    markers_pub_.publish(msg);
  }
  return true;
}

bool SimulatorNode::onSetBallState(SetBallState::Request& req, SetBallState::Response& res)
{
  const Lock guard = lock();
  answerSetBallState(world_, req, res);
  if (res.success)
    publishEdit();
  return true;
}

bool SimulatorNode::onApplyImpulse(ApplyImpulse::Request& req, ApplyImpulse::Response& res)
{
  const Lock guard = lock();
  const core::MotionKind before = kindOf(req.id);
  answerApplyImpulse(world_, req, res);
  if (res.success)
  {
    publishPushTransition(req.id, before);
    publishEdit();
  }
  return true;
}

bool SimulatorNode::onStrike(Strike::Request& req, Strike::Response& res)
{
  const Lock guard = lock();
  strike(req, res);
  return true;
}

void SimulatorNode::strike(const Strike::Request& req, Strike::Response& res)
{
  const core::MotionKind before = kindOf(req.id);
  answerStrike(world_, req, res);
  if (res.success)
  {
    publishPushTransition(req.id, before);
    publishEdit();
  }
}

core::MotionKind SimulatorNode::kindOf(int id) const
{
  const std::size_t k = world_.indexOf(id);
  return k < world_.balls().size() ? world_.motionKind(k) : core::MotionKind::kStationary;
}

void SimulatorNode::publishPushTransition(int id, core::MotionKind before)
{
  const core::MotionKind after = kindOf(id);
  if (after == before)
    return;
  core::MotionTransition transition;
  transition.time = world_.time();
  transition.ball = id;
  transition.from = before;
  transition.to = after;
  transitions_pub_.publish(toMsg(transition, frame_id_));
}

bool SimulatorNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  const Lock guard = lock();
  cancel_run_ = running_;
  world_.reset();
  lost_total_ = 0;
  anchorClock();
  redraw();
  res.success = true;
  res.message = "back to the scene as last loaded (from " + scene_source_ + "): " +
                std::to_string(world_.balls().size()) + " balls, " + std::to_string(world_.walls().size()) +
                " walls, t = 0; run-time settings and pause kept";
  return true;
}

bool SimulatorNode::onLoadScene(LoadScene::Request& req, LoadScene::Response& res)
{
  yaml::SceneFile requested;
  try
  {
    requested = sceneOfRequest(req);  // the reading and checking needs no lock
  }
  catch (const yaml::SceneError& e)
  {
    res.success = false;
    res.message = e.what();
    return true;
  }
  // The new world is built before anything changes: should that throw, nothing has. (It
  // runs on the threads the request names, else on the node's.)
  NodeSettings for_world;
  {
    const Lock guard = lock();
    for_world = settings_.node;
  }
  copyKeys(requested.node_keys, requested.node, for_world);
  std::optional<core::World> built;
  try
  {
    built.emplace(requested.scene, std::move(requested.checked), stepSettingsOf(for_world));
  }
  catch (const std::exception& e)
  {
    res.success = false;
    res.message = e.what();
    return true;
  }
  core::World& fresh = *built;
  NodeSettings in_use;
  {
    const Lock guard = lock();
    cancel_run_ = running_;
    NodeSettings node = settings_.node;
    copyKeys(requested.node_keys, requested.node, node);
    const auto& keys = requested.node_keys;
    if (std::find(keys.begin(), keys.end(), "start_paused") != keys.end())
      paused_ = node.start_paused;
    world_ = std::move(fresh);
    frame_id_ = world_.scene().frame_id;
    scene_source_ = req.path.empty() ? "load_scene's yaml" : req.path;
    applyWiring(resolve(node, nh_.getNamespace()));
    applySettings(node);
    coloring_ = ballColoring(world_, settings_.node);  // the speed scale of the new world
    restartTimer();  // the new scene's dt
    lost_total_ = 0;
    in_use = settings_.node;
    std_msgs::String text;
    text.data = yaml::writeScene(world_.scene(), in_use);
    scene_pub_.publish(text);
    redraw();
    res.message = "loaded " + scene_source_ + ": " + std::to_string(world_.balls().size()) + " balls, " +
                  std::to_string(world_.walls().size()) + " walls" + (paused_ ? ", paused" : "");
  }
  // the master and dynamic_reconfigure's clients learn of it after the lock is let go
  writeSceneParams(pnh_, requested.scene, in_use);
  if (reconfigure_)
    reconfigure_->update(toConfig(in_use));
  res.success = true;
  ROS_INFO("ball_sim: %s", res.message.c_str());
  return true;
}

bool SimulatorNode::onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
{
  const Lock guard = lock();
  if (paused_ && !req.data)
  {
    cancel_run_ = running_;  // running again ends a run of steps
    anchorClock();           // resume from now, without catching up the paused time
  }
  paused_ = req.data;
  res.success = true;
  res.message = (paused_ ? "paused at t = " : "running from t = ") + core::formatNumber(world_.time()) + " s";
  if (paused_)
    publishPresent();
  return true;
}

void SimulatorNode::onClickedPoint(const geometry_msgs::PointStamped& msg)
{
  const Lock guard = lock();
  if (!msg.header.frame_id.empty() && msg.header.frame_id != frame_id_)
  {
    ROS_WARN("ball_sim: clicked point in frame '%s' ignored: set rviz's fixed frame to '%s'",
             msg.header.frame_id.c_str(), frame_id_.c_str());
    return;
  }
  core::BallDef def;
  def.position = toVec3(msg.point);
  def.radius = settings_.node.click_radius;
  def.mass = settings_.node.click_mass;
  // The click lands on the drawn floor: the ball goes onto the floor under it. Without a
  // floor, the centre is lifted by a radius off the clicked plane.
  if (!world_.floor())
  {
    const double g = world_.gravity().norm();
    def.position += def.radius * (g > 0 ? core::Vec3(-world_.gravity() / g) : core::Vec3::UnitZ());
  }
  const std::string full = roomForABall();
  const core::AddResult result =
      full.empty() ? world_.addBall(def, core::Landing::kUnder) : core::AddResult{false, -1, full};
  if (!result.ok)
  {
    ROS_WARN("ball_sim: no ball added at the clicked point: %s", result.error.c_str());
    return;
  }
  ROS_INFO("ball_sim: added ball %d at the clicked point", result.id);
  publishEdit();
}

void SimulatorNode::onReconfigure(const SimulatorConfig& config)
{
  const Lock guard = lock();
  NodeSettings node = settings_.node;
  applyConfig(config, node);  // (checked by reconfigure_, which writes them back to the parameters)
  applySettings(node);
}
}  // namespace ball_collision_sim::bridge
