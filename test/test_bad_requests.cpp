// Every service of the node with bad requests, one table row each: the answer is
// `success: false` with a message that starts with the field's name and gives the reason,
// and the world is bit-identical afterwards (balls, walls and the ids still to be given).
// The node's answers are called directly (bridge/requests.hpp), so no master is needed;
// test_node checks the same services through ROS.
#include "ball_collision_sim/core/state_hash.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/requests.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace bcs = ball_collision_sim;
using bcs::core::World;

namespace
{
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// test/data/node_scene.yaml: a flat floor [-2, 2] x [-1, 1] inside four walls 0.3 m
/// high (ids 1..4), ball 1 (r 0.125) at (-0.763, 0), ball 2 (r 0.125) at (0.5, 0).
World nodeWorld()
{
  return World(bcs::yaml::loadValidScene(std::string(BCS_TEST_DATA_DIR) + "/node_scene.yaml"));
}

/// The exact bits of the balls, the walls and the number of balls and walls.
std::uint64_t fingerprint(const World& world)
{
  bcs::core::Fnv1a h;
  h.add(world.stateHash());
  h.add(world.walls().size());
  for (const bcs::core::Wall& wall : world.walls())
  {
    h.add(wall.id);
    h.add(wall.def.point.data(), 3 * sizeof(double));
    h.add(wall.def.u.data(), 3 * sizeof(double));
    h.add(wall.def.v.data(), 3 * sizeof(double));
    h.add(wall.restitution);
  }
  return h.value();
}

struct Answer
{
  bool success;
  std::string message;
  int id = -1;  ///< add_ball, add_wall: the id answered
};

bcs::AddBall::Request ballRequest(double x, double y, double z, double vx, double vy, double vz, double radius,
                                  double mass)
{
  bcs::AddBall::Request req;
  req.position.x = x;
  req.position.y = y;
  req.position.z = z;
  req.velocity.x = vx;
  req.velocity.y = vy;
  req.velocity.z = vz;
  req.radius = radius;
  req.mass = mass;
  return req;
}

bcs::AddBall::Request placement(bcs::AddBall::Request req, std::uint8_t value)
{
  req.placement = value;
  return req;
}

bcs::AddBall::Request asGiven(const bcs::AddBall::Request& req)
{
  return placement(req, bcs::AddBall::Request::AS_GIVEN);
}

/// A good ball: at (1.2, 0.5) on the floor, clear of everything.
bcs::AddBall::Request goodBall()
{
  return ballRequest(1.2, 0.5, 0.1, 0.3, 0, 0, 0.1, 1);
}

bcs::AddWall::Request wallRequest(double px, double py, double pz, double ux, double uy, double uz, double vx,
                                  double vy, double vz)
{
  bcs::AddWall::Request req;
  req.point.x = px;
  req.point.y = py;
  req.point.z = pz;
  req.u.x = ux;
  req.u.y = uy;
  req.u.z = uz;
  req.v.x = vx;
  req.v.y = vy;
  req.v.z = vz;
  return req;
}

/// A good wall: 0.8 m across the floor at x = 1.5, clear of both balls.
bcs::AddWall::Request goodWall()
{
  return wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 0, 0.3);
}

Answer addBall(World& world, const bcs::AddBall::Request& req, int max_balls = 100)
{
  bcs::AddBall::Response res;
  bcs::bridge::answerAddBall(world, max_balls, req, res);
  return {res.success != 0, res.message, res.id};
}

Answer addWall(World& world, const bcs::AddWall::Request& req)
{
  bcs::AddWall::Response res;
  bcs::bridge::answerAddWall(world, req, res);
  return {res.success != 0, res.message, res.id};
}

Answer removeBall(World& world, int id)
{
  bcs::RemoveObject::Request req;
  req.id = id;
  bcs::RemoveObject::Response res;
  bcs::bridge::answerRemoveBall(world, req, res);
  return {res.success != 0, res.message};
}

Answer removeWall(World& world, int id)
{
  bcs::RemoveObject::Request req;
  req.id = id;
  bcs::RemoveObject::Response res;
  bcs::bridge::answerRemoveWall(world, req, res);
  return {res.success != 0, res.message};
}

Answer setBallState(World& world, int id, double x, double y, double z, double vx, double vy, std::uint8_t place = 0)
{
  bcs::SetBallState::Request req;
  req.id = id;
  req.position.x = x;
  req.position.y = y;
  req.position.z = z;
  req.velocity.x = vx;
  req.velocity.y = vy;
  req.placement = place;
  bcs::SetBallState::Response res;
  bcs::bridge::answerSetBallState(world, req, res);
  return {res.success != 0, res.message};
}

Answer applyImpulse(World& world, int id, double jx, double jy, double jz)
{
  bcs::ApplyImpulse::Request req;
  req.id = id;
  req.impulse.x = jx;
  req.impulse.y = jy;
  req.impulse.z = jz;
  bcs::ApplyImpulse::Response res;
  bcs::bridge::answerApplyImpulse(world, req, res);
  return {res.success != 0, res.message};
}

Answer step(World& world, bool paused, std::uint32_t steps)
{
  (void)world;  // a refused step leaves it as it is, which runTable checks
  const std::string why = bcs::bridge::whyNoSteps(paused, steps);
  return {why.empty(), why};
}

struct Row
{
  const char* what;
  std::function<Answer(World&)> call;
  const char* field;   ///< the message starts with "<field>: "
  const char* reason;  ///< ... and contains this
  bool answers_id = false;  ///< add_ball, add_wall: the id answered must be -1
};

void runTable(const std::vector<Row>& rows)
{
  for (const Row& row : rows)
  {
    SCOPED_TRACE(row.what);
    World world = nodeWorld();
    world.step();  // not at t = 0: a bad request must not reset anything either
    const std::uint64_t before = fingerprint(world);
    const Answer answer = row.call(world);
    EXPECT_FALSE(answer.success);
    EXPECT_EQ(answer.message.rfind(std::string(row.field) + ": ", 0), 0u) << answer.message;
    EXPECT_NE(answer.message.find(row.reason), std::string::npos) << answer.message;
    EXPECT_EQ(answer.message.find('\n'), std::string::npos) << answer.message;
    if (row.answers_id)
    {
      EXPECT_EQ(answer.id, -1);
    }
    EXPECT_EQ(fingerprint(world), before) << "the world changed";
    // no id was used up: the next good ball and wall get the ids they would have had
    EXPECT_EQ(addBall(world, goodBall()).id, 3);
    EXPECT_EQ(addWall(world, goodWall()).id, 5);
  }
}

Row ball(const char* what, bcs::AddBall::Request req, const char* field, const char* reason, int max_balls = 100)
{
  return {what, [req, max_balls](World& w) { return addBall(w, req, max_balls); }, field, reason, true};
}

Row wall(const char* what, bcs::AddWall::Request req, const char* field, const char* reason)
{
  return {what, [req](World& w) { return addWall(w, req); }, field, reason, true};
}
}  // namespace

TEST(BadRequests, GoodRequestsAreAccepted)
{
  // the rows below differ from these in one field each
  World world = nodeWorld();
  const Answer b = addBall(world, goodBall());
  EXPECT_TRUE(b.success) << b.message;
  const Answer w = addWall(world, goodWall());
  EXPECT_TRUE(w.success) << w.message;
  EXPECT_TRUE(removeBall(world, b.id).success);
  EXPECT_TRUE(removeWall(world, w.id).success);
  EXPECT_TRUE(step(world, true, 1).success);
  EXPECT_TRUE(step(world, true, bcs::bridge::kMaxStepsPerCall).success);
}

TEST(BadRequests, AddBall)
{
  runTable({
      ball("position.x NaN", ballRequest(kNan, 0.5, 0.1, 0, 0, 0, 0.1, 1), "position", "must be finite"),
      ball("position.z inf", ballRequest(1.2, 0.5, kInf, 0, 0, 0, 0.1, 1), "position", "must be finite"),
      ball("position.y -inf", ballRequest(1.2, -kInf, 0.1, 0, 0, 0, 0.1, 1), "position", "must be finite"),
      ball("position 1e300", ballRequest(1e300, 0.5, 0.1, 0, 0, 0, 0.1, 1), "position", "length must be <= 1e+06 m"),
      ball("velocity.y NaN", ballRequest(1.2, 0.5, 0.1, 0, kNan, 0, 0.1, 1), "velocity", "must be finite"),
      ball("velocity.x -inf", ballRequest(1.2, 0.5, 0.1, -kInf, 0, 0, 0.1, 1), "velocity", "must be finite"),
      ball("velocity 1e300", ballRequest(1.2, 0.5, 0.1, 0, 0, 1e300, 0.1, 1), "velocity", "length must be <= 1e+07 m/s"),
      ball("radius 0", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0, 1), "radius", "must be > 0"),
      ball("radius -0.1", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, -0.1, 1), "radius", "must be > 0"),
      ball("radius NaN", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, kNan, 1), "radius", "must be finite"),
      ball("radius inf", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, kInf, 1), "radius", "must be finite"),
      ball("radius 1e300", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 1e300, 1), "radius", "must be <= 1e+06 m"),
      ball("radius 1e-320 (denormal)", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 1e-320, 1), "radius", "must be >= 1e-06 m"),
      ball("mass 0", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, 0), "mass", "must be > 0"),
      ball("mass -1", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, -1), "mass", "must be > 0"),
      ball("mass NaN", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, kNan), "mass", "must be finite"),
      ball("mass inf", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, kInf), "mass", "must be finite"),
      ball("mass 1e300", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, 1e300), "mass", "must be <= 1e+12 kg"),
      ball("mass 1e-320 (denormal)", ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, 1e-320), "mass", "must be >= 1e-12 kg"),
      ball("overlaps ball 2", ballRequest(0.6, 0.1, 0.1, 0, 0, 0, 0.1, 1), "position", "overlaps ball 2 by"),
      ball("on top of ball 1", ballRequest(-0.763, 0, 0.125, 0, 0, 0, 0.125, 1), "position", "overlaps ball 1 by"),
      ball("overlaps wall 4", ballRequest(1.95, 0.5, 0.1, 0, 0, 0, 0.1, 1), "position", "overlaps wall 4 by"),
      ball("off the floor in x", ballRequest(5, 0.5, 0.1, 0, 0, 0, 0.1, 1), "position", "off the floor"),
      ball("off the floor in y", ballRequest(1.2, -3, 0.1, 0, 0, 0, 0.1, 1), "position", "off the floor"),
      ball("AS_GIVEN below the floor", asGiven(ballRequest(1.2, 0.5, -1, 0, 0, 0, 0.1, 1)), "position",
           "below the floor"),
      ball("AS_GIVEN sunk into the floor", asGiven(ballRequest(1.2, 0.5, 0.05, 0, 0, 0, 0.1, 1)), "position",
           "below the floor"),
      ball("placement 2", placement(ballRequest(1.2, 0.5, 0.1, 0, 0, 0, 0.1, 1), 2), "placement",
           "must be 0 (ON_FLOOR) or 1 (AS_GIVEN), got 2"),
      ball("max_balls reached", goodBall(), "max_balls", "already holds 2 balls", 2),
  });
}

TEST(BadRequests, AddWall)
{
  runTable({
      wall("point NaN", wallRequest(kNan, -0.9, 0, 0, 0.8, 0, 0, 0, 0.3), "point", "must be finite"),
      wall("point 1e300", wallRequest(1.5, 1e300, 0, 0, 0.8, 0, 0, 0, 0.3), "point", "length must be <= 1e+06 m"),
      wall("u inf", wallRequest(1.5, -0.9, 0, 0, kInf, 0, 0, 0, 0.3), "u", "must be finite"),
      wall("v NaN", wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 0, kNan), "v", "must be finite"),
      wall("u 1e300", wallRequest(1.5, -0.9, 0, 0, 1e300, 0, 0, 0, 0.3), "u", "length must be <= 1e+06 m"),
      wall("u zero", wallRequest(1.5, -0.9, 0, 0, 0, 0, 0, 0, 0.3), "u", "must be non-zero"),
      wall("v zero", wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 0, 0), "v", "must be non-zero"),
      wall("u and v zero", wallRequest(1.5, -0.9, 0, 0, 0, 0, 0, 0, 0), "u", "must be non-zero"),
      wall("u 1e-200 (squares underflow)", wallRequest(1.5, -0.9, 0, 0, 1e-200, 0, 0, 0, 0.3), "u",
           "length must be >= 1e-06 m"),
      wall("v parallel to u", wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 1.6, 0), "v", "parallel to u"),
      wall("v against u", wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, -0.2, 0), "v", "parallel to u"),
      wall("v all but parallel", wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 0.8, 1e-12), "v", "parallel to u"),
      wall("through ball 1", wallRequest(-0.763, -0.9, 0, 0, 1.8, 0, 0, 0, 0.3), "point", "cuts through ball 1"),
      wall("through ball 2 edgewise", wallRequest(0.5, 0, 0, 0.5, 0, 0, 0, 0, 0.3), "point", "cuts through ball 2"),
  });
}

TEST(BadRequests, RemoveBall)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return removeBall(w, 0); }, "id", "missing (0 names no object"},
      {"unknown id 42", [](World& w) { return removeBall(w, 42); }, "id", "no ball has id 42"},
      {"negative id", [](World& w) { return removeBall(w, -1); }, "id", "must be >= 1 (got -1)"},
      {"largest id", [](World& w) { return removeBall(w, std::numeric_limits<std::int32_t>::max()); }, "id",
       "no ball has id 2147483647"},
      {"smallest id", [](World& w) { return removeBall(w, std::numeric_limits<std::int32_t>::min()); }, "id",
       "must be >= 1 (got -2147483648)"},
      {"the next id, not given yet", [](World& w) { return removeBall(w, 3); }, "id", "no ball has id 3"},
      {"a wall's id", [](World& w) { return removeBall(w, 4); }, "id", "no ball has id 4"},
  });
}

TEST(BadRequests, RemoveWall)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return removeWall(w, 0); }, "id", "missing (0 names no object"},
      {"unknown id 5", [](World& w) { return removeWall(w, 5); }, "id", "no wall has id 5"},
      {"negative id", [](World& w) { return removeWall(w, -1); }, "id", "must be >= 1 (got -1)"},
      {"largest id", [](World& w) { return removeWall(w, std::numeric_limits<std::int32_t>::max()); }, "id",
       "no wall has id 2147483647"},
      {"smallest id", [](World& w) { return removeWall(w, std::numeric_limits<std::int32_t>::min()); }, "id",
       "must be >= 1 (got -2147483648)"},
  });
}

TEST(BadRequests, RemovedOnceIsGone)
{
  World world = nodeWorld();
  ASSERT_TRUE(removeBall(world, 1).success);
  ASSERT_TRUE(removeWall(world, 2).success);
  const std::uint64_t before = fingerprint(world);
  const Answer ball = removeBall(world, 1);
  EXPECT_FALSE(ball.success);
  EXPECT_EQ(ball.message, "id: no ball has id 1");
  const Answer wall = removeWall(world, 2);
  EXPECT_FALSE(wall.success);
  EXPECT_EQ(wall.message, "id: no wall has id 2");
  EXPECT_EQ(fingerprint(world), before);
}

TEST(BadRequests, SetBallState)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return setBallState(w, 0, 1.2, 0.5, 0.1, 0, 0); }, "id",
       "missing (0 names no object"},
      {"unknown id", [](World& w) { return setBallState(w, 3, 1.2, 0.5, 0.1, 0, 0); }, "id", "no ball has id 3"},
      {"negative id", [](World& w) { return setBallState(w, -2, 1.2, 0.5, 0.1, 0, 0); }, "id", "must be >= 1"},
      {"position NaN", [](World& w) { return setBallState(w, 1, kNan, 0.5, 0.1, 0, 0); }, "position", "must be finite"},
      {"velocity inf", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.1, kInf, 0); }, "velocity", "must be finite"},
      {"onto ball 2", [](World& w) { return setBallState(w, 1, 0.55, 0.05, 0.1, 0, 0); }, "position", "overlaps ball 2"},
      {"into wall 4", [](World& w) { return setBallState(w, 1, 1.95, 0.5, 0.1, 0, 0); }, "position", "overlaps wall 4"},
      {"off the floor", [](World& w) { return setBallState(w, 2, 2.5, 0.5, 0.1, 0, 0); }, "position", "off the floor"},
      {"AS_GIVEN below", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.05, 0, 0, 1); }, "position",
       "below the floor"},
      {"AS_GIVEN off the floor", [](World& w) { return setBallState(w, 1, 2.5, 0.5, 0.5, 0, 0, 1); }, "position",
       "off the floor"},
      {"placement 9", [](World& w) { return setBallState(w, 1, 1.2, 0.5, 0.1, 0, 0, 9); }, "placement",
       "must be 0 (ON_FLOOR) or 1 (AS_GIVEN), got 9"},
  });
}

TEST(BadRequests, ApplyImpulse)
{
  runTable({
      {"empty request (id 0)", [](World& w) { return applyImpulse(w, 0, 1, 0, 0); }, "id", "missing (0 names no object"},
      {"unknown id", [](World& w) { return applyImpulse(w, 5, 1, 0, 0); }, "id", "no ball has id 5"},
      {"impulse NaN", [](World& w) { return applyImpulse(w, 1, kNan, 0, 0); }, "impulse", "must be finite"},
      {"impulse past the speed limit", [](World& w) { return applyImpulse(w, 2, 1e300, 0, 0); }, "impulse",
       "a speed of"},
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
  req.velocity.x = -0.2;
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

TEST(BadRequests, Step)
{
  runTable({
      {"zero steps", [](World& w) { return step(w, true, 0); }, "steps", "must be in 1..1000000 (got 0)"},
      {"one too many", [](World& w) { return step(w, true, bcs::bridge::kMaxStepsPerCall + 1); }, "steps",
       "must be in 1..1000000 (got 1000001)"},
      {"largest count", [](World& w) { return step(w, true, std::numeric_limits<std::uint32_t>::max()); }, "steps",
       "(got 4294967295)"},
      {"while running", [](World& w) { return step(w, false, 1); }, "steps", "only while paused"},
  });
}
