// Conversions between the core and ROS messages, and the parameter tree's YAML text.
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/rate_limit.hpp"
#include "ball_collision_sim/ros/run_bag.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>
#include <vector>

using namespace ball_collision_sim;

TEST(ToYaml, KeepsTypesSoTheReaderJudgesThemAlike)
{
  XmlRpc::XmlRpcValue tree;
  tree["dt"] = 0.005;
  tree["restitution"] = 1;  // an integer where a real is expected: accepted
  tree["frame_id"] = std::string("map \"x\"");
  tree["start_paused"] = true;
  tree["gravity"][0] = 0.0;
  tree["gravity"][1] = 0.0;
  tree["gravity"][2] = -9.81;
  const yaml::SceneFile file = yaml::parseSceneFile(bridge::toYaml(tree), "params");
  const core::Scene& scene = file.scene;
  EXPECT_EQ(scene.dt, 0.005);
  EXPECT_EQ(scene.restitution, 1.0);
  EXPECT_EQ(scene.frame_id, "map \"x\"");
  EXPECT_TRUE(file.node.start_paused);
  EXPECT_EQ(scene.gravity.z(), -9.81);

  // a real where an integer is expected stays a real, and is refused
  XmlRpc::XmlRpcValue bad;
  bad["tf_max_balls"] = 3.0;
  EXPECT_THROW(yaml::parseScene(bridge::toYaml(bad), "params"), yaml::SceneError);
  // NaN survives the trip, for validate() to refuse
  XmlRpc::XmlRpcValue nan;
  nan["dt"] = std::nan("");
  EXPECT_TRUE(std::isnan(yaml::parseScene(bridge::toYaml(nan), "params").dt));
  // rosparam (YAML 1.1) leaves `dt: 1e-3` and `-.5` as strings; YAML 1.2 and `simulate`
  // read numbers, and so does the node. A string YAML 1.1 reads as a number was quoted
  // in the file, and stays a string (refused where a number is expected).
  const auto readDt = [](const std::string& text) {
    XmlRpc::XmlRpcValue params;
    params["dt"] = text;
    return yaml::parseScene(bridge::toYaml(params), "params").dt;
  };
  EXPECT_EQ(readDt("1e-3"), 1e-3);
  EXPECT_EQ(readDt("1.5e3"), 1.5e3);
  EXPECT_EQ(readDt("+.5"), 0.5);
  EXPECT_THROW(readDt("0.01"), yaml::SceneError);
  EXPECT_THROW(readDt("2.5E-3"), yaml::SceneError);
  EXPECT_THROW(readDt("1e"), yaml::SceneError);
  EXPECT_THROW(readDt("1e-3 s"), yaml::SceneError);
  // unknown keys are named
  XmlRpc::XmlRpcValue unknown;
  unknown["dtt"] = 0.1;
  try
  {
    yaml::parseScene(bridge::toYaml(unknown), "params");
    FAIL() << "accepted an unknown key";
  }
  catch (const yaml::SceneError& e)
  {
    EXPECT_NE(std::string(e.what()).find("dtt: unknown key"), std::string::npos) << e.what();
  }
}

// Flight's fields from the parameter server: its strings come through toYaml quoted, its
// reals as reals; a scene written to it reads back with the same fields.
TEST(ToYaml, ReadsFloorRestitutionAndBallPlacement)
{
  XmlRpc::XmlRpcValue tree;
  tree["floor"]["type"] = std::string("plane");
  tree["floor"]["restitution"] = 0.25;
  XmlRpc::XmlRpcValue ball;
  ball["position"][0] = 0.0;
  ball["position"][1] = 0.0;
  ball["position"][2] = 0.6;
  ball["radius"] = 0.1;
  ball["placement"] = std::string("as_given");
  tree["balls"][0] = ball;
  ball["position"][0] = 1.0;
  ball["placement"] = std::string("on_floor");
  tree["balls"][1] = ball;
  // the floor's restitution 0.25, the first ball as given, the second on the floor
  const auto expectFlight = [](const core::Scene& s) {
    ASSERT_TRUE(s.floor.has_value());
    EXPECT_EQ(s.floor->restitution, 0.25);
    ASSERT_EQ(s.balls.size(), 2u);
    EXPECT_EQ(s.balls[0].placement, core::BallPlacement::kAsGiven);
    EXPECT_EQ(s.balls[1].placement, core::BallPlacement::kOnFloor);
  };
  const core::Scene scene = yaml::parseScene(bridge::toYaml(tree), "params");
  expectFlight(scene);

  tree["balls"][1]["placement"] = std::string("x");
  try
  {
    yaml::parseScene(bridge::toYaml(tree), "params");
    FAIL() << "accepted placement x";
  }
  catch (const yaml::SceneError& e)
  {
    EXPECT_EQ(std::string(e.what()), "params: balls[1].placement: expected on_floor or as_given, got the string \"x\"");
  }

  // writeSceneParams' path: the written scene, as the parameter server holds it, and back
  XmlRpc::XmlRpcValue written = bridge::toXmlRpc(yaml::writeScene(scene, NodeSettings()));
  const core::Scene back = yaml::parseScene(bridge::toYaml(written), "params");
  expectFlight(back);
  ASSERT_EQ(back.balls.size(), 2u);
  EXPECT_EQ(back.balls[0].position, scene.balls[0].position);
}

TEST(Conversions, BallStateAndTransform)
{
  core::Ball ball;
  ball.id = 7;
  ball.radius = 0.2;
  ball.mass = 3;
  ball.position = core::Vec3(1, 2, 0.2);
  ball.velocity = core::Vec3(0.5, 0, 0);
  ball.orientation = core::Quat(Eigen::AngleAxisd(0.3, core::Vec3::UnitY()));
  const auto msg = bridge::toMsg(ball, core::Vec3(0, 2.5, 0), core::MotionKind::kSpinning, core::kHollowInertia);
  EXPECT_EQ(msg.id, 7);
  EXPECT_EQ(msg.motion, ball_collision_sim::BallState::SPINNING);
  EXPECT_EQ(msg.inertia, 2.0 / 3);
  EXPECT_EQ(msg.pose.position.y, 2);
  EXPECT_EQ(msg.twist.angular.y, 2.5);
  EXPECT_NEAR(msg.pose.orientation.w, std::cos(0.15), 1e-15);
  const auto tf = bridge::toTransform(ball, "world", ros::Time(1.5));
  EXPECT_EQ(tf.child_frame_id, "ball_7");
  EXPECT_EQ(tf.header.frame_id, "world");
  EXPECT_EQ(tf.header.stamp, ros::Time(1.5));
  EXPECT_EQ(tf.transform.translation.x, 1);
}

TEST(Conversions, TransitionStampIsItsExactTime)
{
  core::MotionTransition transition;
  transition.time = 1.2345678901;
  transition.ball = 4;
  transition.from = core::MotionKind::kSliding;
  transition.to = core::MotionKind::kRolling;
  const auto msg = bridge::toMsg(transition, "table");
  EXPECT_EQ(msg.header.stamp, ros::Time(1.2345678901));
  EXPECT_EQ(msg.header.frame_id, "table");
  EXPECT_EQ(msg.ball, 4);
  EXPECT_EQ(msg.before, ball_collision_sim::BallState::SLIDING);
  EXPECT_EQ(msg.after, ball_collision_sim::BallState::ROLLING);
}

TEST(Conversions, CollisionStampIsTheTimeOfImpact)
{
  core::CollisionEvent event;
  event.kind = core::CollisionEvent::Kind::kBallWall;
  event.time = 12.345678901;
  event.ball = 3;
  event.other = 1;
  event.feature = core::WallFeature::kCorner;
  const auto msg = bridge::toMsg(event, "world");
  EXPECT_NEAR(msg.header.stamp.toSec(), 12.345678901, 1e-9);
  EXPECT_EQ(msg.kind, msg.BALL_WALL);
  EXPECT_EQ(msg.feature, msg.CORNER);
  EXPECT_EQ(msg.other, 1);
}

TEST(Markers, FloorMeshFollowsTheSurfaceAndWallsShowBothSides)
{
  core::FloorDef def;
  def.type = core::FloorDef::Type::kBiquadratic;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      def.control_points[i][j] = core::Vec3(i - 1.0, j - 1.0, (i == 1 && j == 1) ? -0.4 : 0.0);
  const core::Floor floor(def, core::Vec3(0, 0, -9.81));
  const auto m = bridge::floorMarker(floor, "world", 8);
  ASSERT_EQ(m.points.size(), 8u * 8u * 6u);
  ASSERT_EQ(m.colors.size(), m.points.size());
  double lowest = 0;
  std::size_t low = 0, high = 0;
  for (std::size_t k = 0; k < m.points.size(); ++k)
  {
    lowest = std::min(lowest, m.points[k].z);
    low = m.points[k].z < m.points[low].z ? k : low;
    high = m.points[k].z > m.points[high].z ? k : high;
  }
  EXPECT_NEAR(lowest, -0.1, 1e-12);  // a quarter of the centre point's depth, at the centre
  // shaded by height: the lowest point dark green-blue, the highest light
  EXPECT_FLOAT_EQ(m.colors[low].g, 0.35f);
  EXPECT_FLOAT_EQ(m.colors[high].g, 0.75f);
  EXPECT_LT(m.colors[low].r + m.colors[low].g + m.colors[low].b,
            m.colors[high].r + m.colors[high].g + m.colors[high].b);

  const core::Wall wall(5, core::WallDef{core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 0, 1), {}}, 1.0);
  const auto w = bridge::wallMarker(wall, "world");
  EXPECT_EQ(w.id, 5);
  ASSERT_EQ(w.points.size(), 6u);
  // a colour per vertex (rviz draws it unlit, from both sides), translucent everywhere
  ASSERT_EQ(w.colors.size(), w.points.size());
  for (std::size_t k = 0; k < w.colors.size(); ++k)
  {
    EXPECT_LE(w.colors[k].a * w.color.a, 0.45f) << k;
    EXPECT_GT(w.colors[k].a * w.color.a, 0.1f) << k;
  }
  EXPECT_GT(w.colors[0].a, w.colors[2].a);  // clearer toward the top (point + v)
}

TEST(Markers, ManyBallsAreDrawnAsOneSphereListPerRadius)
{
  core::Scene scene;
  core::FloorDef floor;
  scene.floor = floor;  // the default 4 m x 4 m plane at z = 0
  for (int k = 0; k < 5; ++k)
  {
    core::BallDef b;
    b.radius = k % 2 ? 0.1 : 0.2;
    b.position = core::Vec3(-1.5 + 0.7 * k, 0, b.radius);
    scene.balls.push_back(b);
  }
  const core::World world(scene);
  const auto single = bridge::ballMarkers(world, "world", ros::Time(1.0), 5, bridge::BallColoring());
  ASSERT_EQ(single.markers.size(), 5u);
  EXPECT_EQ(single.markers[3].type, visualization_msgs::Marker::SPHERE);
  EXPECT_EQ(single.markers[3].id, 4);  // the fourth ball: ids start at 1

  const auto lists = bridge::ballMarkers(world, "world", ros::Time(1.0), 4, bridge::BallColoring());
  ASSERT_EQ(lists.markers.size(), 2u);  // radii 0.1 and 0.2
  EXPECT_EQ(lists.markers[0].type, visualization_msgs::Marker::SPHERE_LIST);
  EXPECT_EQ(lists.markers[0].ns, bridge::kBallListsNs);
  EXPECT_NEAR(lists.markers[0].scale.x, 0.2, 1e-15);
  EXPECT_EQ(lists.markers[0].points.size(), 2u);
  EXPECT_EQ(lists.markers[1].points.size(), 3u);
  EXPECT_EQ(lists.markers[1].colors.size(), 3u);
  EXPECT_NEAR(lists.markers[1].points[1].x, -1.5 + 0.7 * 2, 1e-12);
}

namespace
{
core::Ball ballMoving(int id, double speed)
{
  core::Ball ball;
  ball.id = id;
  ball.velocity = core::Vec3(0.6, 0.8, 0.0) * speed;
  return ball;
}

bool sameColor(const std_msgs::ColorRGBA& a, const std_msgs::ColorRGBA& b)
{
  return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
}

/// A floor with walls and two balls that meet head-on at t = 0.5065 s (the rostest's scene).
core::Scene headOnScene()
{
  core::Scene scene;
  core::FloorDef floor;
  floor.point = core::Vec3(-2, -1, 0);
  floor.u = core::Vec3(4, 0, 0);
  floor.v = core::Vec3(0, 2, 0);
  scene.floor = floor;
  core::BallDef a, b;
  a.position = core::Vec3(-0.763, 0, 0.125);
  a.velocity = core::Vec3(1.5, 0, 0);
  a.radius = 0.125;
  b.position = core::Vec3(0.5, 0, 0.125);
  b.velocity = core::Vec3(-0.5, 0, 0);
  b.radius = 0.125;
  b.mass = 3;
  scene.balls = {a, b};
  return scene;
}
}  // namespace

TEST(BallColors, BySpeedFromBlueThroughMagentaToYellow)
{
  bridge::BallColoring coloring;
  coloring.mode = BallColor::kSpeed;
  coloring.speed_max = 2.0;
  const auto still = bridge::ballColor(ballMoving(0, 0.0), coloring);
  const auto slow = bridge::ballColor(ballMoving(0, 0.5), coloring);
  const auto middle = bridge::ballColor(ballMoving(0, 1.0), coloring);
  const auto fast = bridge::ballColor(ballMoving(0, 2.0), coloring);
  // the ends and the middle of the scale, exactly
  EXPECT_FLOAT_EQ(still.r, 0.2f);
  EXPECT_FLOAT_EQ(still.g, 0.35f);
  EXPECT_FLOAT_EQ(still.b, 1.0f);
  EXPECT_FLOAT_EQ(middle.r, 0.9f);
  EXPECT_FLOAT_EQ(middle.g, 0.15f);
  EXPECT_FLOAT_EQ(middle.b, 0.65f);
  EXPECT_FLOAT_EQ(fast.r, 1.0f);
  EXPECT_FLOAT_EQ(fast.g, 0.85f);
  EXPECT_FLOAT_EQ(fast.b, 0.1f);
  // a quarter of the way: halfway from blue to magenta
  EXPECT_FLOAT_EQ(slow.r, 0.55f);
  EXPECT_FLOAT_EQ(slow.b, 0.825f);
  EXPECT_EQ(fast.a, 1.0f);
  // a fast ball and a slow one differ; faster than the top of the scale is the top
  EXPECT_FALSE(sameColor(slow, fast));
  EXPECT_TRUE(sameColor(bridge::ballColor(ballMoving(0, 50.0), coloring), fast));
  // never green: green is the floor's colour
  for (double v = 0; v <= 2.0; v += 0.05)
  {
    const auto c = bridge::ballColor(ballMoving(0, v), coloring);
    EXPECT_FALSE(c.g > c.r && c.g > c.b) << v;
  }
  // the colour goes into the marker
  EXPECT_TRUE(sameColor(bridge::ballMarker(ballMoving(4, 2.0), "world", ros::Time(1), coloring).color, fast));
}

TEST(BallColors, ByIdDoNotChangeWithSpeed)
{
  bridge::BallColoring coloring;
  coloring.mode = BallColor::kId;
  coloring.speed_max = 2.0;
  const auto still = bridge::ballColor(ballMoving(3, 0.0), coloring);
  EXPECT_TRUE(sameColor(still, bridge::ballColor(ballMoving(3, 1.9), coloring)));
  EXPECT_TRUE(sameColor(still, bridge::ballColor(ballMoving(3, 40.0), coloring)));
  // neighbouring ids differ clearly
  const auto next = bridge::ballColor(ballMoving(4, 0.0), coloring);
  EXPECT_GT(std::abs(still.r - next.r) + std::abs(still.g - next.g) + std::abs(still.b - next.b), 0.5f);
}

TEST(BallColors, SpeedScaleFromTheSettingsOrTheFastestBall)
{
  core::Scene scene = headOnScene();
  NodeSettings node;
  // speed_color_max 0: the fastest ball at the start, 1.5 m/s
  bridge::BallColoring coloring = bridge::ballColoring(core::World(scene), node);
  EXPECT_EQ(coloring.mode, BallColor::kSpeed);
  EXPECT_DOUBLE_EQ(coloring.speed_max, 1.5);
  node.speed_color_max = 4.0;
  node.ball_color = BallColor::kId;
  coloring = bridge::ballColoring(core::World(scene), node);
  EXPECT_EQ(coloring.mode, BallColor::kId);
  EXPECT_DOUBLE_EQ(coloring.speed_max, 4.0);
  // every ball still: 1 m/s, not a division by zero
  node.speed_color_max = 0.0;
  for (core::BallDef& b : scene.balls)
    b.velocity = core::Vec3::Zero();
  EXPECT_DOUBLE_EQ(bridge::ballColoring(core::World(scene), node).speed_max, 1.0);
  // sphere lists (many balls) carry the same colours per point
  core::World world(headOnScene());
  const bridge::BallColoring by_speed = bridge::ballColoring(world, NodeSettings());
  const auto lists = bridge::ballMarkers(world, "world", ros::Time(1.0), 1, by_speed);
  ASSERT_EQ(lists.markers.size(), 1u);
  ASSERT_EQ(lists.markers[0].colors.size(), 2u);
  EXPECT_TRUE(sameColor(lists.markers[0].colors[0], bridge::ballColor(world.balls()[0], by_speed)));
  EXPECT_FALSE(sameColor(lists.markers[0].colors[0], lists.markers[0].colors[1]));
}

TEST(SceneYaml, BallColorSettingsAreCheckedByName)
{
  EXPECT_EQ(yaml::parseSceneFile("ball_color: id").node.ball_color, BallColor::kId);
  EXPECT_EQ(yaml::parseSceneFile("ball_color: speed").node.ball_color, BallColor::kSpeed);
  EXPECT_EQ(yaml::parseSceneFile("{}").node.ball_color, BallColor::kSpeed);
  EXPECT_EQ(yaml::parseSceneFile("speed_color_max: 3").node.speed_color_max, 3.0);
  EXPECT_FALSE(yaml::parseSceneFile("collision_flashes: false").node.collision_flashes);
  EXPECT_TRUE(yaml::parseSceneFile("{}").node.collision_flashes);
  auto error = [](const std::string& text) {
    try
    {
      yaml::parseScene(text, "t.yaml");
    }
    catch (const yaml::SceneError& e)
    {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("ball_color: fast"), "t.yaml: ball_color: expected speed, id or motion, got fast");
  EXPECT_EQ(error("ball_color: [speed]"), "t.yaml: ball_color: expected speed, id or motion, got a list");
  EXPECT_EQ(error("speed_color_max: -1"),
            "t.yaml: speed_color_max: must be in [0, 1e7] m/s (0 = the fastest ball at the start), got -1");
  EXPECT_EQ(error("speed_color_max: .nan"),
            "t.yaml: speed_color_max: must be in [0, 1e7] m/s (0 = the fastest ball at the start), got .nan");
  EXPECT_EQ(error("collision_flashes: 1"), "t.yaml: collision_flashes: expected true or false, got 1");
  // the parameter server's strings come through toYaml quoted, and are read alike
  XmlRpc::XmlRpcValue params;
  params["ball_color"] = std::string("id");
  EXPECT_EQ(yaml::parseSceneFile(bridge::toYaml(params)).node.ball_color, BallColor::kId);
  params["ball_color"] = std::string("fast");
  EXPECT_NE(error(bridge::toYaml(params)).find("ball_color: expected speed, id or motion"), std::string::npos);
}

TEST(CollisionFlashes, AShortLivedSphereAtTheContactPoint)
{
  core::CollisionEvent event;
  event.point = core::Vec3(0.12175, -0.5, 0.125);
  event.time = 0.5065;
  const auto m = bridge::collisionFlash(event, "world", ros::Time(0.51), 17);
  EXPECT_EQ(m.ns, "collisions");
  EXPECT_EQ(m.id, 17);
  EXPECT_EQ(m.type, visualization_msgs::Marker::SPHERE);
  EXPECT_EQ(m.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.header.stamp, ros::Time(0.51));
  EXPECT_EQ(m.pose.position.x, 0.12175);
  EXPECT_EQ(m.pose.position.y, -0.5);
  EXPECT_EQ(m.pose.position.z, 0.125);
  EXPECT_EQ(m.lifetime, ros::Duration(0.3));
  EXPECT_NEAR(m.scale.x, 0.12, 1e-12);
  EXPECT_GT(m.color.a, 0.5f);
}

TEST(CollisionFlashes, CappedPerSetRestingContactsSkippedIdsCycle)
{
  bridge::CollisionFlashes flashes(3);
  std::vector<core::CollisionEvent> events(5);
  for (int k = 0; k < 5; ++k)
    events[k].point = core::Vec3(k, 0, 0);
  events[1].resting = true;  // a ball leaning on something: no flash
  flashes.add(events);
  EXPECT_EQ(flashes.pending(), 3u);
  flashes.add(events);  // full: nothing more until taken
  auto markers = flashes.take("world", ros::Time(2));
  ASSERT_EQ(markers.size(), 3u);
  EXPECT_EQ(markers[0].pose.position.x, 0);
  EXPECT_EQ(markers[1].pose.position.x, 2);  // the resting contact 1 was skipped
  EXPECT_EQ(markers[2].pose.position.x, 3);
  EXPECT_EQ(markers[0].id, 0);
  EXPECT_EQ(markers[2].id, 2);
  EXPECT_EQ(flashes.pending(), 0u);
  EXPECT_TRUE(flashes.take("world", ros::Time(2)).empty());
  // ids go on where they stopped, and wrap after kIdCycle
  flashes.add({events[0]});
  EXPECT_EQ(flashes.take("world", ros::Time(3)).at(0).id, 3);
  for (int k = 4; k < bridge::CollisionFlashes::kIdCycle; ++k)
  {
    flashes.add({events[0]});
    flashes.take("world", ros::Time(3));
  }
  flashes.add({events[0]});
  EXPECT_EQ(flashes.take("world", ros::Time(3)).at(0).id, 0);
  flashes.add(events);
  flashes.clear();
  EXPECT_TRUE(flashes.take("world", ros::Time(4)).empty());
}

// The offline tool's bags carry the flashes like the node's topic, and not when switched off.
TEST(CollisionFlashes, InTheBagAtTheContactPointOnlyWhenSwitchedOn)
{
  for (const bool on : {true, false})
  {
    NodeSettings node;
    node.collision_flashes = on;
    core::World world(headOnScene());
    const std::string path = "/tmp/bcs_flashes_" + std::to_string(getpid()) + (on ? "_on" : "_off") + ".bag";
    {
      bridge::RunBag bag(path, world, node, "{}", 20.0);  // markers every 5 steps
      for (int k = 0; k < 60; ++k)
      {
        world.step();
        bag.afterStep(world);
      }
      bag.close();
    }
    std::vector<visualization_msgs::Marker> flashes;
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ball_sim/markers")))
    {
      const auto array = m.instantiate<visualization_msgs::MarkerArray>();  // kept alive for the loop
      ASSERT_TRUE(array);
      for (const auto& marker : array->markers)
        if (marker.ns == bridge::kCollisionsNs)
        {
          flashes.push_back(marker);
          EXPECT_EQ(m.getTime(), marker.header.stamp);
        }
    }
    bag.close();
    std::remove(path.c_str());
    if (!on)
    {
      EXPECT_TRUE(flashes.empty());
      continue;
    }
    // the one collision, at t = 0.5065 s, is drawn with the set after it (t = 0.55 s)
    ASSERT_EQ(flashes.size(), 1u);
    EXPECT_NEAR(flashes[0].pose.position.x, -0.763 + 1.5 * 0.5065 + 0.125, 1e-9);
    EXPECT_NEAR(flashes[0].pose.position.y, 0.0, 1e-12);
    EXPECT_NEAR(flashes[0].header.stamp.toSec(), 0.55, 1e-9);
    EXPECT_EQ(flashes[0].lifetime, ros::Duration(bridge::kFlashLifetime));
  }
}

// Views go out on the node's timer ticks (10 ms at dt = 0.01 s): 30 Hz is 30 a second,
// not 25 (every fourth tick); a whole number of ticks stays exact; a gap starts the
// count afresh rather than sending a burst; forcing sends at once.
TEST(RateLimit, KeepsTheRateOnTicks)
{
  const auto sends = [](double rate, double tick, double seconds, bridge::RateLimit& limit, double start = 0) {
    int count = 0;
    for (int k = 0; k * tick < seconds - 1e-9; ++k)
      count += limit.due(rate, start + k * tick, false) ? 1 : 0;
    return count;
  };
  bridge::RateLimit thirty, twenty, zero;
  EXPECT_EQ(sends(30, 0.01, 10, thirty), 300);
  EXPECT_EQ(sends(20, 0.01, 10, twenty), 200);
  EXPECT_EQ(sends(0, 0.01, 10, zero), 0);
  // a stall of 2 s, then ticks again: one send at once, then 30 a second, no burst
  EXPECT_TRUE(thirty.due(30, 12.0, false));
  EXPECT_FALSE(thirty.due(30, 12.01, false));
  EXPECT_EQ(sends(30, 0.01, 1, thirty, 12.02), 30);
  // forced: at once, whenever, and the next a period after it
  bridge::RateLimit forced;
  EXPECT_TRUE(forced.due(30, 5.0, false));
  EXPECT_TRUE(forced.due(30, 5.001, true));
  EXPECT_FALSE(forced.due(30, 5.02, false));
  EXPECT_TRUE(forced.due(30, 5.04, false));
}
