// Playing in rviz (run by rostest with test/play.test): the node's interactive markers
// driven as rviz drives them, by InteractiveMarkerFeedback on ~play/feedback, and what
// the node does, read back through get_state, ~play/update_full, motion_transitions and
// /rosout.
#include <ball_collision_sim/GetState.h>
#include <ball_collision_sim/LoadScene.h>
#include <ball_collision_sim/MotionTransition.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include "ros_inbox.hpp"

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace bcs = ball_collision_sim;
using visualization_msgs::InteractiveMarkerFeedback;

namespace
{
// test/data/play_scene.yaml
constexpr double kR = 0.028575;
constexpr double kM = 0.170097;
constexpr double kInertia = 0.4;  // solid
// The cue as documented (cue_shot.hpp): 10 m/s of ball speed per metre of pull, at most 10 m/s.
constexpr double kSpeedPerPull = 10.0;
constexpr double kMaxSpeed = 10.0;

using Vec3 = Eigen::Vector3d;
/// Ball 1's place in both scenes of the test [m]
const Vec3 kStart1(-0.6, 0.0, kR);

using ball_collision_sim::test::Inbox;

Vec3 toVec(const geometry_msgs::Point& p)
{
  return Vec3(p.x, p.y, p.z);
}
Vec3 toVec(const geometry_msgs::Vector3& v)
{
  return Vec3(v.x, v.y, v.z);
}

bcs::GetState::Response state()
{
  bcs::GetState srv;
  EXPECT_TRUE(ros::service::call("/ball_sim/get_state", srv));
  return srv.response;
}

const bcs::BallState* ballOf(const bcs::GetState::Response& s, int id)
{
  for (const bcs::BallState& b : s.balls)
    if (b.id == id)
      return &b;
  return nullptr;
}

/// The marker of that name in a full update, or none.
std::optional<visualization_msgs::InteractiveMarker> markerIn(const visualization_msgs::InteractiveMarkerInit& init,
                                                              const std::string& name)
{
  for (const auto& m : init.markers)
    if (m.name == name)
      return m;
  return std::nullopt;
}

geometry_msgs::Pose poseAt(const Vec3& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity())
{
  geometry_msgs::Pose pose;
  pose.position.x = p.x();
  pose.position.y = p.y();
  pose.position.z = p.z();
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  pose.orientation.w = q.w();
  return pose;
}

void expectSameWorld(const bcs::GetState::Response& a, const bcs::GetState::Response& b)
{
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.balls.size(), b.balls.size());
  for (std::size_t k = 0; k < a.balls.size(); ++k)
  {
    EXPECT_EQ(a.balls[k].id, b.balls[k].id);
    EXPECT_EQ(toVec(a.balls[k].pose.position), toVec(b.balls[k].pose.position)) << "ball " << a.balls[k].id;
    EXPECT_EQ(toVec(a.balls[k].twist.linear), toVec(b.balls[k].twist.linear)) << "ball " << a.balls[k].id;
    EXPECT_EQ(toVec(a.balls[k].twist.angular), toVec(b.balls[k].twist.angular)) << "ball " << a.balls[k].id;
  }
}

class Play : public ::testing::Test
{
protected:
  Play() : full_("/ball_sim/play/update_full"), transitions_("/ball_sim/motion_transitions"), log_("/rosout")
  {
    feedback_ = ros::NodeHandle().advertise<InteractiveMarkerFeedback>("/ball_sim/play/feedback", 100);
  }

  void SetUp() override
  {
    ASSERT_TRUE(ros::service::waitForService("/ball_sim/get_state", ros::Duration(20)));
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10);
    while (feedback_.getNumSubscribers() == 0 && ros::WallTime::now() < end) ros::WallDuration(0.01).sleep();
    ASSERT_GT(feedback_.getNumSubscribers(), 0u) << "no interactive marker server on /ball_sim/play";
    ASSERT_TRUE(full_.waitFor([](const auto& m) { return !m.empty() && markerIn(m.back(), "ball_4"); }, 10))
        << "no marker ball_4 in /ball_sim/play/update_full";
    ros::WallDuration(0.3).sleep();  // (the connections settle)
  }

  void send(const std::string& marker, const std::string& control, std::uint8_t type, const geometry_msgs::Pose& pose,
            std::uint32_t menu_entry = 0)
  {
    InteractiveMarkerFeedback f;
    f.header.frame_id = "world";
    f.client_id = "/test_play/rviz";
    f.marker_name = marker;
    f.control_name = control;
    f.event_type = type;
    f.pose = pose;
    f.menu_entry_id = menu_entry;
    feedback_.publish(f);
    ros::WallDuration(0.02).sleep();  // (in order, as rviz sends them a frame apart)
  }

  /// A drag as rviz sends it: a pose update and MOUSE_DOWN where it starts, pose updates
  /// on the way, and a pose update and MOUSE_UP where it ends.
  void drag(const std::string& marker, const std::string& control, const geometry_msgs::Pose& from,
            const geometry_msgs::Pose& to)
  {
    send(marker, control, InteractiveMarkerFeedback::POSE_UPDATE, from);
    send(marker, control, InteractiveMarkerFeedback::MOUSE_DOWN, from);
    send(marker, control, InteractiveMarkerFeedback::POSE_UPDATE, to);
    send(marker, control, InteractiveMarkerFeedback::POSE_UPDATE, to);
    send(marker, control, InteractiveMarkerFeedback::MOUSE_UP, to);
  }

  /// The marker's pose in the latest full update, once `pred` holds for it.
  std::optional<visualization_msgs::InteractiveMarker> waitMarker(
      const std::string& name, const std::function<bool(const visualization_msgs::InteractiveMarker&)>& pred)
  {
    std::optional<visualization_msgs::InteractiveMarker> found;
    full_.waitFor(
        [&](const auto& msgs)
        {
          found = msgs.empty() ? std::nullopt : markerIn(msgs.back(), name);
          return found && pred(*found);
        });
    return found;
  }

  bool warned(const std::string& a, const std::string& b)
  {
    return log_.waitFor(
        [&](const std::vector<rosgraph_msgs::Log>& logs)
        {
          return std::any_of(logs.begin(), logs.end(),
                             [&](const rosgraph_msgs::Log& l)
                             {
                               return l.level == rosgraph_msgs::Log::WARN && l.msg.find(a) != std::string::npos &&
                                      l.msg.find(b) != std::string::npos;
                             });
        });
  }

  Inbox<visualization_msgs::InteractiveMarkerInit> full_;
  Inbox<bcs::MotionTransition> transitions_;
  Inbox<rosgraph_msgs::Log> log_;
  ros::Publisher feedback_;
};

// One test in order: each step starts from the world the one before left.
TEST_F(Play, DragsMoveBallsOrAreRefusedAndTheCueStrikesAsItsPoseSays)
{
  const bcs::GetState::Response start = state();
  ASSERT_EQ(start.balls.size(), 4u);
  ASSERT_TRUE(start.paused);

  // ---- a drag moves ball 2, which keeps its id ----
  const Vec3 to(0.05, -0.3, kR);
  drag("ball_2", "move", poseAt(Vec3(0.3, 0, kR)), poseAt(to));
  bcs::GetState::Response moved;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5);
  do
  {
    moved = state();
  } while ((toVec(ballOf(moved, 2)->pose.position) - to).norm() > 1e-12 && ros::WallTime::now() < end);
  ASSERT_NE(ballOf(moved, 2), nullptr);
  EXPECT_NEAR((toVec(ballOf(moved, 2)->pose.position) - to).norm(), 0.0, 1e-12);
  ASSERT_EQ(moved.balls.size(), 4u);
  for (int id = 1; id <= 4; ++id) EXPECT_NE(ballOf(moved, id), nullptr) << "ball " << id;
  EXPECT_EQ(toVec(ballOf(moved, 2)->twist.linear), Vec3::Zero());
  EXPECT_EQ(moved.time, start.time);
  // ... and its marker follows
  EXPECT_TRUE(waitMarker("ball_2", [&](const auto& m) { return (toVec(m.pose.position) - to).norm() < 1e-12; }));

  // ---- a drag onto ball 2 is refused: nothing changes, a WARN says why, the marker goes back ----
  const Vec3 at3 = toVec(ballOf(moved, 3)->pose.position);
  drag("ball_3", "move", poseAt(at3), poseAt(to + Vec3(0.01, 0.02, 0)));
  EXPECT_TRUE(warned("ball 3 not moved", "overlaps ball 2"));
  expectSameWorld(state(), moved);
  EXPECT_TRUE(waitMarker("ball_3", [&](const auto& m) { return toVec(m.pose.position) == at3; }))
      << "ball_3's marker is not back on the ball";

  // ---- a click (MOUSE_UP where MOUSE_DOWN was) moves nothing, even away from the ball ----
  const geometry_msgs::Pose stale = poseAt(toVec(ballOf(moved, 4)->pose.position) + Vec3(0.05, 0, 0));
  send("ball_4", "move", InteractiveMarkerFeedback::MOUSE_DOWN, stale);
  send("ball_4", "move", InteractiveMarkerFeedback::MOUSE_UP, stale);
  ros::WallDuration(0.3).sleep();
  expectSameWorld(state(), moved);

  // ---- ball 1 chosen as the cue ball from its menu: the cue sits on it, aimed level at
  //      the nearest ball (ball 4) ----
  const auto ball1 = waitMarker("ball_1", [](const auto&) { return true; });
  ASSERT_TRUE(ball1);
  std::uint32_t entry = 0;
  for (const auto& e : ball1->menu_entries)
    if (e.title == "Cue ball")
      entry = e.id;
  ASSERT_NE(entry, 0u) << "no menu entry \"Cue ball\" on ball_1";
  send("ball_1", "", InteractiveMarkerFeedback::MENU_SELECT, ball1->pose, entry);
  const Vec3 c = toVec(ballOf(moved, 1)->pose.position);
  const auto cue = waitMarker("cue", [](const auto&) { return true; });
  ASSERT_TRUE(cue) << "no cue marker after choosing ball 1";
  const Eigen::Quaterniond seated(cue->pose.orientation.w, cue->pose.orientation.x, cue->pose.orientation.y,
                                  cue->pose.orientation.z);
  EXPECT_NEAR((toVec(cue->pose.position) - c).norm(), 0.0, 1e-12);
  const Vec3 toward4 = (toVec(ballOf(moved, 4)->pose.position) - c).normalized();
  EXPECT_NEAR((seated * Vec3::UnitX() - toward4).norm(), 0.0, 1e-12);

  // ---- a pull whose line misses the ball strikes nothing ----
  const Eigen::Quaterniond level(Eigen::AngleAxisd(0.35, Vec3::UnitZ()));
  const Vec3 d = level * Vec3::UnitX();
  const Vec3 side = level * Vec3::UnitY();
  drag("cue", "pull", cue->pose, poseAt(c + 1.5 * kR * side - 0.2 * d, level));
  EXPECT_TRUE(warned("cue on ball 1", "outside its radius"));
  expectSameWorld(state(), moved);

  // ---- pulled back 0.25 m, turned to 0.35 rad, its line 8 mm aside and 10 mm above the
  //      centre, let go: J = m min(10 s, 10) d at o, as the closed forms say ----
  const double s = 0.25;
  const Vec3 o = 0.008 * side + 0.010 * Vec3::UnitZ();
  const Vec3 J = kM * std::min(kSpeedPerPull * s, kMaxSpeed) * d;
  drag("cue", "pull", cue->pose, poseAt(c + o - s * d, level));
  ASSERT_TRUE(transitions_.waitFor([](const auto& msgs) { return !msgs.empty(); }))
      << "no motion transition after the strike";
  const bcs::MotionTransition t = transitions_.all().front();
  EXPECT_EQ(t.ball, 1);
  EXPECT_EQ(t.before, bcs::BallState::STATIONARY);
  EXPECT_EQ(t.after, bcs::BallState::SLIDING);
  const bcs::GetState::Response struck = state();
  const bcs::BallState* b1 = ballOf(struck, 1);
  ASSERT_NE(b1, nullptr);
  EXPECT_EQ(struck.time, start.time);  // (paused: struck, not moved)
  EXPECT_EQ(toVec(b1->pose.position), c);
  const Vec3 dv = J / kM;                                  // 2.5 m/s along d
  const Vec3 dw = o.cross(J) / (kInertia * kM * kR * kR);  // follow and side spin
  EXPECT_NEAR((toVec(b1->twist.linear) - dv).norm(), 0.0, 1e-12) << toVec(b1->twist.linear).transpose();
  EXPECT_NEAR((toVec(b1->twist.angular) - dw).norm(), 0.0, 1e-9) << toVec(b1->twist.angular).transpose();
  EXPECT_GT(dw.norm(), 90.0);  // (a spin that matters: about 7.7 rad/s per mm of offset)
  for (int id = 2; id <= 4; ++id) EXPECT_EQ(toVec(ballOf(struck, id)->twist.linear), Vec3::Zero());
  // the cue goes back seated on its ball, at the aim it was let go at
  EXPECT_TRUE(waitMarker("cue", [&](const auto& m) { return (toVec(m.pose.position) - (c + o)).norm() < 1e-12; }));

  // ---- past play_max_balls no ball has a marker; the cue stays on its ball ----
  const auto setLimit = [](int value)
  {
    dynamic_reconfigure::Reconfigure srv;
    dynamic_reconfigure::IntParameter p;
    p.name = "play_max_balls";
    p.value = value;
    srv.request.config.ints.push_back(p);
    EXPECT_TRUE(ros::service::call("/ball_sim/set_parameters", srv));
  };
  setLimit(3);
  EXPECT_TRUE(full_.waitFor(
      [](const auto& msgs)
      {
        return !msgs.empty() && !markerIn(msgs.back(), "ball_1") && !markerIn(msgs.back(), "ball_4") &&
               markerIn(msgs.back(), "cue");
      }))
      << "ball markers left past play_max_balls";
  setLimit(4);
  EXPECT_TRUE(
      full_.waitFor([](const auto& msgs)
                    { return !msgs.empty() && markerIn(msgs.back(), "ball_1") && markerIn(msgs.back(), "ball_4"); }))
      << "ball markers not back within play_max_balls";

  // ---- without friction a ball keeps no spin of its own: the cue strikes through its
  //      centre whatever its line's offset (or the round-off of rviz's pose), dv = J / m ----
  bcs::LoadScene load;
  load.request.yaml = "dt: 0.002\nfloor: {type: plane, point: [-1.27, -0.635, 0], u: [2.54, 0, 0], v: [0, 1.27, 0]}\n"
                      "balls:\n  - {position: [-0.6, 0.0, 0.028575], radius: 0.028575, mass: 0.170097}\n"
                      "  - {position: [0.3, 0.0, 0.028575], radius: 0.028575, mass: 0.170097}\n"
                      "start_paused: true\n";
  ASSERT_TRUE(ros::service::call("/ball_sim/load_scene", load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  const auto plain1 = waitMarker("ball_1", [](const auto& m) { return !m.menu_entries.empty(); });
  ASSERT_TRUE(plain1);
  send("ball_1", "", InteractiveMarkerFeedback::MENU_SELECT, plain1->pose, entry);
  const auto plain_cue = waitMarker("cue", [&](const auto& m) { return (toVec(m.pose.position) - kStart1).norm() < 1e-12; });
  ASSERT_TRUE(plain_cue) << "no cue on ball 1 of the frictionless table";
  drag("cue", "pull", plain_cue->pose, poseAt(kStart1 + o - s * d, level));
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(5);
  bcs::GetState::Response plain;
  do
  {
    plain = state();
  } while (ballOf(plain, 1) != nullptr && toVec(ballOf(plain, 1)->twist.linear) == Vec3::Zero() &&
           ros::WallTime::now() < until);
  ASSERT_NE(ballOf(plain, 1), nullptr);
  EXPECT_NEAR((toVec(ballOf(plain, 1)->twist.linear) - dv).norm(), 0.0, 1e-12)
      << toVec(ballOf(plain, 1)->twist.linear).transpose();
  // (rolling's spin, n x v / r, and none of the offset's)
  EXPECT_NEAR((toVec(ballOf(plain, 1)->twist.angular) - Vec3::UnitZ().cross(dv) / kR).norm(), 0.0, 1e-9);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_play");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
