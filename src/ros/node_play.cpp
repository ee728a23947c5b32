// Playing in rviz: the node's side of the interactive markers (interactive_play.hpp says
// what a feedback asks for; here it is done, as the services do it).
#include "ball_collision_sim/ros/simulator_node.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/interactive_play.hpp"

#include <optional>
#include <string>

namespace ball_collision_sim::bridge
{
namespace
{
std::string vec(const core::Vec3& v)
{
  return "(" + core::formatNumber(v.x()) + ", " + core::formatNumber(v.y()) + ", " + core::formatNumber(v.z()) + ")";
}
}  // namespace

void SimulatorNode::onPlayFeedback(const visualization_msgs::InteractiveMarkerFeedback& feedback)
{
  const Lock guard = lock();
  const PlayRequest request = play_->interpret(world_, feedback);
  if (const auto* move = std::get_if<PlayMove>(&request))
    playMove(*move);
  else if (const auto* shot = std::get_if<PlayStrike>(&request))
    playStrike(*shot);
  // (not while a drag goes on: rviz would put the marker back where the ball is when it
  // is let go, before the move arrives)
  if (feedback.event_type != visualization_msgs::InteractiveMarkerFeedback::POSE_UPDATE &&
      feedback.event_type != visualization_msgs::InteractiveMarkerFeedback::KEEP_ALIVE)
    syncPlay();
}

void SimulatorNode::playMove(const PlayMove& move)
{
  const std::size_t k = world_.indexOf(move.id);
  if (k == world_.balls().size())
    return;
  // set_ball_state's call with only the position set: its velocity and spin are kept
  core::BallEdit edit;
  edit.position = move.position;
  const core::AddResult result = world_.setBallState(move.id, edit);
  if (!result.ok)
  {
    ROS_WARN("ball_sim: ball %d not moved to %s m: %s", move.id, vec(move.position).c_str(), result.error.c_str());
    play_->resend(move.id);
    return;
  }
  ROS_INFO("ball_sim: moved ball %d to %s m", move.id, vec(world_.balls()[k].position).c_str());
  publishEdit();
}

void SimulatorNode::playStrike(const PlayStrike& shot)
{
  Strike::Request req;
  req.id = shot.id;
  req.impulse = toVector3(shot.impulse);
  req.offset = toVector3(shot.offset);
  Strike::Response res;
  strike(req, res);
  if (!res.success)
  {
    ROS_WARN("ball_sim: the cue did not strike ball %d: %s", shot.id, res.message.c_str());
    return;
  }
  ROS_INFO("ball_sim: the cue struck ball %d: impulse %s N s at %s m from its centre", shot.id,
           vec(shot.impulse).c_str(), vec(shot.offset).c_str());
}

void SimulatorNode::syncPlay()
{
  if (play_)
    play_->sync(world_, settings_.node.play_max_balls);
}
}  // namespace ball_collision_sim::bridge
