// The stages of a step, in order, as functions over the step's context: StepContext::step()
// runs them top to bottom, and each can be run and tested alone on a StepContext.
#pragma once

#include "step_context.hpp"

namespace ball_collision_sim::core::step
{
/// The step's lists emptied and its record of where balls started made ready
/// (step_context.cpp).
void startStep(StepContext& c);
/// Each ball's free motion over the step, on the floor (or in flight), and its swept box
/// in the grid (predict.cpp).
void predictMotions(StepContext& c);
/// The swept boxes into the uniform grid, the walls and the floor's open edges its
/// obstacles (detect.cpp).
void buildBroadPhase(StepContext& c);
/// The step's resting contacts at its start: touching pairs and walls that close no
/// faster than they rest, each group of balls they join solved together
/// (resting_groups.cpp).
void formRestingGroups(StepContext& c);
/// The exact first times of impact of nearby pairs and walls, and where each motion
/// ends within the step, into the event queue (detect.cpp).
void findFirstImpacts(StepContext& c);
/// The events earliest first: impacts bounce, slow approaches become resting contacts,
/// motions end; only the balls involved are detected again (resolve.cpp).
void resolveEventsInTimeOrder(StepContext& c);
/// Every ball to the step's end, back on the floor; with predict_next also each ball's
/// motion for the next step, which keeps this step's visiting order (commit.cpp).
void commitToFloor(StepContext& c, bool predict_next);
}  // namespace ball_collision_sim::core::step
