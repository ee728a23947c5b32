#pragma once

#include "ball_collision_sim/core/world.hpp"

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/Step.h>

#include <cstdint>
#include <string>

namespace ball_collision_sim::bridge
{
/// The answers of the node's services, without the publishing that follows a change, so
/// that they can be tested without a master. A bad request answers `success: false` with a
/// message that starts with the field's name and says why, and changes nothing.

/// Most steps one step call may ask for: a bound on how long the node stays busy.
constexpr std::uint32_t kMaxStepsPerCall = 1000000;

/// Why no ball may be added now (the world holds max_balls), or "".
std::string roomForABall(const core::World& world, int max_balls);

void answerAddBall(core::World& world, int max_balls, const AddBall::Request& req, AddBall::Response& res);
void answerAddWall(core::World& world, const AddWall::Request& req, AddWall::Response& res);
void answerRemoveBall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res);
void answerRemoveWall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res);
/// Whether `req.steps` steps may run now; when not, `res` says why (and has the time).
bool acceptStep(const core::World& world, bool paused, const Step::Request& req, Step::Response& res);
}  // namespace ball_collision_sim::bridge
