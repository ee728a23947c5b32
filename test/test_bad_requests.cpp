// Every service of the node that adds or removes an object, and step, with bad
// requests, one table row each (request_table.hpp): the answer is `success: false` with a
// message that starts with the field's name and gives the reason, and the world is
// bit-identical afterwards. The node's answers are called directly, so no master is
// needed; test_node checks the same services through ROS. test_bad_edits.cpp has the
// requests that change a ball.
#include "request_table.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace ball_collision_sim::test::requests;

namespace
{
/// `req` with a spin of `w` [rad/s] about y, its flag as given.
bcs::AddBall::Request spun(bcs::AddBall::Request req, double w, bool set_angular_velocity)
{
  req.angular_velocity.y = w;
  req.set_angular_velocity = set_angular_velocity;
  return req;
}

bcs::AddBall::Request withInertia(bcs::AddBall::Request req, double inertia)
{
  req.inertia = inertia;
  return req;
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
      // a value is used or refused, never dropped: a spin without its flag; and the scene
      // has no friction, where a ball keeps no spin of its own and k plays no part
      ball("angular_velocity without its flag", spun(goodBall(), 5, false), "angular_velocity",
           "given, but set_angular_velocity is false"),
      ball("angular_velocity NaN without its flag", spun(goodBall(), kNan, false), "angular_velocity",
           "given, but set_angular_velocity is false"),
      ball("a spin without friction", spun(goodBall(), 5, true), "angular_velocity", "the scene has no friction"),
      ball("hollow without friction", withInertia(goodBall(), 2.0 / 3), "inertia", "the scene has no friction"),
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
