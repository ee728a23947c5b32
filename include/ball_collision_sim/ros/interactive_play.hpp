#pragma once

#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/cue_shot.hpp"
#include "ball_collision_sim/ros/play_markers.hpp"

#include <interactive_markers/interactive_marker_server.h>
#include <ros/subscriber.h>
#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace ball_collision_sim::bridge
{
/// A drag asks to move ball `id` to `position` [m] (onto the floor under it).
struct PlayMove
{
  int id = 0;
  core::Vec3 position = core::Vec3::Zero();
};
/// A cue's release asks to strike ball `id` (core::World::strike()).
struct PlayStrike
{
  int id = 0;
  core::Vec3 impulse = core::Vec3::Zero();  ///< [N s]
  core::Vec3 offset = core::Vec3::Zero();   ///< [m] from the centre
};
/// What one feedback asks of the world: nothing, a move or a strike.
using PlayRequest = std::variant<std::monostate, PlayMove, PlayStrike>;

/// The balls and a cue as rviz interactive markers (topics `<topic_ns>/update`,
/// `/update_full` and `/feedback`): a ball is dragged in the floor's plane by the ring
/// around it, chosen as the cue ball from its menu; the cue is aimed by turning it about
/// the floor's normal and tilting it, its line moved across the ball for spin, and pulled
/// back and let go to strike (cue_shot.hpp). It only says what a feedback asks for (a
/// PlayRequest); the node does it. Every method is called under the node's lock.
class InteractivePlay
{
public:
  using Handler = std::function<void(const visualization_msgs::InteractiveMarkerFeedback&)>;
  /// Every feedback on `<topic_ns>/feedback` goes to `handler`, from the global queue.
  InteractivePlay(const std::string& topic_ns, const std::string& frame_id, const Handler& handler);
  InteractivePlay(const InteractivePlay&) = delete;
  InteractivePlay& operator=(const InteractivePlay&) = delete;

  /// The markers as the world is now: one per ball while there are at most `max_balls`
  /// (none past it), the cue on its ball; only what changed is sent (poses of balls that
  /// moved, markers of balls added or removed).
  void sync(const core::World& world, int max_balls);
  /// What `feedback` asks for. Choosing, aiming and putting away the cue are done here;
  /// a move asks only after a drag (MOUSE_UP away from where MOUSE_DOWN was), a strike
  /// only after the cue's pull control was dragged back and let go.
  PlayRequest interpret(const core::World& world, const visualization_msgs::InteractiveMarkerFeedback& feedback);
  /// Puts ball `id`'s marker back on the ball at the next sync() (a refused move).
  void resend(int id);
  /// After the world was rebuilt (reset, load_scene): every marker sent anew in
  /// `frame_id`; the cue stays on its ball id while that exists.
  void restart(const std::string& frame_id);

private:
  struct Shown
  {
    int id = 0;
    double radius = 0.0;                       ///< [m]
    core::Vec3 position = core::Vec3::Zero();  ///< as last sent [m]
    bool stale = false;                        ///< rviz moved it since: send again
  };
  struct Cue
  {
    int id = 0;                                  ///< the cue ball
    core::Vec3 direction = core::Vec3::UnitX();  ///< unit
    core::Vec3 offset = core::Vec3::Zero();      ///< [m] from the centre, square to direction
    std::optional<CuePose> sent;                 ///< pose last sent; none: insert it
  };

  void syncBalls(const core::World& world, int max_balls);
  void syncCue(const core::World& world);
  void chooseCue(const core::World& world, int id);
  /// The cue let go after a drag: its aim kept, and where it was pulled back, a strike.
  PlayRequest interpretCue(const core::World& world, const visualization_msgs::InteractiveMarkerFeedback& feedback);
  void markStale(const std::string& name);

  interactive_markers::InteractiveMarkerServer server_;
  std::string frame_id_;
  ros::Subscriber feedback_sub_;
  core::Vec3 up_ = core::Vec3::UnitZ();  ///< the floor's normal, against gravity
  std::vector<Shown> shown_;             ///< ball markers in the server, by id
  bool over_limit_ = false;              ///< past max_balls at the last sync()
  std::optional<Cue> cue_;
  /// where each marker was at its MOUSE_DOWN, until its MOUSE_UP
  std::map<std::string, geometry_msgs::Pose> pressed_;
};
}  // namespace ball_collision_sim::bridge
