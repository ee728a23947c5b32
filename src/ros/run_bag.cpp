#include "ball_collision_sim/ros/run_bag.hpp"

#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/requests.hpp"

#include <ball_collision_sim/LostBall.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace ball_collision_sim::bridge
{
RunBag::RunBag(const std::string& path, const core::World& world, const NodeSettings& node,
               const std::string& scene_yaml, double marker_rate)
    : path_(path)
    , active_path_(path + ".active")
    , frame_id_(world.scene().frame_id)
    , state_every_(stepsPer(node.state_rate, world.dt()))
    , tf_every_(node.tf_rate > 0 ? stepsPer(node.tf_rate, world.dt()) : 0)
    , marker_every_(marker_rate > 0 ? stepsPer(marker_rate, world.dt()) : 0)
    , tf_max_balls_(static_cast<std::size_t>(node.tf_max_balls))
    , node_(node)
    , coloring_(ballColoring(world, node))
{
  bag_.open(active_path_, rosbag::bagmode::Write);
  const ros::Time stamp(world.time());
  std_msgs::String scene;
  scene.data = scene_yaml;
  write("/ball_sim/scene", stamp, scene);
  write("/clock", stamp, clockMessage(stamp));
  write("/ball_sim/markers", stamp, staticMarkers(world, frame_id_));
  write("/ball_sim/ball_states", stamp, statesMessage(world, frame_id_, stamp));
  writeView(world, stamp);
}

void RunBag::lost(const core::World& world, const std::vector<core::LostBall>& balls)
{
  const ros::Time stamp(world.time());
  for (const core::LostBall& gone : balls)
    write("/ball_sim/lost_balls", stamp, lostBallMessage(gone, frame_id_, world.time()));
}

void RunBag::pocketed(const core::World& world)
{
  for (const core::PocketedBall& dropped : world.lastPocketed())
    write("/ball_sim/pocketed", ros::Time(dropped.time), pocketedMessage(dropped, frame_id_));
}

RunBag::~RunBag()
{
  if (!closed_)
    bag_.close();
}

template <class Msg>
void RunBag::write(const std::string& topic, const ros::Time& stamp, const Msg& msg)
{
  // A bag cannot hold time 0: the start is written at the first representable instant.
  bag_.write(topic, std::max(stamp, ros::TIME_MIN), msg);
}

void RunBag::writeView(const core::World& world, const ros::Time& stamp)
{
  if (tf_every_ > 0 && world.stats().steps % tf_every_ == 0 && tf_max_balls_ > 0)
    write("/tf", stamp, transformsMessage(world, frame_id_, stamp, tf_max_balls_, node_.frame_prefix.value_or("")));
  if (world.stats().steps == 0 || (marker_every_ > 0 && world.stats().steps % marker_every_ == 0))
  {
    visualization_msgs::MarkerArray markers = ballMarkers(
        world, frame_id_, stamp, static_cast<std::size_t>(node_.marker_list_threshold), coloring_);
    const std::vector<visualization_msgs::Marker> flashes = flashes_.take(frame_id_, stamp);
    markers.markers.insert(markers.markers.end(), flashes.begin(), flashes.end());
    write("/ball_sim/markers", stamp, markers);
  }
}

void RunBag::afterStep(const core::World& world)
{
  const ros::Time stamp(world.time());
  write("/clock", stamp, clockMessage(stamp));
  if (node_.publish_collisions)
    for (const core::CollisionEvent& event : world.lastEvents())
    {
      const auto msg = toMsg(event, frame_id_);
      write("/ball_sim/collisions", msg.header.stamp, msg);
    }
  for (const core::MotionTransition& transition : world.lastTransitions())
  {
    const auto msg = toMsg(transition, frame_id_);
    write("/ball_sim/motion_transitions", msg.header.stamp, msg);
  }
  if (world.stats().steps % state_every_ == 0)
    write("/ball_sim/ball_states", stamp, statesMessage(world, frame_id_, stamp));
  if (marker_every_ > 0 && node_.collision_flashes)
    flashes_.add(world.lastEvents());
  writeView(world, stamp);
}

void RunBag::close()
{
  if (closed_)
    return;
  bag_.close();
  closed_ = true;
  if (std::rename(active_path_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(path_ + ": cannot move the finished bag there from " + active_path_ + " (" +
                             std::strerror(errno) + ")");
}
}  // namespace ball_collision_sim::bridge
