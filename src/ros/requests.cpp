#include "ball_collision_sim/ros/requests.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/conversions.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ros/package.h>

namespace ball_collision_sim::bridge
{
std::string checkId(int id)
{
  if (id >= core::kFirstId)
    return "";
  if (id == 0)
    return "id: missing (0 names no object; ids start at " + std::to_string(core::kFirstId) + ")";
  return "id: must be >= " + std::to_string(core::kFirstId) + " (got " + std::to_string(id) + ")";
}

std::optional<core::Landing> landingOf(std::uint8_t placement, std::string& error)
{
  if (placement == AddBall::Request::ON_FLOOR)
    return core::Landing::kUnder;
  if (placement == AddBall::Request::AS_GIVEN)
    return core::Landing::kAsGiven;
  error = "placement: must be 0 (ON_FLOOR) or 1 (AS_GIVEN), got " + std::to_string(placement);
  return std::nullopt;
}

std::string roomForABall(const core::World& world, int max_balls)
{
  if (world.balls().size() < static_cast<std::size_t>(max_balls))
    return "";
  return "max_balls: the world already holds " + std::to_string(world.balls().size()) +
         " balls, the most this node takes (parameter max_balls)";
}

namespace
{
/// Whether a request gives this field: not all 0, the value of a field it leaves out
/// (NaN counts as given).
bool given(const geometry_msgs::Vector3& v)
{
  return v.x != 0 || v.y != 0 || v.z != 0;
}

bool given(const geometry_msgs::Point& p)
{
  return p.x != 0 || p.y != 0 || p.z != 0;
}

/// Why a field is refused that a request gives with its flag false: "<field>: given, but
/// <flag> is false (...; false <what false does>)".
std::string givenWithoutFlag(const std::string& field, const std::string& flag, const std::string& when_false)
{
  return field + ": given, but " + flag + " is false (set " + flag + ": true to use it; false " + when_false + ")";
}

/// Why `world` cannot take a spin or an inertia that a request (add_ball, set_ball_state)
/// gives, or "": without friction a ball keeps no spin of its own, and its moment of
/// inertia plays no part.
template <class Request>
std::string spinWithoutFriction(const core::World& world, const Request& req)
{
  if (world.friction())
    return "";
  if (req.set_angular_velocity)
    return "angular_velocity: the scene has no friction, so a ball keeps no spin of its own (it turns by rolling, "
           "n x v / r): leave set_angular_velocity false";
  if (req.inertia != 0)
    return "inertia: the scene has no friction, so a ball's moment of inertia plays no part: leave it 0";
  return "";
}
}  // namespace

void answerAddBall(core::World& world, int max_balls, const AddBall::Request& req, AddBall::Response& res)
{
  res.id = -1;
  res.success = false;
  const std::optional<core::Landing> landing = landingOf(req.placement, res.message);
  if (!landing)
    return;
  if (!req.set_angular_velocity && given(req.angular_velocity))
  {
    res.message =
        givenWithoutFlag("angular_velocity", "set_angular_velocity", "rolls the ball without slip, n x v / r");
    return;
  }
  res.message = spinWithoutFriction(world, req);
  if (!res.message.empty())
    return;
  if (const std::string full = roomForABall(world, max_balls); !full.empty())
  {
    res.message = full;
    return;
  }
  const core::AddResult result = world.addBall(fromMsg(req), *landing);
  res.success = result.ok;
  res.id = result.id;
  res.message = result.ok ? "added ball " + std::to_string(result.id) : result.error;
}

void answerAddWall(core::World& world, const AddWall::Request& req, AddWall::Response& res)
{
  const core::AddResult result = world.addWall(fromMsg(req));
  res.success = result.ok;
  res.id = result.id;
  res.message = result.ok ? "added wall " + std::to_string(result.id) : result.error;
}

void answerRemoveBall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res)
{
  res.message = checkId(req.id);
  res.success = res.message.empty() && world.removeBall(req.id);
  if (res.message.empty())
    res.message = res.success ? "removed ball " + std::to_string(req.id) : "id: no ball has id " + std::to_string(req.id);
}

void answerRemoveWall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res)
{
  res.message = checkId(req.id);
  res.success = res.message.empty() && world.removeWall(req.id);
  if (res.message.empty())
    res.message = res.success ? "removed wall " + std::to_string(req.id) : "id: no wall has id " + std::to_string(req.id);
}

void answerSetBallState(core::World& world, const SetBallState::Request& req, SetBallState::Response& res)
{
  res.success = false;
  res.message = checkId(req.id);
  if (!res.message.empty())
    return;
  const std::optional<core::Landing> landing = landingOf(req.placement, res.message);
  if (!landing)
    return;
  if (!req.set_position && given(req.position))
    res.message = givenWithoutFlag("position", "set_position", "keeps the ball where it is");
  else if (!req.set_velocity && given(req.velocity))
    res.message = givenWithoutFlag("velocity", "set_velocity", "keeps the ball's velocity");
  else if (!req.set_angular_velocity && given(req.angular_velocity))
    res.message = givenWithoutFlag("angular_velocity", "set_angular_velocity",
                                   "keeps the ball's spin, or with a new velocity rolls it, n x v / r");
  else if (!req.set_position && !req.set_velocity && !req.set_angular_velocity && req.inertia == 0)
    res.message =
        "set_position, set_velocity, set_angular_velocity, inertia: nothing to set (the flags are false "
        "and inertia is 0)";
  else
    res.message = spinWithoutFriction(world, req);
  if (!res.message.empty())
    return;
  core::BallEdit edit;
  edit.landing = *landing;
  if (req.set_position)
    edit.position = toVec3(req.position);
  if (req.set_velocity)
    edit.velocity = toVec3(req.velocity);
  if (req.set_angular_velocity)
    edit.angular_velocity = toVec3(req.angular_velocity);
  if (req.inertia != 0)
    edit.inertia = req.inertia;
  const core::AddResult result = world.setBallState(req.id, edit);
  res.success = result.ok;
  res.message = result.ok ? "ball " + std::to_string(req.id) + " set" : result.error;
  if (result.ok)
    res.state = ballState(world, req.id);
}

void answerApplyImpulse(core::World& world, const ApplyImpulse::Request& req, ApplyImpulse::Response& res)
{
  res.success = false;
  res.message = checkId(req.id);
  if (!res.message.empty())
    return;
  if (!given(req.impulse))
  {
    res.message = "impulse: missing (0 N s would push nothing)";
    return;
  }
  const core::AddResult result = world.applyImpulse(req.id, toVec3(req.impulse));
  res.success = result.ok;
  res.message = result.ok ? "pushed ball " + std::to_string(req.id) : result.error;
  if (result.ok)
    res.state = ballState(world, req.id);
}

void answerStrike(core::World& world, const Strike::Request& req, Strike::Response& res)
{
  res.success = false;
  res.message = checkId(req.id);
  if (!res.message.empty())
    return;
  if (!given(req.impulse))
    res.message = "impulse: missing (0 N s would strike nothing)";
  else if (!world.friction() && given(req.offset))
    res.message =
        "offset: the scene has no friction, so a ball keeps no spin of its own and a strike off its "
        "centre acts as one through it: give offset 0 (or apply_impulse)";
  if (!res.message.empty())
    return;
  const core::AddResult result = world.strike(req.id, toVec3(req.impulse), toVec3(req.offset));
  res.success = result.ok;
  res.message = result.ok ? "struck ball " + std::to_string(req.id) : result.error;
  if (result.ok)
    res.state = ballState(world, req.id);
}

std::string whyNoSteps(bool paused, std::uint32_t steps)
{
  if (!paused)
    return "steps: stepping works only while paused (call pause with data: true first)";
  if (steps < 1 || steps > kMaxStepsPerCall)
    return "steps: must be in 1.." + std::to_string(kMaxStepsPerCall) + " (got " + std::to_string(steps) + ")";
  return "";
}

LostBall lostBallMessage(const core::LostBall& gone, const std::string& frame_id, double time)
{
  LostBall msg;
  msg.header.stamp = ros::Time(time);
  msg.header.frame_id = frame_id;
  msg.ball = toMsg(gone.ball, gone.angular_velocity, gone.motion, gone.inertia);
  msg.reason = gone.reason;
  return msg;
}

PocketedBall pocketedMessage(const core::PocketedBall& dropped, const std::string& frame_id)
{
  PocketedBall msg;
  msg.header.stamp = ros::Time(dropped.time);
  msg.header.frame_id = frame_id;
  msg.ball = toMsg(dropped.ball, dropped.angular_velocity, dropped.motion, dropped.inertia);
  msg.pocket = dropped.pocket;
  return msg;
}

BallState ballState(const core::World& world, int id)
{
  return toMsg(world, world.indexOf(id));
}

void answerGetState(const core::World& world, bool paused, const std::string& frame_prefix, GetState::Response& res)
{
  res.success = true;
  res.time = world.time();
  res.steps = world.stats().steps;
  res.paused = paused;
  res.frame_id = world.scene().frame_id;
  res.frame_prefix = frame_prefix;
  res.balls.clear();
  res.balls.reserve(world.balls().size());
  for (std::size_t k = 0; k < world.balls().size(); ++k)
    res.balls.push_back(toMsg(world, k));
  res.walls.clear();
  for (const core::Wall& wall : world.walls())
    res.walls.push_back(toMsg(wall));
  res.message = "t = " + core::formatNumber(res.time) + " s, " + std::to_string(res.balls.size()) + " balls, " +
                std::to_string(res.walls.size()) + " walls" + (paused ? ", paused" : "");
}

namespace
{
/// A path as given, or package://PACKAGE/REST resolved to that package's folder.
std::string resolvePath(const std::string& path)
{
  const std::string scheme = "package://";
  if (path.rfind(scheme, 0) != 0)
    return path;
  const std::string rest = path.substr(scheme.size());
  const std::size_t slash = rest.find('/');
  const std::string package = rest.substr(0, slash);
  const std::string folder = ros::package::getPath(package);
  if (folder.empty())
    throw yaml::SceneError("path: no package named \"" + package + "\" (in " + path + ")");
  return folder + (slash == std::string::npos ? "" : rest.substr(slash));
}
}  // namespace

yaml::SceneFile sceneOfRequest(const LoadScene::Request& req)
{
  if (req.path.empty() == req.yaml.empty())
    throw yaml::SceneError(req.path.empty() ? "path: missing (give a scene file in path, or its text in yaml)"
                                            : "yaml: give either path or yaml, not both");
  const auto read = [](const std::string& text, const std::string& source) {
    yaml::SceneFile file = yaml::parseSceneFile(text, source);
    const std::vector<core::SceneIssue> issues = yaml::check(file);
    if (!issues.empty())
      throw yaml::SceneError(source + ": " + core::joinIssues(issues));
    return file;
  };
  if (req.path.empty())
    return read(req.yaml, "yaml");  // (its messages start "yaml: ")
  const std::string source = resolvePath(req.path);
  try
  {
    return read(yaml::readTextFile(source), source);
  }
  catch (const yaml::SceneError& e)
  {
    // the field first, then the file and what is wrong in it
    throw yaml::SceneError(std::string("path: ") + e.what());
  }
}
}  // namespace ball_collision_sim::bridge
