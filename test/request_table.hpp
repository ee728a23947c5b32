// The node's answers to requests, called directly (bridge/requests.hpp) on the world of
// test/data/node_scene.yaml, and a table of bad requests: each is answered `success: false`
// with a message that starts with the field's name and gives the reason, and the world is
// bit-identical afterwards (balls, walls and the ids still to be given).
#pragma once

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

namespace ball_collision_sim::test::requests
{
namespace bcs = ball_collision_sim;
using bcs::core::World;

inline constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// test/data/node_scene.yaml: a flat floor [-2, 2] x [-1, 1] inside four walls 0.3 m
/// high (ids 1..4), ball 1 (r 0.125) at (-0.763, 0), ball 2 (r 0.125) at (0.5, 0).
inline World nodeWorld()
{
  return World(bcs::yaml::loadValidScene(std::string(BCS_TEST_DATA_DIR) + "/node_scene.yaml"));
}

/// The exact bits of the balls, the walls and the number of balls and walls.
inline std::uint64_t fingerprint(const World& world)
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

inline bcs::AddBall::Request ballRequest(double x, double y, double z, double vx, double vy, double vz, double radius,
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

inline bcs::AddBall::Request placement(bcs::AddBall::Request req, std::uint8_t value)
{
  req.placement = value;
  return req;
}

inline bcs::AddBall::Request asGiven(const bcs::AddBall::Request& req)
{
  return placement(req, bcs::AddBall::Request::AS_GIVEN);
}

/// A good ball: at (1.2, 0.5) on the floor, clear of everything.
inline bcs::AddBall::Request goodBall()
{
  return ballRequest(1.2, 0.5, 0.1, 0.3, 0, 0, 0.1, 1);
}

inline bcs::AddWall::Request wallRequest(double px, double py, double pz, double ux, double uy, double uz, double vx,
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
inline bcs::AddWall::Request goodWall()
{
  return wallRequest(1.5, -0.9, 0, 0, 0.8, 0, 0, 0, 0.3);
}

inline Answer addBall(World& world, const bcs::AddBall::Request& req, int max_balls = 100)
{
  bcs::AddBall::Response res;
  bcs::bridge::answerAddBall(world, max_balls, req, res);
  return {res.success != 0, res.message, res.id};
}

inline Answer addWall(World& world, const bcs::AddWall::Request& req)
{
  bcs::AddWall::Response res;
  bcs::bridge::answerAddWall(world, req, res);
  return {res.success != 0, res.message, res.id};
}

inline Answer removeBall(World& world, int id)
{
  bcs::RemoveObject::Request req;
  req.id = id;
  bcs::RemoveObject::Response res;
  bcs::bridge::answerRemoveBall(world, req, res);
  return {res.success != 0, res.message};
}

inline Answer removeWall(World& world, int id)
{
  bcs::RemoveObject::Request req;
  req.id = id;
  bcs::RemoveObject::Response res;
  bcs::bridge::answerRemoveWall(world, req, res);
  return {res.success != 0, res.message};
}

/// A set_ball_state request that moves ball `id` to (x, y, z) with velocity (vx, vy, 0).
inline bcs::SetBallState::Request moveRequest(int id, double x, double y, double z, double vx, double vy,
                                              std::uint8_t place = 0)
{
  bcs::SetBallState::Request req;
  req.id = id;
  req.position.x = x;
  req.position.y = y;
  req.position.z = z;
  req.set_position = true;
  req.velocity.x = vx;
  req.velocity.y = vy;
  req.set_velocity = true;
  req.placement = place;
  return req;
}

inline Answer setBallState(World& world, const bcs::SetBallState::Request& req)
{
  bcs::SetBallState::Response res;
  bcs::bridge::answerSetBallState(world, req, res);
  return {res.success != 0, res.message};
}

inline Answer setBallState(World& world, int id, double x, double y, double z, double vx, double vy,
                           std::uint8_t place = 0)
{
  return setBallState(world, moveRequest(id, x, y, z, vx, vy, place));
}

inline Answer applyImpulse(World& world, int id, double jx, double jy, double jz)
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

inline Answer step(World& world, bool paused, std::uint32_t steps)
{
  (void)world;  // a refused step leaves it as it is, which runTable checks
  const std::string why = bcs::bridge::whyNoSteps(paused, steps);
  return {why.empty(), why};
}

struct Row
{
  const char* what;
  std::function<Answer(World&)> call;
  const char* field;        ///< the message starts with "<field>: "
  const char* reason;       ///< ... and contains this
  bool answers_id = false;  ///< add_ball, add_wall: the id answered must be -1
};

inline void runTable(const std::vector<Row>& rows)
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

inline Row ball(const char* what, bcs::AddBall::Request req, const char* field, const char* reason, int max_balls = 100)
{
  return {what, [req, max_balls](World& w) { return addBall(w, req, max_balls); }, field, reason, true};
}

inline Row wall(const char* what, bcs::AddWall::Request req, const char* field, const char* reason)
{
  return {what, [req](World& w) { return addWall(w, req); }, field, reason, true};
}
}  // namespace ball_collision_sim::test::requests
