// Long runs of steps while paused: the step service and the step action. They step in
// chunks of a few milliseconds under the node's lock and give it up between chunks, so
// that the other services answer meanwhile; progress shows on /clock, ball_states, the
// action's feedback and a log line every few seconds.
#include "ball_collision_sim/ros/simulator_node.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/ros/requests.hpp"

#include <chrono>
#include <thread>

namespace ball_collision_sim::bridge
{
namespace
{
/// Wall time one chunk of steps may hold the lock [s]: what a service call waits at most
/// on top of its own work while a run goes on.
constexpr double kChunkSeconds = 0.005;
/// A progress line in the log every this many wall seconds of a run [s].
constexpr double kProgressLogPeriod = 2.0;
/// Action feedback at most this often [s].
constexpr double kFeedbackPeriod = 0.1;
}  // namespace

SimulatorNode::StepOutcome SimulatorNode::runSteps(std::uint32_t steps,
                                                   const std::function<void(std::uint32_t, double)>& progress,
                                                   const std::function<bool()>& cancelled)
{
  StepOutcome out;
  {
    const Lock guard = lock();
    out.time = world_.time();
    out.message = whyNoSteps(paused_, steps);
    if (out.message.empty() && running_)
      out.message = "steps: another run of steps is going (" + std::to_string(run_done_) + " of " +
                    std::to_string(run_total_) + " done); cancel it first (~cancel_step)";
    if (!out.message.empty())
      return out;
    running_ = true;
    cancel_run_ = false;
    run_done_ = 0;
    run_total_ = steps;
  }
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime logged = start;
  std::string stopped;
  while (out.done < steps)
  {
    {
      const Lock guard(mutex_);
      if (cancel_run_ || !paused_ || cancelled() || !ros::ok())
      {
        stopped = cancel_run_ || cancelled() || !ros::ok() ? "cancelled" : "resumed";
        break;
      }
      const ros::WallTime chunk = ros::WallTime::now();
      do
      {
        stepOnce();
        ++out.done;
      } while (out.done < steps && (ros::WallTime::now() - chunk).toSec() < kChunkSeconds);
      run_done_ = out.done;
      out.time = world_.time();
      publishView(false);
    }
    progress(out.done, out.time);
    if ((ros::WallTime::now() - logged).toSec() >= kProgressLogPeriod)
    {
      logged = ros::WallTime::now();
      ROS_INFO("ball_sim: stepping: %u of %u steps, t = %s s", out.done, steps, core::formatNumber(out.time).c_str());
    }
    // Whoever waits for the lock goes first.
    while (waiting_.load() > 0)
      std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  const Lock guard = lock();
  running_ = false;
  cancel_run_ = false;
  out.time = world_.time();
  publishPresent();
  out.success = stopped.empty();
  out.message = stopped.empty() ? "at t = " + core::formatNumber(out.time) + " s"
                                : "steps: " + stopped + " after " + std::to_string(out.done) + " of " +
                                      std::to_string(steps) + " steps, at t = " + core::formatNumber(out.time) + " s";
  if (!stopped.empty() || (ros::WallTime::now() - start).toSec() >= kProgressLogPeriod)
    ROS_INFO("ball_sim: %s", out.message.c_str());
  return out;
}

bool SimulatorNode::onStep(Step::Request& req, Step::Response& res)
{
  const StepOutcome out = runSteps(req.steps, [](std::uint32_t, double) {}, [] { return false; });
  res.success = out.success;
  res.message = out.message;
  res.time = out.time;
  return true;
}

void SimulatorNode::onStepGoal(const StepGoalConstPtr& goal)
{
  ros::WallTime fed;
  const StepOutcome out = runSteps(
      goal->steps,
      [&](std::uint32_t done, double time) {
        if ((ros::WallTime::now() - fed).toSec() < kFeedbackPeriod && done < goal->steps)
          return;
        fed = ros::WallTime::now();
        StepFeedback feedback;
        feedback.steps_done = done;
        feedback.time = time;
        step_action_->publishFeedback(feedback);
      },
      [this] { return step_action_->isPreemptRequested(); });
  StepResult result;
  result.success = out.success;
  result.message = out.message;
  result.steps_done = out.done;
  result.time = out.time;
  if (out.success)
    step_action_->setSucceeded(result, out.message);
  else if (step_action_->isPreemptRequested() || out.done > 0)
    step_action_->setPreempted(result, out.message);
  else
    step_action_->setAborted(result, out.message);
}

bool SimulatorNode::onCancelStep(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  const Lock guard = lock();
  res.success = running_;
  res.message = running_ ? "cancelling the run of steps at " + std::to_string(run_done_) + " of " +
                               std::to_string(run_total_)
                         : "no run of steps is going";
  cancel_run_ = running_;
  return true;
}
}  // namespace ball_collision_sim::bridge
