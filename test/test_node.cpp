// The simulator node through its real interfaces (run by rostest with test/node.test):
// services with good and bad requests, markers, tf, stepping, reset, collisions, and the
// parameter-server reader against the YAML reader.
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/BallStateArray.h>
#include <ball_collision_sim/CollisionEvent.h>
#include <ball_collision_sim/MotionTransition.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/Step.h>
#include <ball_collision_sim/Strike.h>
#include <geometry_msgs/PointStamped.h>
#include "ros_inbox.hpp"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unistd.h>
#include <mutex>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace bcs = ball_collision_sim;

namespace
{
// The scene of test/data/node_scene.yaml.
constexpr double kDt = 0.01;
constexpr double kImpactTime = (1.263 - 0.25) / 2.0;  // gap over closing speed [s]

using ball_collision_sim::test::Inbox;

template <class Msg>
void waitConnected(const Inbox<Msg>& inbox)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (!inbox.connected() && ros::WallTime::now() < end)
    ros::WallDuration(0.01).sleep();
  ros::WallDuration(0.2).sleep();  // let the connection settle before publishing starts
}

template <class Srv>
Srv call(const std::string& name, Srv srv)
{
  EXPECT_TRUE(ros::service::call(name, srv)) << name << " failed as a call";
  return srv;
}

bcs::Step::Response step(std::uint32_t n)
{
  bcs::Step srv;
  srv.request.steps = n;
  return call("/ball_sim/step", srv).response;
}

void pause(bool on)
{
  std_srvs::SetBool srv;
  srv.request.data = on;
  EXPECT_TRUE(call("/ball_sim/pause", srv).response.success);
}

void reset()
{
  std_srvs::Trigger srv;
  EXPECT_TRUE(call("/ball_sim/reset", srv).response.success);
}

bcs::AddBall::Response addBall(double x, double y, double vx, double vy, double r, double m)
{
  bcs::AddBall srv;
  srv.request.position.x = x;
  srv.request.position.y = y;
  srv.request.position.z = std::min(r, 0.1);
  srv.request.velocity.x = vx;
  srv.request.velocity.y = vy;
  srv.request.radius = r;
  srv.request.mass = m;
  return call("/ball_sim/add_ball", srv).response;
}

bcs::AddWall::Response addWall(double px, double py, double ux, double uy, double vx, double vy, double vz)
{
  bcs::AddWall srv;
  srv.request.point.x = px;
  srv.request.point.y = py;
  srv.request.u.x = ux;
  srv.request.u.y = uy;
  srv.request.v.x = vx;
  srv.request.v.y = vy;
  srv.request.v.z = vz;
  return call("/ball_sim/add_wall", srv).response;
}

bcs::RemoveObject::Response remove(const std::string& what, int id)
{
  bcs::RemoveObject srv;
  srv.request.id = id;
  return call("/ball_sim/remove_" + what, srv).response;
}

/// A fresh, paused world at t = 0.
void fresh()
{
  pause(true);
  reset();
}

/// The ball states after stepping n steps from now.
bcs::BallStateArray statesAfter(std::uint32_t n)
{
  Inbox<bcs::BallStateArray> states("/ball_sim/ball_states");
  waitConnected(states);
  const double t = step(n).time;
  std::vector<bcs::BallStateArray> got;
  EXPECT_TRUE(states.waitFor([&](const auto& all) { return !all.empty() && std::abs(all.back().header.stamp.toSec() - t) < 1e-6; }));
  got = states.take();
  return got.empty() ? bcs::BallStateArray() : got.back();
}
}  // namespace

TEST(Node, PauseThenStepAdvancesExactlyNSteps)
{
  fresh();
  Inbox<rosgraph_msgs::Clock> clock("/clock");
  waitConnected(clock);
  const auto r = step(7);
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_NEAR(r.time, 7 * kDt, 1e-12);
  // (a new subscriber is first sent the present, t = 0: the step's ticks follow it)
  ASSERT_TRUE(clock.waitFor(
      [](const auto& all) { return !all.empty() && std::abs(all.back().clock.toSec() - 7 * kDt) < 1e-9; }));
  const auto ticks = clock.take();
  EXPECT_GE(ticks.size(), 7u);
  for (std::size_t k = 1; k < ticks.size(); ++k)
    EXPECT_LT(ticks[k - 1].clock.toSec(), ticks[k].clock.toSec()) << "the clock goes forward, tick " << k;
  // paused: the clock does not move by itself
  ros::WallDuration(0.3).sleep();
  EXPECT_TRUE(clock.take().empty());
  EXPECT_NEAR(step(5).time, 12 * kDt, 1e-12);
}

TEST(Node, StepIsRefusedWhileRunningOrOutOfRange)
{
  fresh();
  auto r = step(0);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.message.rfind("steps", 0), 0u) << r.message;
  r = step(2000000);
  EXPECT_FALSE(r.success);
  pause(false);
  r = step(1);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.message.rfind("steps", 0), 0u) << r.message;
  pause(true);
}

TEST(Node, HeadOnCollisionAtTheAnalyticTime)
{
  fresh();
  Inbox<bcs::CollisionEvent> collisions("/ball_sim/collisions");
  waitConnected(collisions);
  step(60);
  ASSERT_TRUE(collisions.waitFor([](const auto& all) { return !all.empty(); }));
  ros::WallDuration(0.2).sleep();
  const auto events = collisions.take();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, bcs::CollisionEvent::BALL_BALL);
  EXPECT_EQ(events[0].ball, 1);  // ids start at 1
  EXPECT_EQ(events[0].other, 2);
  EXPECT_NEAR(events[0].header.stamp.toSec(), kImpactTime, 1e-9);
  EXPECT_EQ(events[0].header.frame_id, "world");
  // 1 kg at 1.5 m/s meets 3 kg at -0.5 m/s: the impulse is 2 m1 m2 / (m1 + m2) * 2 m/s
  EXPECT_NEAR(events[0].impulse, 2 * 3.0 / 4.0 * 2.0, 1e-12);
}

// A jump shot through the service: struck down into the floor (the scene's restitution,
// 1, is the floor's), the ball comes off it at 1 m/s, flies (FLYING in its state and on
// ball_states) and lands 2 v / g later, a BALL_FLOOR event at that time.
TEST(Node, StrikeDownIntoTheFloorJumps)
{
  fresh();
  Inbox<bcs::CollisionEvent> collisions("/ball_sim/collisions");
  Inbox<bcs::MotionTransition> transitions("/ball_sim/motion_transitions");
  waitConnected(collisions);
  waitConnected(transitions);
  bcs::Strike srv;
  srv.request.id = 1;
  srv.request.impulse.z = -1.0;  // 1 kg
  const auto struck = call("/ball_sim/strike", srv).response;
  ASSERT_TRUE(struck.success) << struck.message;
  EXPECT_EQ(struck.state.motion, bcs::BallState::FLYING);
  EXPECT_NEAR(struck.state.twist.linear.z, 1.0, 1e-15);
  // the strike's own change of kind, at once: rolling (without friction, moving) to flying
  ASSERT_TRUE(transitions.waitFor([](const auto& all) { return !all.empty(); }));
  const auto took_off = transitions.take();
  ASSERT_EQ(took_off.size(), 1u);
  EXPECT_EQ(took_off[0].ball, 1);
  EXPECT_EQ(took_off[0].before, bcs::BallState::ROLLING);
  EXPECT_EQ(took_off[0].after, bcs::BallState::FLYING);
  EXPECT_EQ(took_off[0].header.stamp.toSec(), 0.0);
  const bcs::BallStateArray mid = statesAfter(10);
  ASSERT_EQ(mid.balls.size(), 2u);
  EXPECT_EQ(mid.balls[0].motion, bcs::BallState::FLYING);
  EXPECT_NEAR(mid.balls[0].pose.position.z, 0.125 + 0.1 - 0.5 * 9.81 * 0.01, 1e-12);
  step(20);
  ASSERT_TRUE(collisions.waitFor([](const auto& all) {
    return std::any_of(all.begin(), all.end(), [](const auto& e) { return e.kind == bcs::CollisionEvent::BALL_FLOOR; });
  }));
  const auto events = collisions.take();
  const auto landing = std::find_if(events.begin(), events.end(),
                                    [](const auto& e) { return e.kind == bcs::CollisionEvent::BALL_FLOOR; });
  EXPECT_EQ(landing->ball, 1);
  EXPECT_NEAR(landing->header.stamp.toSec(), 2 * 1.0 / 9.81, 1e-9);
  EXPECT_NEAR(landing->approach_speed, 1.0, 1e-12);
  EXPECT_NEAR(landing->point.z, 0.0, 1e-12);
}

TEST(Node, AddedBallHasATfFrameWhereThePhysicsPutsIt)
{
  fresh();
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ros::WallDuration(0.5).sleep();
  const auto added = addBall(-1, 0.6, 0.8, -0.3, 0.1, 1);
  ASSERT_TRUE(added.success) << added.message;
  EXPECT_EQ(added.id, 3);
  step(25);
  const ros::Time t(25 * kDt);
  std::string error;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (!buffer.canTransform("world", "ball_3", t, &error) && ros::WallTime::now() < end)
    ros::WallDuration(0.02).sleep();
  ASSERT_TRUE(buffer.canTransform("world", "ball_3", t, &error)) << error;
  const auto tf = buffer.lookupTransform("world", "ball_3", t);
  EXPECT_NEAR(tf.transform.translation.x, -1 + 0.8 * 0.25, 1e-9);
  EXPECT_NEAR(tf.transform.translation.y, 0.6 - 0.3 * 0.25, 1e-9);
  EXPECT_NEAR(tf.transform.translation.z, 0.1, 1e-12);
  // rolled: turned by distance / radius
  const double turned = 2 * std::acos(std::min(1.0, std::abs(tf.transform.rotation.w)));
  EXPECT_NEAR(turned, std::hypot(0.8, 0.3) * 0.25 / 0.1, 1e-9);
}

TEST(Node, GoodRequestsChangeTheWorld)
{
  fresh();
  const auto ball = addBall(1.2, 0.5, 0, 0, 0.1, 2);
  ASSERT_TRUE(ball.success) << ball.message;
  const auto wall = addWall(0.5, -1, 0, 0.8, 0, 0, 0.3);
  ASSERT_TRUE(wall.success) << wall.message;
  EXPECT_EQ(wall.id, 5);
  EXPECT_EQ(statesAfter(1).balls.size(), 3u);
  // a third ball is the most this node takes (max_balls: 3 in its scene)
  const auto over = addBall(-1.2, 0.5, 0, 0, 0.1, 1);
  EXPECT_FALSE(over.success);
  EXPECT_EQ(over.message.rfind("max_balls", 0), 0u) << over.message;
  EXPECT_TRUE(remove("wall", wall.id).success);
  EXPECT_FALSE(remove("wall", wall.id).success);
  EXPECT_TRUE(remove("ball", ball.id).success);
  const auto r = remove("ball", ball.id);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.message.rfind("id", 0), 0u) << r.message;
  EXPECT_EQ(statesAfter(1).balls.size(), 2u);
}

TEST(Node, BadRequestsNameTheFieldAndChangeNothing)
{
  fresh();
  const auto reference = statesAfter(30);
  fresh();
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  struct Case
  {
    bcs::AddBall::Response response;
    const char* field;
  };
  const Case balls[] = {
      {addBall(nan, 0.5, 0, 0, 0.1, 1), "position"}, {addBall(1, 0.5, inf, 0, 0.1, 1), "velocity"},
      {addBall(1, 0.5, 0, 0, 0, 1), "radius"},       {addBall(1, 0.5, 0, 0, -0.1, 1), "radius"},
      {addBall(1, 0.5, 0, 0, 0.1, 0), "mass"},       {addBall(1, 0.5, 0, 0, 1e300, 1), "radius"},
      {addBall(0.5, 0, 0, 0, 0.1, 1), "position"},   // overlaps ball 2
      {addBall(1.95, 0.5, 0, 0, 0.1, 1), "position"},  // overlaps a wall
      {addBall(5, 0.5, 0, 0, 0.1, 1), "position"},     // off the floor
  };
  for (const Case& c : balls)
  {
    EXPECT_FALSE(c.response.success) << c.field;
    EXPECT_EQ(c.response.message.rfind(c.field, 0), 0u) << c.response.message;
  }
  const auto parallel = addWall(0, 0, 1, 0, 2, 0, 0);
  EXPECT_FALSE(parallel.success);
  EXPECT_EQ(parallel.message.rfind("v", 0), 0u) << parallel.message;
  const auto zero = addWall(0, 0, 0, 0, 0, 0, 1);
  EXPECT_FALSE(zero.success);
  EXPECT_EQ(zero.message.rfind("u", 0), 0u) << zero.message;
  const auto through = addWall(-0.763, -1, 0, 2, 0, 0, 0.3);  // across ball 1
  EXPECT_FALSE(through.success);
  EXPECT_EQ(through.message.rfind("point", 0), 0u) << through.message;
  EXPECT_FALSE(remove("ball", 42).success);
  EXPECT_FALSE(remove("wall", -1).success);
  // the world is exactly as if nothing had been asked
  const auto after = statesAfter(30);
  ASSERT_EQ(after.balls.size(), reference.balls.size());
  for (std::size_t i = 0; i < after.balls.size(); ++i)
  {
    EXPECT_EQ(after.balls[i].pose.position.x, reference.balls[i].pose.position.x);
    EXPECT_EQ(after.balls[i].pose.position.y, reference.balls[i].pose.position.y);
    EXPECT_EQ(after.balls[i].twist.linear.x, reference.balls[i].twist.linear.x);
  }
}

TEST(Node, ResetRestoresTheLoadedScene)
{
  fresh();
  const auto first = statesAfter(1);
  addBall(1.2, 0.5, 0, 0, 0.1, 2);
  step(80);
  reset();
  const auto again = statesAfter(1);
  ASSERT_EQ(again.balls.size(), 2u);
  ASSERT_EQ(first.balls.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i)
  {
    EXPECT_EQ(again.balls[i].id, first.balls[i].id);
    EXPECT_EQ(again.balls[i].pose.position.x, first.balls[i].pose.position.x);
    EXPECT_EQ(again.balls[i].twist.linear.x, first.balls[i].twist.linear.x);
  }
  EXPECT_NEAR(again.header.stamp.toSec(), kDt, 1e-9);
}

TEST(Node, MarkersShowFloorWallsAndOneStableIdPerBall)
{
  fresh();
  Inbox<visualization_msgs::MarkerArray> markers("/ball_sim/markers");
  waitConnected(markers);
  // a new subscriber is sent the whole scene
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  auto arrays = markers.take();
  int floors = 0, walls = 0;
  std::vector<int> ball_ids;
  for (const auto& array : arrays)
    for (const auto& m : array.markers)
    {
      if (m.ns == "floor")
      {
        ++floors;
        EXPECT_EQ(m.type, visualization_msgs::Marker::TRIANGLE_LIST);
        EXPECT_FALSE(m.points.empty());
        EXPECT_EQ(m.points.size() % 3, 0u);
      }
      if (m.ns == "walls")
        ++walls;
      if (m.ns == "balls")
      {
        ball_ids.push_back(m.id);
        EXPECT_EQ(m.type, visualization_msgs::Marker::SPHERE);
        EXPECT_NEAR(m.scale.x, 0.25, 1e-12);
        EXPECT_EQ(m.header.frame_id, "world");
      }
    }
  EXPECT_EQ(floors, 1);
  EXPECT_EQ(walls, 4);
  EXPECT_EQ(ball_ids, (std::vector<int>{1, 2}));
  // coloured by speed on a scale up to the fastest ball at the start (ball 1, 1.5 m/s):
  // ball 1 at the top (yellow), ball 2 (0.5 m/s) a third of the way, blue toward magenta
  for (const auto& m : arrays.back().markers)
  {
    if (m.ns == "balls" && m.id == 1)
    {
      EXPECT_FLOAT_EQ(m.color.r, 1.0f);
      EXPECT_FLOAT_EQ(m.color.g, 0.85f);
      EXPECT_FLOAT_EQ(m.color.b, 0.1f);
    }
    if (m.ns == "balls" && m.id == 2)
    {
      EXPECT_NEAR(m.color.r, 0.2 + 0.7 * 2 / 3.0, 1e-6);
      EXPECT_NEAR(m.color.g, 0.35 - 0.2 * 2 / 3.0, 1e-6);
      EXPECT_NEAR(m.color.b, 1.0 - 0.35 * 2 / 3.0, 1e-6);
    }
  }
  // a step moves the balls under the same ids, and sends no floor again
  step(10);
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  arrays = markers.take();
  for (const auto& m : arrays.back().markers)
  {
    EXPECT_EQ(m.ns, "balls");
    if (m.id == 1)
    {
      EXPECT_NEAR(m.pose.position.x, -0.763 + 1.5 * 0.1, 1e-9);
    }
  }
  // removing a ball deletes its marker; reset clears everything first
  const auto added = addBall(1.2, 0.5, 0, 0, 0.1, 2);
  remove("ball", added.id);
  ASSERT_TRUE(markers.waitFor([&](const auto& all) {
    for (const auto& a : all)
      for (const auto& m : a.markers)
        if (m.ns == "balls" && m.id == added.id && m.action == visualization_msgs::Marker::DELETE)
          return true;
    return false;
  }));
  markers.take();
  reset();
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  EXPECT_EQ(markers.take().front().markers.front().action, visualization_msgs::Marker::DELETEALL);
}

namespace
{
/// The collision flashes among the marker arrays.
std::vector<visualization_msgs::Marker> flashesIn(const std::vector<visualization_msgs::MarkerArray>& arrays)
{
  std::vector<visualization_msgs::Marker> out;
  for (const auto& array : arrays)
    for (const auto& m : array.markers)
      if (m.ns == "collisions")
        out.push_back(m);
  return out;
}
}  // namespace

// A collision flashes briefly at its contact point, on the markers topic.
TEST(Node, CollisionFlashesAtTheContactPoint)
{
  fresh();
  Inbox<visualization_msgs::MarkerArray> markers("/ball_sim/markers");
  waitConnected(markers);
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  markers.take();
  step(45);  // before the impact: no flash
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  EXPECT_TRUE(flashesIn(markers.take()).empty());
  step(15);  // through the impact at t = 0.5065 s
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !flashesIn(all).empty(); }));
  const auto flashes = flashesIn(markers.take());
  ASSERT_EQ(flashes.size(), 1u);
  // the balls touch at x = -0.763 + 1.5 t + 0.125, on the line of centres at z = r
  EXPECT_NEAR(flashes[0].pose.position.x, -0.763 + 1.5 * kImpactTime + 0.125, 1e-9);
  EXPECT_NEAR(flashes[0].pose.position.y, 0.0, 1e-12);
  EXPECT_NEAR(flashes[0].pose.position.z, 0.125, 1e-12);
  EXPECT_EQ(flashes[0].lifetime, ros::Duration(0.3));
  EXPECT_EQ(flashes[0].type, visualization_msgs::Marker::SPHERE);
  EXPECT_EQ(flashes[0].header.frame_id, "world");
  EXPECT_NEAR(flashes[0].header.stamp.toSec(), 60 * kDt, 1e-9);
}

// collision_flashes: false (the second node of node.test): the same collision, no flash.
TEST(Node, NoFlashesWhenSwitchedOff)
{
  ASSERT_TRUE(ros::service::waitForService("/noflash_sim/step", ros::Duration(20.0)));
  Inbox<visualization_msgs::MarkerArray> markers("/noflash_sim/markers");
  Inbox<bcs::CollisionEvent> collisions("/noflash_sim/collisions");
  waitConnected(markers);
  waitConnected(collisions);
  ASSERT_TRUE(markers.waitFor([](const auto& all) { return !all.empty(); }));
  bcs::Step srv;
  srv.request.steps = 60;
  ASSERT_TRUE(call("/noflash_sim/step", srv).response.success) << srv.response.message;
  // the collision happened (it is on the collisions topic) ...
  ASSERT_TRUE(collisions.waitFor([](const auto& all) { return !all.empty(); }));
  EXPECT_NEAR(collisions.take().at(0).header.stamp.toSec(), kImpactTime, 1e-9);
  // ... and the markers sent after it carry the balls but no flash
  ASSERT_TRUE(markers.waitFor([](const auto& all) {
    for (const auto& a : all)
      for (const auto& m : a.markers)
        if (m.ns == "balls" && std::abs(m.header.stamp.toSec() - 60 * kDt) < 1e-9)
          return true;
    return false;
  }));
  EXPECT_TRUE(flashesIn(markers.take()).empty());
}

// The node's ball states (paused, stepped through the service, recorded to a bag) are
// the offline tool's, to the last bit.
TEST(Node, StatesMatchTheOfflineToolsBagBitForBit)
{
  const std::string dir = "/tmp/bcs_test_node_" + std::to_string(getpid());
  std::system(("mkdir -p " + dir).c_str());
  const std::string offline = dir + "/offline.bag", recorded = dir + "/node.bag";
  const std::string command = std::string(BCS_SIMULATE_EXE) + " " + BCS_TEST_DATA_DIR +
                              "/node_scene.yaml --duration 0.8 --bag " + offline + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  fresh();
  Inbox<bcs::BallStateArray> states("/ball_sim/ball_states");
  waitConnected(states);
  // a new subscriber is sent the present at once; the run starts after it
  ASSERT_TRUE(states.waitFor([](const auto& all) { return !all.empty(); }));
  states.take();
  reset();  // publishes the states at t = 0
  step(80);
  ASSERT_TRUE(states.waitFor([](const auto& all) { return all.size() >= 81; }));
  {
    rosbag::Bag bag(recorded, rosbag::bagmode::Write);
    for (const auto& msg : states.take())
      bag.write("/ball_sim/ball_states", std::max(msg.header.stamp, ros::TIME_MIN), msg);
  }

  auto read = [](const std::string& path) {
    std::vector<bcs::BallStateArray> out;
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ball_sim/ball_states")))
      out.push_back(*m.instantiate<bcs::BallStateArray>());
    return out;
  };
  auto a = read(offline), b = read(recorded);
  ASSERT_EQ(a.size(), 81u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    ASSERT_EQ(a[k].header.stamp, b[k].header.stamp) << k;
    ASSERT_EQ(a[k].balls.size(), b[k].balls.size()) << k;
    // serialised, the two messages are the same bytes (but for the sequence number
    // that roscpp's publisher stamps on every header)
    a[k].header.seq = b[k].header.seq = 0;
    const ros::SerializedMessage x = ros::serialization::serializeMessage(a[k]);
    const ros::SerializedMessage y = ros::serialization::serializeMessage(b[k]);
    ASSERT_EQ(x.num_bytes, y.num_bytes) << k;
    EXPECT_EQ(std::memcmp(x.buf.get(), y.buf.get(), x.num_bytes), 0) << "step " << k;
  }
  std::system(("rm -rf " + dir).c_str());
}

// rviz's "Publish Point" adds a ball on the floor under the click.
TEST(Node, ClickedPointAddsABallOnTheFloor)
{
  fresh();
  ros::NodeHandle nh;
  ros::Publisher clicks = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 1);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (clicks.getNumSubscribers() == 0 && ros::WallTime::now() < end)
    ros::WallDuration(0.01).sleep();
  geometry_msgs::PointStamped click;
  click.header.frame_id = "world";
  click.point.x = 1.3;
  click.point.y = -0.4;
  click.point.z = 0.0;  // on the floor's surface
  clicks.publish(click);
  bcs::BallStateArray states;
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(5.0);
  do
    states = statesAfter(1);
  while (states.balls.size() < 3 && ros::WallTime::now() < until);
  ASSERT_EQ(states.balls.size(), 3u);
  EXPECT_EQ(states.balls[2].id, 3);
  EXPECT_NEAR(states.balls[2].pose.position.x, 1.3, 1e-12);
  EXPECT_NEAR(states.balls[2].pose.position.y, -0.4, 1e-12);
  // (click_radius above the floor: the scene's most common ball's, 0.125 m, where it
  // sets none)
  EXPECT_NEAR(states.balls[2].pose.position.z, 0.125, 1e-12);
  // a click in another frame is ignored
  click.header.frame_id = "map";
  clicks.publish(click);
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(statesAfter(1).balls.size(), 3u);
}

// The parameter-server reader and the YAML reader give the same scene from one file.
TEST(SceneParams, SameSceneAsTheYamlReader)
{
  for (const char* name : {"default", "billiards", "bowl", "newtons_cradle", "random_gas"})
  {
    const bcs::yaml::SceneFile params = bcs::bridge::loadSceneParams(ros::NodeHandle(std::string("/scenes/") + name));
    const bcs::yaml::SceneFile file = bcs::yaml::loadValidSceneFile(std::string(BCS_CONFIG_DIR) + "/" + name + ".yaml");
    const bcs::core::Scene& from_params = params.scene;
    const bcs::core::Scene& from_yaml = file.scene;
    EXPECT_EQ(from_params.dt, from_yaml.dt) << name;
    EXPECT_EQ(from_params.gravity, from_yaml.gravity) << name;
    EXPECT_EQ(from_params.restitution, from_yaml.restitution) << name;
    EXPECT_EQ(from_params.walls.size(), from_yaml.walls.size()) << name;
    EXPECT_EQ(params.node.real_time_factor, file.node.real_time_factor) << name;
    std::vector<std::string> a = params.node_keys, b = file.node_keys;  // (the parameter server sorts them)
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << name;
    // every ball, explicit or random, to the bit
    EXPECT_EQ(bcs::core::World(from_params).stateHash(), bcs::core::World(from_yaml).stateHash()) << name;
  }
}

// A bad scene stops the node at start with one message naming the key, exit code 1.
namespace
{
/// Starts the node under `name` (its parameters come from node.test) and checks that it
/// stops at once: exit code 1 and a FATAL line containing `expected`.
void expectNodeStopsAtStart(const std::string& name, const std::string& expected)
{
  const std::string command = std::string(BCS_SIMULATOR_NODE_EXE) + " __name:=" + name + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    output += buffer;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  EXPECT_NE(output.find("FATAL"), std::string::npos) << output;
  EXPECT_NE(output.find(expected), std::string::npos) << output;
}
}  // namespace

TEST(SceneParams, BadSceneStopsTheNode)
{
  expectNodeStopsAtStart("bad_sim", "balls[0].radius: must be > 0");
}

// A bad node setting stops the node the same way, with one message naming the key.
TEST(SceneParams, BadBallColorStopsTheNode)
{
  expectNodeStopsAtStart("bad_color_sim", "ball_color: expected speed, id or motion, got the string \"fast\"");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  if (!ros::service::waitForService("/ball_sim/step", ros::Duration(20.0)))
  {
    ADD_FAILURE() << "the node's services did not come up";
    return 1;
  }
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
