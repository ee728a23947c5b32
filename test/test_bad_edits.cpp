// The requests that change a ball (set_ball_state, apply_impulse, strike): bad ones, one
// table row each (request_table.hpp), changing nothing; and good ones, which change what
// they give and keep what they leave out. A value a request gives is used or refused,
// never dropped.
#include "request_table.hpp"

#include "ball_collision_sim/ros/conversions.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace ball_collision_sim::test::requests;
using bcs::core::Vec3;

namespace
{
/// `req` with `change` made to it.
template <typename Change>
bcs::SetBallState::Request with(bcs::SetBallState::Request req, Change change)
{
  change(req);
  return req;
}

/// A set_ball_state request naming ball `id` and nothing else.
bcs::SetBallState::Request idOnly(int id)
{
  bcs::SetBallState::Request req;
  req.id = id;
  return req;
}

bcs::SetBallState::Request positionOnly(int id, double x, double y)
{
  bcs::SetBallState::Request req = idOnly(id);
  req.position.x = x;
  req.position.y = y;
  req.set_position = true;
  return req;
}

bcs::SetBallState::Request velocityOnly(int id, double vx, double vy, double vz)
{
  bcs::SetBallState::Request req = idOnly(id);
  req.velocity.x = vx;
  req.velocity.y = vy;
  req.velocity.z = vz;
  req.set_velocity = true;
  return req;
}

bcs::SetBallState::Request spinOnly(int id, double wx, double wy, double wz)
{
  bcs::SetBallState::Request req = idOnly(id);
  req.angular_velocity.x = wx;
  req.angular_velocity.y = wy;
  req.angular_velocity.z = wz;
  req.set_angular_velocity = true;
  return req;
}

Row set(const char* what, const bcs::SetBallState::Request& req, const char* field, const char* reason)
{
  return {what, [req](World& w) { return setBallState(w, req); }, field, reason};
}

Answer strike(World& world, int id, const Vec3& impulse, const Vec3& offset)
{
  bcs::Strike::Request req;
  req.id = id;
  req.impulse = bcs::bridge::toVector3(impulse);
  req.offset = bcs::bridge::toVector3(offset);
  bcs::Strike::Response res;
  bcs::bridge::answerStrike(world, req, res);
  return {res.success != 0, res.message};
}

/// node_scene.yaml's world with friction: sliding 0.2, rolling 0.01.
World frictionWorld()
{
  bcs::core::Scene scene = bcs::yaml::loadValidScene(std::string(BCS_TEST_DATA_DIR) + "/node_scene.yaml");
  scene.friction.emplace();
  scene.friction->sliding = 0.2;
  scene.friction->rolling = 0.01;
  return World(scene);
}
}  // namespace

TEST(BadRequests, SetBallState)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return setBallState(w, 0, 1.2, 0.5, 0.1, 0, 0); }, "id",
       "missing (0 names no object"},
      {"unknown id", [](World& w) { return setBallState(w, 3, 1.2, 0.5, 0.1, 0, 0); }, "id", "no ball has id 3"},
      {"negative id", [](World& w) { return setBallState(w, -2, 1.2, 0.5, 0.1, 0, 0); }, "id", "must be >= 1"},
      {"position NaN", [](World& w) { return setBallState(w, 1, kNan, 0.5, 0.1, 0, 0); }, "position", "must be finite"},
      {"velocity inf", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.1, kInf, 0); }, "velocity",
       "must be finite"},
      {"onto ball 2", [](World& w) { return setBallState(w, 1, 0.55, 0.05, 0.1, 0, 0); }, "position",
       "overlaps ball 2"},
      {"into wall 4", [](World& w) { return setBallState(w, 1, 1.95, 0.5, 0.1, 0, 0); }, "position", "overlaps wall 4"},
      {"off the floor", [](World& w) { return setBallState(w, 2, 2.5, 0.5, 0.1, 0, 0); }, "position", "off the floor"},
      {"AS_GIVEN below", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.05, 0, 0, 1); }, "position",
       "below the floor"},
      {"AS_GIVEN off the floor", [](World& w) { return setBallState(w, 1, 2.5, 0.5, 0.5, 0, 0, 1); }, "position",
       "off the floor"},
      {"placement 9", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.1, 0, 0, 9); }, "placement",
       "must be 0 (ON_FLOOR) or 1 (AS_GIVEN), got 9"},
      // a value given is used or refused, never dropped; a request that sets nothing is refused
      set("position without set_position",
          with(moveRequest(1, 1.2, 0.5, 0.1, 0, 0), [](auto& r) { r.set_position = false; }), "position",
          "given, but set_position is false"),
      set("velocity without set_velocity",
          with(moveRequest(1, 1.2, 0.5, 0.1, 0.3, 0), [](auto& r) { r.set_velocity = false; }), "velocity",
          "given, but set_velocity is false"),
      set("angular_velocity {y: 5} without its flag",
          with(velocityOnly(1, 0.2, 0, 0), [](auto& r) { r.angular_velocity.y = 5; }), "angular_velocity",
          "given, but set_angular_velocity is false"),
      set("position NaN without its flag", with(idOnly(1), [](auto& r) { r.position.y = kNan; }), "position",
          "given, but set_position is false"),
      set("nothing to set", idOnly(1), "set_position, set_velocity, set_angular_velocity, inertia", "nothing to set"),
      set("nothing to set, AS_GIVEN",
          with(idOnly(1), [](auto& r) { r.placement = bcs::SetBallState::Request::AS_GIVEN; }),
          "set_position, set_velocity, set_angular_velocity, inertia", "nothing to set"),
      // without friction a ball keeps no spin of its own, and its k plays no part
      set("a spin without friction", spinOnly(1, 0, 5, 0), "angular_velocity", "the scene has no friction"),
      set("inertia without friction", with(idOnly(1), [](auto& r) { r.inertia = 0.5; }), "inertia",
          "the scene has no friction"),
      // a value alone is checked as it is with the others
      set("velocity alone inf", velocityOnly(2, 0, -kInf, 0), "velocity", "must be finite"),
      set("velocity alone 1e300", velocityOnly(2, 1e300, 0, 0), "velocity", "length must be <= 1e+07 m/s"),
      set("position alone onto ball 2", positionOnly(1, 0.55, 0), "position", "overlaps ball 2"),
  });
}

TEST(BadRequests, ApplyImpulse)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return applyImpulse(w, 0, 1, 0, 0); }, "id",
       "missing (0 names no object"},
      {"unknown id", [](World& w) { return applyImpulse(w, 5, 1, 0, 0); }, "id", "no ball has id 5"},
      {"impulse NaN", [](World& w) { return applyImpulse(w, 1, kNan, 0, 0); }, "impulse", "must be finite"},
      {"impulse past the speed limit", [](World& w) { return applyImpulse(w, 2, 1e300, 0, 0); }, "impulse",
       "a speed of"},
      {"impulse missing (0)", [](World& w) { return applyImpulse(w, 1, 0, 0, 0); }, "impulse", "missing"},
  });
}

TEST(BadRequests, Strike)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return strike(w, 0, Vec3(1, 0, 0), Vec3::Zero()); }, "id",
       "missing (0 names no object"},
      {"unknown id", [](World& w) { return strike(w, 5, Vec3(1, 0, 0), Vec3::Zero()); }, "id", "no ball has id 5"},
      {"impulse missing (0)", [](World& w) { return strike(w, 1, Vec3::Zero(), Vec3::Zero()); }, "impulse", "missing"},
      {"impulse inf", [](World& w) { return strike(w, 1, Vec3(0, kInf, 0), Vec3::Zero()); }, "impulse",
       "must be finite"},
      {"impulse past the speed limit", [](World& w) { return strike(w, 2, Vec3(0, 1e300, 0), Vec3::Zero()); },
       "impulse", "a speed of"},
      // without friction the offset would be lost: the ball keeps no spin
      {"offset without friction", [](World& w) { return strike(w, 1, Vec3(1, 0, 0), Vec3(0, 0, 0.05)); }, "offset",
       "the scene has no friction"},
  });
}

// The same requests done right change the world as asked, and keep the ball's id.
TEST(BadRequests, GoodSetAndPushAreAccepted)
{
  World world = nodeWorld();
  const Answer set = setBallState(world, 2, 1.2, 0.5, 7.0, -0.4, 0.2);  // any height: it lands
  ASSERT_TRUE(set.success) << set.message;
  EXPECT_EQ(world.findBall(2)->position, bcs::core::Vec3(1.2, 0.5, 0.125));
  EXPECT_EQ(world.findBall(2)->velocity, bcs::core::Vec3(-0.4, 0.2, 0));
  const Answer pushed = applyImpulse(world, 2, 3.0, 0, 0);  // ball 2 has 3 kg
  ASSERT_TRUE(pushed.success) << pushed.message;
  EXPECT_EQ(world.findBall(2)->velocity, bcs::core::Vec3(0.6, 0.2, 0));
  EXPECT_EQ(world.balls().size(), 2u);
}

// AS_GIVEN takes the centre and the velocity as given: 0.5 m above the floor the ball
// flies, and its state says so.
TEST(BadRequests, AsGivenAboveTheFloorFlies)
{
  World world = nodeWorld();
  bcs::AddBall::Response added;
  bcs::bridge::answerAddBall(world, 100, asGiven(ballRequest(1.2, 0.5, 0.6, 0.3, 0, 1.5, 0.1, 1)), added);
  ASSERT_TRUE(added.success) << added.message;
  ASSERT_EQ(added.id, 3);
  EXPECT_EQ(world.findBall(3)->position, bcs::core::Vec3(1.2, 0.5, 0.6));
  EXPECT_EQ(world.findBall(3)->velocity, bcs::core::Vec3(0.3, 0, 1.5));  // the part off the floor kept
  EXPECT_EQ(bcs::bridge::ballState(world, 3).motion, bcs::BallState::FLYING);

  bcs::SetBallState::Request req;
  req.id = 2;
  req.position.x = -1.2;
  req.position.y = 0.5;
  req.position.z = 0.625;  // radius 0.125: 0.5 m clear of the floor
  req.set_position = true;
  req.velocity.x = -0.2;
  req.set_velocity = true;
  req.placement = bcs::SetBallState::Request::AS_GIVEN;
  bcs::SetBallState::Response set;
  bcs::bridge::answerSetBallState(world, req, set);
  ASSERT_TRUE(set.success) << set.message;
  EXPECT_EQ(world.findBall(2)->position, bcs::core::Vec3(-1.2, 0.5, 0.625));
  EXPECT_EQ(world.findBall(2)->velocity, bcs::core::Vec3(-0.2, 0, 0));
  EXPECT_EQ(set.state.motion, bcs::BallState::FLYING);
  EXPECT_EQ(set.state.pose.position.z, 0.625);

  // resting exactly on the floor and not moving off it, AS_GIVEN is not flying
  bcs::AddBall::Response resting;
  bcs::bridge::answerAddBall(world, 100, asGiven(ballRequest(0.5, -0.6, 0.1, 0.3, 0, 0, 0.1, 1)), resting);
  ASSERT_TRUE(resting.success) << resting.message;
  EXPECT_NE(bcs::bridge::ballState(world, resting.id).motion, bcs::BallState::FLYING);
}

// A request that leaves a field out keeps it, bit for bit: the place of a ball given only
// a velocity, the velocity of one given only a place; with friction, the place, velocity
// and spin of one given only its k, and the velocity of one given only a spin.
TEST(BadRequests, SetBallStateKeepsWhatItLeavesOut)
{
  World world = nodeWorld();
  world.step();
  const Vec3 p1 = world.findBall(1)->position, v2 = world.findBall(2)->velocity;
  const Answer faster = setBallState(world, velocityOnly(1, 2.5, 0, 0));
  ASSERT_TRUE(faster.success) << faster.message;
  EXPECT_EQ(world.findBall(1)->position, p1);
  EXPECT_EQ(world.findBall(1)->velocity, Vec3(2.5, 0, 0));
  const Answer moved = setBallState(world, positionOnly(2, 1.2, 0.5));
  ASSERT_TRUE(moved.success) << moved.message;
  EXPECT_EQ(world.findBall(2)->position, Vec3(1.2, 0.5, 0.125));
  EXPECT_EQ(world.findBall(2)->velocity, v2);

  World rough = frictionWorld();
  rough.step();
  const bcs::BallState before = bcs::bridge::ballState(rough, 1);
  ASSERT_NE(before.twist.angular.y, 0.0);
  bcs::SetBallState::Response hollow;
  bcs::bridge::answerSetBallState(rough, with(idOnly(1), [](auto& r) { r.inertia = 2.0 / 3; }), hollow);
  ASSERT_TRUE(hollow.success) << hollow.message;
  EXPECT_EQ(hollow.state.inertia, 2.0 / 3);
  EXPECT_EQ(hollow.state.pose, before.pose);
  EXPECT_EQ(hollow.state.twist, before.twist);
  bcs::SetBallState::Response spun;
  bcs::bridge::answerSetBallState(rough, spinOnly(1, 0, 0, 3), spun);
  ASSERT_TRUE(spun.success) << spun.message;
  EXPECT_EQ(spun.state.twist.linear, before.twist.linear);
  EXPECT_EQ(spun.state.twist.angular.x, 0.0);
  EXPECT_EQ(spun.state.twist.angular.y, 0.0);
  EXPECT_EQ(spun.state.twist.angular.z, 3.0);
  EXPECT_EQ(spun.state.pose.position, before.pose.position);
}
