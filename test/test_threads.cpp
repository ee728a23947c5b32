// The step on several threads gives the bits it gives on one (StepSettings::threads): on
// every kind of scene, each step's state hash, collisions and transitions are the same for
// 1, 2 and 3 threads, and so are the counts of the whole run.
#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
/// What a run leaves that tells two runs apart: per step its hash, its collisions (time,
/// balls, impulse) and its transitions, and the run's counters.
struct Trace
{
  std::vector<std::uint64_t> hashes;
  std::vector<double> numbers;
  std::vector<int> ids;
  WorldStats stats;
};

Trace run(const Scene& scene, unsigned threads, int steps, const std::function<void(World&, int)>& edit = {})
{
  StepSettings settings;
  settings.threads = threads;
  settings.parallel_min_balls = 1;  // (every loop split, however few the balls)
  World world(scene, settings);
  Trace trace;
  for (int k = 0; k < steps; ++k)
  {
    if (edit)
      edit(world, k);
    world.step();
    trace.hashes.push_back(world.stateHash());
    for (const CollisionEvent& e : world.lastEvents())
    {
      trace.numbers.insert(trace.numbers.end(), {e.time, e.impulse, e.approach_speed});
      trace.ids.insert(trace.ids.end(), {e.ball, e.other, static_cast<int>(e.kind)});
    }
    for (const MotionTransition& t : world.lastTransitions())
    {
      trace.numbers.push_back(t.time);
      trace.ids.insert(trace.ids.end(), {t.ball, static_cast<int>(t.from), static_cast<int>(t.to)});
    }
    for (const PocketedBall& p : world.lastPocketed())
    {
      trace.numbers.insert(trace.numbers.end(), {p.time, p.ball.position.x(), p.ball.position.y()});
      trace.ids.insert(trace.ids.end(), {p.ball.id, p.pocket});
    }
  }
  trace.stats = world.stats();
  return trace;
}

/// Runs `scene` on 1, 2 and 3 threads and checks the traces are equal; returns the one's
/// stats, for the caller to see that the scene did what it is there for.
WorldStats sameOnEveryCount(const std::string& what, const Scene& scene, int steps,
                            const std::function<void(World&, int)>& edit = {})
{
  const Trace one = run(scene, 1, steps, edit);
  // (under the sanitizers, BCS_SLOWDOWN, which look for what the threads do to memory,
  // 3 threads only: runs of uneven lengths, more than there are cores here)
  const std::vector<unsigned> counts = std::getenv("BCS_SLOWDOWN") != nullptr ? std::vector<unsigned>{3}
                                                                               : std::vector<unsigned>{2, 3};
  for (const unsigned threads : counts)
  {
    const Trace many = run(scene, threads, steps, edit);
    EXPECT_EQ(many.hashes, one.hashes) << what << " on " << threads << " threads";
    EXPECT_EQ(many.numbers, one.numbers) << what << " on " << threads << " threads";
    EXPECT_EQ(many.ids, one.ids) << what << " on " << threads << " threads";
    EXPECT_EQ(many.stats.events, one.stats.events) << what;
    EXPECT_EQ(many.stats.transitions, one.stats.transitions) << what;
    EXPECT_EQ(many.stats.stopped_balls, one.stats.stopped_balls) << what;
    EXPECT_EQ(many.stats.floor_impacts, one.stats.floor_impacts) << what;
    EXPECT_EQ(many.stats.sleeping_balls, one.stats.sleeping_balls) << what;
  }
  return one.stats;
}

Scene plane(int count, double restitution)
{
  Scene scene = flatScene(-1.5, 1.5, -1.5, 1.5);
  addBox(scene, -1.5, 1.5, -1.5, 1.5);
  scene.restitution = restitution;
  scene.random_balls = randomBalls(count, 11, {0.03, 0.06}, {0.5, 2}, {0, 3});
  return scene;
}
}  // namespace

TEST(Threads, PlaneGivesTheSameBits)
{
  const WorldStats stats = sameOnEveryCount("plane", plane(300, 1.0), 120);
  EXPECT_GT(stats.events, 1000u);
}

TEST(Threads, CurvedFloorGivesTheSameBits)
{
  // (the walled bowl of bowlPile(), livelier: more balls, faster, bouncier)
  Scene scene = bowlPile(4);
  scene.restitution = 0.9;
  scene.random_balls = randomBalls(150, 4, {0.04, 0.07}, {0.5, 2}, {0, 2});
  const WorldStats stats = sameOnEveryCount("bowl", scene, 120);
  EXPECT_GT(stats.events, 500u);
}

TEST(Threads, FrictionGivesTheSameBits)
{
  Scene scene = plane(200, 0.95);
  scene.friction = pileFriction();
  scene.friction->ball_ball = 0.1;
  scene.friction->wall = 0.1;
  const WorldStats stats = sameOnEveryCount("friction", scene, 150);
  EXPECT_GT(stats.transitions, 200u);  // (sliding to rolling, rolling to stationary, ...)
}

TEST(Threads, PocketsGiveTheSameBits)
{
  // (the friction plane with a pocket in each corner and one in the middle)
  Scene scene = plane(200, 0.95);
  scene.friction = pileFriction();
  for (const auto& [x, y] : {std::pair{-1.4, -1.4}, std::pair{1.4, -1.4}, std::pair{-1.4, 1.4}, std::pair{1.4, 1.4},
                             std::pair{0.0, 0.0}})
    scene.pockets.push_back({Vec2(x, y), 0.12});
  const WorldStats stats = sameOnEveryCount("pockets", scene, 150);
  EXPECT_GT(stats.pocketed_balls, 10u);
}

TEST(Threads, PilesGiveTheSameBits)
{
  Scene pile = bowlPile(5);
  pile.friction = pileFriction();
  const WorldStats in_bowl = sameOnEveryCount("bowl pile", pile, 400);
  EXPECT_GT(in_bowl.resting_contacts, 1000u);
  const WorldStats on_slope = sameOnEveryCount("slope pile", slopePile(), 400);
  EXPECT_GT(on_slope.resting_contacts, 1000u);
}

TEST(Threads, FlightGivesTheSameBits)
{
  // balls dropped and thrown onto a dome they partly roll off and fly from, and a ball
  // struck into the floor every 20 steps (a jump)
  Scene scene;
  scene.floor = dome();
  addBox(scene, -4, 4, -4, 4, 12.0);
  scene.restitution = 0.8;
  for (int k = 0; k < 40; ++k)
  {
    BallDef b;
    b.radius = 0.1;
    b.position = Vec3(-3 + 0.17 * k, -2.5 + 0.12 * k, 9 + 0.05 * k);
    b.velocity = Vec3(0.5 * (k % 5) - 1, 0.3 * (k % 3), 0);
    b.placement = BallPlacement::kAsGiven;
    scene.balls.push_back(b);
  }
  scene.random_balls = randomBalls(60, 9, {0.05, 0.08}, {0.5, 2}, {1, 4});
  const auto strike = [](World& world, int k) {
    if (k % 20 == 10)
      world.applyImpulse(world.balls()[static_cast<std::size_t>(k / 20)].id, Vec3(0.3, 0, -4.0));
  };
  const WorldStats stats = sameOnEveryCount("flight", scene, 200, strike);
  EXPECT_GT(stats.floor_impacts, 50u);
  // (take-offs and landings: 21 and 3; found along the chord, one ball took off and
  // landed 257 times at one instant)
  EXPECT_GE(stats.transitions, 20u);
}
