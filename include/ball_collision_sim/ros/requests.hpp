#pragma once

#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/ApplyImpulse.h>
#include <ball_collision_sim/Strike.h>
#include <ball_collision_sim/GetState.h>
#include <ball_collision_sim/LoadScene.h>
#include <ball_collision_sim/LostBall.h>
#include <ball_collision_sim/PocketedBall.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/SetBallState.h>
#include <ball_collision_sim/Step.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ball_collision_sim::bridge
{
/// The answers of the node's services, without the publishing that follows a change, so
/// that they can be tested without a master. A bad request answers `success: false` with a
/// message that starts with the field's name and says why, and changes nothing.

/// Most steps one step call may ask for: a bound on how long one call runs.
constexpr std::uint32_t kMaxStepsPerCall = 1000000;

/// Why `id` names no object, or "": ids start at core::kFirstId, so 0, the value of a
/// field a request leaves out, names nothing.
std::string checkId(int id);

/// The core's landing for a request's `placement` field (ON_FLOOR or AS_GIVEN); nullopt,
/// with `error` set, for any other value.
std::optional<core::Landing> landingOf(std::uint8_t placement, std::string& error);

/// Why no ball may be added now (the world holds max_balls), or "".
std::string roomForABall(const core::World& world, int max_balls);

void answerAddBall(core::World& world, int max_balls, const AddBall::Request& req, AddBall::Response& res);
void answerAddWall(core::World& world, const AddWall::Request& req, AddWall::Response& res);
void answerRemoveBall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res);
void answerRemoveWall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res);
void answerSetBallState(core::World& world, const SetBallState::Request& req, SetBallState::Response& res);
void answerApplyImpulse(core::World& world, const ApplyImpulse::Request& req, ApplyImpulse::Response& res);
/// A strike: impulse at an offset from the centre (core::World::strike()).
void answerStrike(core::World& world, const Strike::Request& req, Strike::Response& res);
/// Why `steps` steps may not run now (not paused, or out of range), or "".
std::string whyNoSteps(bool paused, std::uint32_t steps);

/// A ball that left the world, for ~lost_balls, stamped with the world's time.
LostBall lostBallMessage(const core::LostBall& gone, const std::string& frame_id, double time);
/// The message of a ball that dropped into a pocket, stamped with the drop's time.
PocketedBall pocketedMessage(const core::PocketedBall& dropped, const std::string& frame_id);

/// The world now, for get_state.
void answerGetState(const core::World& world, bool paused, const std::string& frame_prefix, GetState::Response& res);
/// BallState of ball `id` (which must exist).
BallState ballState(const core::World& world, int id);

/// The scene a load_scene request names, read and validated: from `path` (absolute,
/// relative to the node's working directory, or package://PACKAGE/PATH) or from `yaml`,
/// exactly one of them. Throws yaml::SceneError with the field or key and the reason.
yaml::SceneFile sceneOfRequest(const LoadScene::Request& req);
}  // namespace ball_collision_sim::bridge
