#pragma once

#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/node_settings.hpp"

#include <rosbag/bag.h>

#include <cstdint>
#include <string>

namespace ball_collision_sim::bridge
{
/// A run written to a rosbag with the node's topics, every stamp simulated time:
/// /clock every step, /ball_sim/collisions per collision, /ball_sim/ball_states at the
/// scene's state_rate, /tf at its tf_rate (first tf_max_balls balls), /ball_sim/markers
/// at `marker_rate` (with the flashes of the collisions since the last set when the
/// scene's collision_flashes is on), each ball that left the world on
/// /ball_sim/lost_balls, each ball that dropped into a pocket on /ball_sim/pocketed, and the scene's YAML once on /ball_sim/scene. The
/// bag is written under PATH.active and renamed to PATH by close(): no run leaves a
/// truncated bag under the final name.
class RunBag
{
public:
  /// Opens PATH.active and writes the world as it starts; throws rosbag::BagException.
  /// @param marker_rate markers per simulated second [Hz]; 0 = only the first set
  /// @param node the node's settings of the scene file: state_rate, tf_rate, ... as the node would
  RunBag(const std::string& path, const core::World& world, const NodeSettings& node, const std::string& scene_yaml,
         double marker_rate);
  /// Without close(), the partial bag stays under PATH.active.
  ~RunBag();
  RunBag(const RunBag&) = delete;
  RunBag& operator=(const RunBag&) = delete;

  /// Writes what the node publishes after a step of `world`.
  void afterStep(const core::World& world);
  /// Writes the balls that left `world` in its last step on /ball_sim/lost_balls.
  void lost(const core::World& world, const std::vector<core::LostBall>& balls);
  /// Writes the balls that dropped into pockets in `world`'s last step on
  /// /ball_sim/pocketed, each stamped with its drop's time.
  void pocketed(const core::World& world);
  /// Closes the bag and moves it to PATH; throws std::runtime_error when the rename fails.
  void close();

  const std::string& path() const { return path_; }

private:
  template <class Msg>
  void write(const std::string& topic, const ros::Time& stamp, const Msg& msg);
  void writeView(const core::World& world, const ros::Time& stamp);

  std::string path_;
  std::string active_path_;
  std::string frame_id_;
  rosbag::Bag bag_;
  std::uint64_t state_every_;
  std::uint64_t tf_every_;
  std::uint64_t marker_every_;  ///< 0: never after the start
  std::size_t tf_max_balls_;
  NodeSettings node_;
  BallColoring coloring_;  ///< from the world at the start, like the node's
  CollisionFlashes flashes_;
  bool closed_ = false;
};
}  // namespace ball_collision_sim::bridge
