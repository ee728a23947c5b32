#pragma once

#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/node_settings.hpp"

#include <ball_collision_sim/BallStateArray.h>
#include <ros/time.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <string>
#include <vector>

namespace ball_collision_sim::bridge
{
// What the simulator puts out about its world, built in one place so that the node's
// topics and the offline tool's rosbags carry the same messages.

/// Simulated time for /clock.
rosgraph_msgs::Clock clockMessage(const ros::Time& stamp);

/// Every ball's state, stamped `stamp` in `frame_id`.
BallStateArray statesMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp);
/// frame_id -> prefix + ball_<id> for the first `max_balls` balls.
tf2_msgs::TFMessage transformsMessage(const core::World& world, const std::string& frame_id, const ros::Time& stamp,
                                      std::size_t max_balls, const std::string& prefix = "");
/// The colouring the node's settings ask for: ball_color, and as the top of the speed
/// scale speed_color_max, or when that is 0 the fastest ball of `world` now (1 m/s when
/// every ball is still).
BallColoring ballColoring(const core::World& world, const NodeSettings& node);
/// A sphere marker per ball, or, past `list_threshold` balls, one sphere list per radius
/// (rviz draws a few lists far faster than thousands of markers).
visualization_msgs::MarkerArray ballMarkers(const core::World& world, const std::string& frame_id,
                                            const ros::Time& stamp, std::size_t list_threshold,
                                            const BallColoring& coloring);
/// The floor and the walls.
visualization_msgs::MarkerArray staticMarkers(const core::World& world, const std::string& frame_id);

/// The collisions between two marker sets, drawn as short-lived flashes at their contact
/// points. Resting contacts (a ball leaning on a wall or a ball, every step) do not flash,
/// and at most `max_per_set` collisions are kept per set, so that a dense pile cannot
/// flood rviz.
class CollisionFlashes
{
public:
  /// Most flashes in one marker set.
  static constexpr std::size_t kDefaultMaxPerSet = 32;

  explicit CollisionFlashes(std::size_t max_per_set = kDefaultMaxPerSet) : max_per_set_(max_per_set) {}

  /// Notes the events of a step (the first ones, up to the limit).
  void add(const std::vector<core::CollisionEvent>& events);
  /// The flashes of the events noted since the last call, then forgets them. Ids cycle
  /// through kIdCycle values, more than can be alive at once at common marker rates.
  std::vector<visualization_msgs::Marker> take(const std::string& frame_id, const ros::Time& stamp);
  /// Forgets the noted events (the world was reset).
  void clear() { pending_.clear(); }
  std::size_t pending() const { return pending_.size(); }

  static constexpr int kIdCycle = 4096;

private:
  std::size_t max_per_set_;
  std::vector<core::CollisionEvent> pending_;
  int next_id_ = 0;
};

/// Steps between outputs at `rate` per simulated second: round(1 / (rate dt)), at least
/// one; rate 0 means every step.
std::uint64_t stepsPer(double rate, double dt);
}  // namespace ball_collision_sim::bridge
