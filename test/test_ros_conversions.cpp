// Conversions between the core and ROS messages, and the parameter tree's YAML text.
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/ros/markers.hpp"
#include "ball_collision_sim/ros/outputs.hpp"
#include "ball_collision_sim/ros/scene_param.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  const core::Scene scene = yaml::parseScene(bridge::toYaml(tree), "params");
  EXPECT_EQ(scene.dt, 0.005);
  EXPECT_EQ(scene.restitution, 1.0);
  EXPECT_EQ(scene.frame_id, "map \"x\"");
  EXPECT_TRUE(scene.node.start_paused);
  EXPECT_EQ(scene.gravity.z(), -9.81);

  // a real where an integer is expected stays a real, and is refused
  XmlRpc::XmlRpcValue bad;
  bad["tf_max_balls"] = 3.0;
  EXPECT_THROW(yaml::parseScene(bridge::toYaml(bad), "params"), yaml::SceneError);
  // NaN survives the trip, for validate() to refuse
  XmlRpc::XmlRpcValue nan;
  nan["dt"] = std::nan("");
  EXPECT_TRUE(std::isnan(yaml::parseScene(bridge::toYaml(nan), "params").dt));
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

TEST(Conversions, BallStateAndTransform)
{
  core::Ball ball;
  ball.id = 7;
  ball.radius = 0.2;
  ball.mass = 3;
  ball.position = core::Vec3(1, 2, 0.2);
  ball.velocity = core::Vec3(0.5, 0, 0);
  ball.orientation = core::Quat(Eigen::AngleAxisd(0.3, core::Vec3::UnitY()));
  ball.angular_velocity = core::Vec3(0, 2.5, 0);
  const auto msg = bridge::toMsg(ball);
  EXPECT_EQ(msg.id, 7);
  EXPECT_EQ(msg.pose.position.y, 2);
  EXPECT_EQ(msg.twist.angular.y, 2.5);
  EXPECT_NEAR(msg.pose.orientation.w, std::cos(0.15), 1e-15);
  const auto tf = bridge::toTransform(ball, "world", ros::Time(1.5));
  EXPECT_EQ(tf.child_frame_id, "ball_7");
  EXPECT_EQ(tf.header.frame_id, "world");
  EXPECT_EQ(tf.header.stamp, ros::Time(1.5));
  EXPECT_EQ(tf.transform.translation.x, 1);
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
  for (const auto& p : m.points)
    lowest = std::min(lowest, p.z);
  EXPECT_NEAR(lowest, -0.1, 1e-12);  // a quarter of the centre point's depth, at the centre

  const core::Wall wall(5, core::WallDef{core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 0, 1), {}}, 1.0);
  const auto w = bridge::wallMarker(wall, "world");
  EXPECT_EQ(w.id, 5);
  EXPECT_EQ(w.points.size(), 12u);
  EXPECT_LT(w.color.a, 1.0f);
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
  const auto single = bridge::ballMarkers(world, "world", ros::Time(1.0), 5);
  ASSERT_EQ(single.markers.size(), 5u);
  EXPECT_EQ(single.markers[3].type, visualization_msgs::Marker::SPHERE);
  EXPECT_EQ(single.markers[3].id, 3);

  const auto lists = bridge::ballMarkers(world, "world", ros::Time(1.0), 4);
  ASSERT_EQ(lists.markers.size(), 2u);  // radii 0.1 and 0.2
  EXPECT_EQ(lists.markers[0].type, visualization_msgs::Marker::SPHERE_LIST);
  EXPECT_EQ(lists.markers[0].ns, bridge::kBallListsNs);
  EXPECT_NEAR(lists.markers[0].scale.x, 0.2, 1e-15);
  EXPECT_EQ(lists.markers[0].points.size(), 2u);
  EXPECT_EQ(lists.markers[1].points.size(), 3u);
  EXPECT_EQ(lists.markers[1].colors.size(), 3u);
  EXPECT_NEAR(lists.markers[1].points[1].x, -1.5 + 0.7 * 2, 1e-12);
}
