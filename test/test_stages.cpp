// The step's stages one at a time on a StepContext (src/core/step/step_context.hpp), each
// against what it alone must give: predict (a ball's motion over the step: a line, the
// parabola along a sloped plane, a flight), broad phase and detection (the queued first
// impact of a pair and of a wall at their closed-form times), a landing and a take-off
// queued as motion ends, resolve (the pair's velocities exchanged at the impact),
// and commit (every ball at its closed-form end, the next step's motions predicted).
#include "fixtures.hpp"

#include "core/step/flight.hpp"
#include "core/step/stages.hpp"
#include "core/step/floor_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kDt = 0.01;

/// A context at a step's start, as StepContext::step() makes it before its first stage.
StepContext started(const Scene& scene)
{
  StepContext c(scene);
  step::startStep(c);
  return c;
}

/// ... and through detection: its motions predicted, the grid built, the resting groups
/// formed and the first impacts and motion ends queued.
StepContext detected(const Scene& scene)
{
  StepContext c = started(scene);
  step::predictMotions(c);
  step::buildBroadPhase(c);
  step::formRestingGroups(c);
  step::findFirstImpacts(c);
  return c;
}

/// Two balls of radius r closing head on at 2 v on a level floor, 0.4 m apart.
Scene headOn(double r, double v)
{
  Scene scene = flatScene(-5, 5, -5, 5);
  scene.balls = {ball(-0.2, 0, v, 0, r), ball(0.2, 0, -v, 0, r)};
  return scene;
}
}  // namespace

// Predict: on a level plane a ball's motion is the line dt v; along a plane sloped by
// angle a, the parabola of g sin(a) along its fall line; a ball in flight, gravity's own.
TEST(Stages, PredictGivesEachBallsMotionOverTheStep)
{
  Scene level = flatScene(-5, 5, -5, 5);
  level.balls = {ball(0, 0, 1, 0.5), ball(2, 0, 0, 0)};
  BallDef up = ball(-2, 0, 1, 0);
  up.position.z() = 1;
  up.velocity.z() = 2;
  up.placement = BallPlacement::kAsGiven;
  level.balls.push_back(up);
  StepContext c = started(level);
  step::predictMotions(c);
  EXPECT_EQ(c.motions_[0].b, Vec3(kDt * 1, kDt * 0.5, 0));
  EXPECT_EQ(c.motions_[0].type, MotionType::kLine);
  EXPECT_EQ(c.motions_[1].b, Vec3::Zero());
  EXPECT_EQ(c.motions_[2].type, MotionType::kFlight);
  EXPECT_EQ(c.motions_[2].b, Vec3(kDt * 1, 0, kDt * 2));
  EXPECT_EQ(c.pathTerm(2), Vec3(0, 0, -0.5 * 9.81 * kDt * kDt));
  const Vec3 end = c.positionAt(2, 1.0);
  EXPECT_NEAR(end.z(), 1 + 2 * kDt - 0.5 * 9.81 * kDt * kDt, 1e-15);

  // sloped: z = -x tan(a) over the plane
  const double a = 0.2;
  Scene slope;
  FloorDef f;
  f.type = FloorDef::Type::kPlane;
  f.point = Vec3(-5, -5, 5 * std::tan(a));
  f.u = Vec3(10, 0, -10 * std::tan(a));
  f.v = Vec3(0, 10, 0);
  slope.floor = f;
  slope.balls = {ball(0, 0, 0, 1)};
  StepContext s = started(slope);
  step::predictMotions(s);
  const Vec3 d = s.positionAt(0, 1.0) - s.balls_[0].position;
  const double along = 0.5 * 9.81 * std::sin(a) * kDt * kDt;  // down the fall line
  EXPECT_NEAR(d.x(), along * std::cos(a), 1e-15);
  EXPECT_NEAR(d.y(), kDt, 1e-15);
  EXPECT_NEAR(d.z(), -along * std::sin(a), 1e-15);
}

// Broad phase and detection: two balls closing head on at 2 v meet after (d - 2 r) / (2 v);
// one toward a wall, after (g - r) / v: each the first event queued, at that step fraction.
TEST(Stages, DetectionQueuesTheFirstImpactsAtTheirTimes)
{
  const double r = 0.1, v = 10;
  StepContext c = detected(headOn(r, v));
  ASSERT_FALSE(c.queue_.empty());
  const StepEvent first = c.queue_.pop();
  EXPECT_EQ(first.kind, EventKind::kBallBall);
  EXPECT_NEAR(first.x * kDt, (0.4 - 2 * r) / (2 * v), 1e-15);

  Scene walled = flatScene(-5, 5, -5, 5);
  addBox(walled, -1, 1, -1, 1);
  walled.balls = {ball(0.85, 0, v, 0, r)};
  StepContext w = detected(walled);
  ASSERT_FALSE(w.queue_.empty());
  const StepEvent hit = w.queue_.pop();
  EXPECT_EQ(hit.kind, EventKind::kBallWall);
  EXPECT_NEAR(hit.x * kDt, (1 - 0.85 - r) / v, 1e-15);
  EXPECT_NEAR(hit.normal.x(), -1, 1e-15);
}

// A ball in flight 0.5 m above a plane, falling at 20 m/s: its landing is queued as a
// motion end at the root of its height, 0.5 + r - r = 20 t + g t^2 / 2 - ... within the step.
TEST(Stages, DetectionQueuesALandingAtTheRootOfTheHeight)
{
  Scene scene = flatScene(-5, 5, -5, 5);
  const double r = 0.1, h = 0.1, v = 20;
  BallDef b = ball(0, 0, 0, 0, r);
  b.position.z() = r + h;
  b.velocity.z() = -v;
  b.placement = BallPlacement::kAsGiven;
  scene.balls = {b};
  StepContext c = detected(scene);
  ASSERT_FALSE(c.queue_.empty());
  const StepEvent landing = c.queue_.pop();
  EXPECT_EQ(landing.kind, EventKind::kMotionEnd);
  EXPECT_EQ(landing.end, MotionEnd::kLanding);
  const double g = 9.81;
  const double t = (-v + std::sqrt(v * v + 2 * g * h)) / g;  // h = v t + g t^2 / 2
  EXPECT_NEAR(landing.x * kDt, t, 1e-15);
}

// The dome of test_flight's take-off, a ball 3.0 m down its diagonal at the speed its
// energy gives from the top at 4 m/s, just before it leaves: the take-off is queued as a
// motion end where the floor's push along the integrated motion (FloorFlow) falls through
// zero, within 1e-12 s past it: the push there below zero by less than 1e-9 of g.
TEST(Stages, DetectionQueuesATakeOffWhereTheFloorsPushFallsToZero)
{
  Scene scene;
  scene.floor = dome();
  const double x = 3.0 / std::sqrt(2.0), speed = 6.41;
  const double w = 3.0 / (8 * std::sqrt(2.0));
  // along the floor's tangent down the diagonal
  const double slope = std::atan((32 * w + 128 * w * w * w) / (8 * std::sqrt(2.0)));
  const double level = speed * std::cos(slope) / std::sqrt(2.0);
  BallDef b = ball(x, x, level, level, 0.1);
  b.velocity.z() = -speed * std::sin(slope);
  b.position.z() = 6 - 16 * w * w - 32 * w * w * w * w + 0.1;  // (put on the floor under it)
  scene.balls = {b};
  StepContext c = detected(scene);
  bool found = false;
  while (!c.queue_.empty())
  {
    const StepEvent e = c.queue_.pop();
    if (e.kind != EventKind::kMotionEnd || e.end != MotionEnd::kTakeOff)
      continue;
    found = true;
    const Floor& floor = *c.ground_.floor();
    const auto push = [&](double s) {
      const FloorFoot foot = floor.project(c.positionAt(0, s), c.guessOf(0));
      return step::floorPush(c, 0, foot.uv, foot.normal,
                         c.onFloorVelocity(0, s, floor.ballCentre(foot, 0.1), foot.normal));
    };
    EXPECT_GT(e.x, 0);
    EXPECT_LT(e.x, 1);
    EXPECT_LT(push(e.x), 0);
    EXPECT_GT(push(e.x), -1e-9 * 9.81);
  }
  EXPECT_TRUE(found);
}

// Resolve: the head-on pair of equal balls at e = 1 exchange their velocities at the
// impact, which is listed once at its time; commit then puts each at x0 + v t from the
// impact to the step's end, and predicts the next step's motion from there.
TEST(Stages, ResolveExchangesAndCommitEndsTheStep)
{
  const double r = 0.1, v = 10;
  StepContext c = detected(headOn(r, v));
  step::resolveEventsInTimeOrder(c);
  ASSERT_EQ(c.events_.size(), 1u);
  const double t = (0.4 - 2 * r) / (2 * v);
  EXPECT_NEAR(c.events_[0].time, t, 1e-15);
  EXPECT_NEAR(c.startVelocity(0).x(), -v, 1e-12);
  EXPECT_NEAR(c.startVelocity(1).x(), v, 1e-12);
  step::commitToFloor(c, true);
  const double after = kDt - t;
  EXPECT_NEAR(c.balls_[0].position.x(), -0.2 + v * t - v * after, 1e-12);
  EXPECT_NEAR(c.balls_[1].position.x(), 0.2 - v * t + v * after, 1e-12);
  EXPECT_NEAR(c.balls_[0].velocity.x(), -v, 1e-12);
  // (the next step's motions, from the records' ends)
  EXPECT_NEAR(c.motions_[0].b.x(), -v * kDt, 1e-12);
  EXPECT_EQ(c.motions_[0].x0, 0.0);
}

// The floor's edges as the grid's obstacles: a floor walled in on every side has none
// (a ball on it meets a wall before its foot can pass an edge); each wall taken away
// leaves its edge to be passed, and a wall that only hangs below an edge covers nothing.
TEST(Stages, OnlyEdgesNoWallCoversAreObstacles)
{
  Scene scene = flatScene(-1, 1, -1, 1);
  addBox(scene, -1, 1, -1, 1);
  StepContext c(scene);
  EXPECT_TRUE(c.edge_boxes_.empty());
  // (as an edit does: the walls changed, the boxes made again)
  const auto at_x1 = std::find_if(c.walls_.begin(), c.walls_.end(), [](const Wall& w) { return w.id == 4; });
  ASSERT_NE(at_x1, c.walls_.end());
  c.walls_.erase(at_x1);
  c.edge_boxes_ = step::floorEdgeBoxes(c);
  ASSERT_EQ(c.edge_boxes_.size(), 1u);
  EXPECT_EQ(c.edge_boxes_[0].min.x(), 1);
  EXPECT_EQ(c.edge_boxes_[0].max.x(), 1);
  WallDef below;
  below.point = Vec3(1, -1, 0);
  below.u = Vec3(0, 2, 0);
  below.v = Vec3(0, 0, -0.5);
  c.walls_.push_back(Wall(5, below, 1.0));
  c.edge_boxes_ = step::floorEdgeBoxes(c);
  EXPECT_EQ(c.edge_boxes_.size(), 1u);
  Scene open = flatScene(-1, 1, -1, 1);
  EXPECT_EQ(StepContext(open).edge_boxes_.size(), 4u);
}
