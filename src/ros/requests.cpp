#include "ball_collision_sim/ros/requests.hpp"

#include "ball_collision_sim/ros/conversions.hpp"

namespace ball_collision_sim::bridge
{
std::string roomForABall(const core::World& world, int max_balls)
{
  if (world.balls().size() < static_cast<std::size_t>(max_balls))
    return "";
  return "max_balls: the world already holds " + std::to_string(world.balls().size()) +
         " balls, the most this node takes (parameter max_balls)";
}

void answerAddBall(core::World& world, int max_balls, const AddBall::Request& req, AddBall::Response& res)
{
  res.id = -1;
  if (const std::string full = roomForABall(world, max_balls); !full.empty())
  {
    res.success = false;
    res.message = full;
    return;
  }
  const core::AddResult result = world.addBall(fromMsg(req));
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
  res.success = world.removeBall(req.id);
  res.message = res.success ? "removed ball " + std::to_string(req.id) : "id: no ball has id " + std::to_string(req.id);
}

void answerRemoveWall(core::World& world, const RemoveObject::Request& req, RemoveObject::Response& res)
{
  res.success = world.removeWall(req.id);
  res.message = res.success ? "removed wall " + std::to_string(req.id) : "id: no wall has id " + std::to_string(req.id);
}

bool acceptStep(const core::World& world, bool paused, const Step::Request& req, Step::Response& res)
{
  res.time = world.time();
  res.success = false;
  if (!paused)
  {
    res.message = "steps: stepping works only while paused (call pause with data: true first)";
    return false;
  }
  if (req.steps < 1 || req.steps > kMaxStepsPerCall)
  {
    res.message = "steps: must be in 1.." + std::to_string(kMaxStepsPerCall) + " (got " + std::to_string(req.steps) + ")";
    return false;
  }
  return true;
}
}  // namespace ball_collision_sim::bridge
