// The balls and the cue as rviz interactive markers: what is sent, and what a feedback
// asks for (interactive_play.hpp); how they look is in play_markers.cpp, the arithmetic
// of a cue's pose in cue_shot.cpp.
#include "ball_collision_sim/ros/interactive_play.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/conversions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>

namespace ball_collision_sim::bridge
{
namespace
{
using visualization_msgs::InteractiveMarkerFeedback;

/// The floor's normal, up against gravity: a plane's own, else gravity's (+z without).
core::Vec3 upOf(const core::World& world)
{
  if (world.floor() && world.floor()->isPlane())
    return world.floor()->planeNormal();
  const double g = world.gravity().norm();
  return g > 0 ? core::Vec3(-world.gravity() / g) : core::Vec3::UnitZ();
}

}  // namespace

InteractivePlay::InteractivePlay(const std::string& topic_ns, const std::string& frame_id, const Handler& handler)
    : server_(topic_ns), frame_id_(frame_id)
{
  // The feedback topic read here rather than through the server's callbacks: the server
  // drops a client's feedback while a marker is younger than 1 s of ROS time, which is
  // simulated time and stands still while the world is paused; and it calls back under
  // its own lock, which sync() takes under the node's.
  feedback_sub_ = ros::NodeHandle().subscribe<visualization_msgs::InteractiveMarkerFeedback>(
      topic_ns + "/feedback", 100,
      [handler](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback) { handler(*feedback); });
}

void InteractivePlay::sync(const core::World& world, int max_balls)
{
  up_ = upOf(world);
  syncBalls(world, max_balls);
  syncCue(world);
  server_.applyChanges();
}

void InteractivePlay::syncBalls(const core::World& world, int max_balls)
{
  const auto balls = world.balls();
  const bool over = balls.size() > static_cast<std::size_t>(std::max(0, max_balls));
  if (over && !over_limit_)
    ROS_INFO("ball_sim: %zu balls, past play_max_balls (%d): no ball markers to drag or choose as the cue ball",
             balls.size(), max_balls);
  over_limit_ = over;
  std::vector<Shown> now;
  if (!over)
    now.reserve(balls.size());
  // Both lists are in id order: one walk finds the balls gone, new and moved.
  auto old = shown_.begin();
  for (std::size_t k = 0; k < (over ? 0 : balls.size()); ++k)
  {
    const core::Ball& ball = balls[k];
    for (; old != shown_.end() && old->id < ball.id; ++old) server_.erase(playMarkerName(old->id));
    const bool known = old != shown_.end() && old->id == ball.id;
    if (!known || old->radius != ball.radius)
      server_.insert(ballPlayMarker(ball, frame_id_, up_));
    else if (old->stale || old->position != ball.position)
    {
      geometry_msgs::Pose pose;
      pose.position = toPoint(ball.position);
      pose.orientation.w = 1.0;
      server_.setPose(playMarkerName(ball.id), pose);
    }
    if (known)
      ++old;
    now.push_back({ball.id, ball.radius, ball.position, false});
  }
  for (; old != shown_.end(); ++old) server_.erase(playMarkerName(old->id));
  shown_ = std::move(now);
}

void InteractivePlay::syncCue(const core::World& world)
{
  if (!cue_)
    return;
  const std::size_t k = world.indexOf(cue_->id);
  if (k == world.balls().size())
  {
    ROS_INFO("ball_sim: the cue ball %d is gone; cue put away", cue_->id);
    server_.erase(kCueMarker);
    cue_.reset();
    return;
  }
  const core::Ball& ball = world.balls()[k];
  const CuePose pose = seatedCue(ball.position, cue_->direction, cue_->offset, up_);
  if (!cue_->sent)
    server_.insert(cuePlayMarker(pose, cue_->id, ball.radius, frame_id_, up_));
  else if (!samePose(poseOf(*cue_->sent), poseOf(pose)))
    server_.setPose(kCueMarker, poseOf(pose));
  cue_->sent = pose;
}

void InteractivePlay::resend(int id)
{
  markStale(playMarkerName(id));
}

void InteractivePlay::markStale(const std::string& name)
{
  if (name == kCueMarker)
  {
    if (cue_ && cue_->sent)
      cue_->sent->position.x() = std::nan("");  // (no pose equals it)
    return;
  }
  const int id = ballOfPlayMarker(name);
  const auto it = std::lower_bound(shown_.begin(), shown_.end(), id, [](const Shown& s, int i) { return s.id < i; });
  if (it != shown_.end() && it->id == id)
    it->stale = true;
}

void InteractivePlay::restart(const std::string& frame_id)
{
  server_.clear();
  server_.applyChanges();
  frame_id_ = frame_id;
  shown_.clear();
  pressed_.clear();
  if (cue_)
    cue_->sent.reset();
}

void InteractivePlay::chooseCue(const core::World& world, int id)
{
  const std::size_t k = world.indexOf(id);
  if (k == world.balls().size())
    return;
  const core::Ball& ball = world.balls()[k];
  // Aimed level at the nearest other ball (the rack, from a pool table's cue ball), else
  // along +x as far as that is level.
  const core::Vec3 up = up_ = upOf(world);
  core::Vec3 toward = core::Vec3::UnitX();
  double nearest = std::numeric_limits<double>::infinity();
  for (const core::Ball& other : world.balls())
  {
    const double distance = (other.position - ball.position).norm();
    if (other.id != id && distance < nearest)
    {
      nearest = distance;
      toward = other.position - ball.position;
    }
  }
  core::Vec3 level = toward - toward.dot(up) * up;
  if (level.norm() < 1e-12)
    level = up.unitOrthogonal();
  if (cue_ && cue_->id != id)
    server_.erase(kCueMarker);
  cue_ = Cue{id, level.normalized(), core::Vec3::Zero(), std::nullopt};
  ROS_INFO("ball_sim: ball %d is the cue ball", id);
}

PlayRequest InteractivePlay::interpret(const core::World& world, const InteractiveMarkerFeedback& feedback)
{
  const std::string& name = feedback.marker_name;
  if (!feedback.header.frame_id.empty() && feedback.header.frame_id != frame_id_)
  {
    ROS_WARN("ball_sim: feedback for %s in frame '%s' ignored: set rviz's fixed frame to '%s'", name.c_str(),
             feedback.header.frame_id.c_str(), frame_id_.c_str());
    return {};
  }
  const int id = ballOfPlayMarker(name);
  switch (feedback.event_type)
  {
    case InteractiveMarkerFeedback::MENU_SELECT:
      if (id != 0 && feedback.menu_entry_id == kMenuCueBall)
        chooseCue(world, id);
      else if (name == kCueMarker && feedback.menu_entry_id == kMenuPutAway && cue_)
      {
        ROS_INFO("ball_sim: cue put away");
        server_.erase(kCueMarker);
        cue_.reset();
      }
      return {};
    case InteractiveMarkerFeedback::MOUSE_DOWN:
      pressed_[name] = feedback.pose;
      return {};
    case InteractiveMarkerFeedback::POSE_UPDATE:
      markStale(name);  // (the server now holds rviz's pose for it)
      return {};
    case InteractiveMarkerFeedback::MOUSE_UP:
      break;
    default:
      return {};
  }
  // A click moves nothing: rviz sends MOUSE_UP where MOUSE_DOWN was.
  const auto down = pressed_.find(name);
  const bool dragged = down != pressed_.end() && !samePose(down->second, feedback.pose);
  if (down != pressed_.end())
    pressed_.erase(down);
  markStale(name);
  if (name == kCueMarker)
    return dragged ? interpretCue(world, feedback) : PlayRequest{};
  if (id == 0 || !dragged || world.indexOf(id) == world.balls().size())
    return {};
  return PlayMove{id, toVec3(feedback.pose.position)};
}

PlayRequest InteractivePlay::interpretCue(const core::World& world, const InteractiveMarkerFeedback& feedback)
{
  if (!cue_)
    return {};
  const std::size_t k = world.indexOf(cue_->id);
  if (k == world.balls().size())
    return {};
  const core::Ball& ball = world.balls()[k];
  const CuePose pose = cuePoseOf(feedback.pose);
  const CueShot shot = cueShot(pose, ball.position, ball.radius, ball.mass);
  if (!shot.error.empty())
  {
    ROS_WARN("ball_sim: the cue on ball %d goes back to its aim: %s", cue_->id, shot.error.c_str());
    return {};
  }
  // the aim (direction and offset) as the pose has it; the cue goes back seated
  cue_->direction = shot.direction;
  cue_->offset = shot.offset;
  if (feedback.control_name != kCuePull || shot.impulse == core::Vec3::Zero())
    return {};
  // (without friction a ball keeps no spin of its own: the strike goes through its centre,
  // as the strike service asks there, whatever round-off rviz's pose leaves off it)
  return PlayStrike{cue_->id, shot.impulse, world.friction() ? shot.offset : core::Vec3(core::Vec3::Zero())};
}
}  // namespace ball_collision_sim::bridge
