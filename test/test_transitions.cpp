// Every change of a ball's motion kind on a curved floor with friction has its cause: a
// ball that friction can hold rolling (k |g_t| / (1 + k) <= mu_s g_n where it is) starts
// to slide only at an impact; a slip ends only where one began (an impact, or the start);
// a ball stops only where it then is at rest. Counted in a walled paraboloid bowl, on a
// walled saddle and in config/bowl_friction.yaml, and for a lone ball on each floor,
// which never slides.
#include "fixtures.hpp"

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iostream>
#include <map>
#include <string>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
/// What the transitions of a run were, by cause.
struct Tally
{
  int to_sliding_at_impact = 0;   ///< impacts that made a ball slide
  int to_sliding_by_pull = 0;     ///< balls whose friction could not hold rolling where they were
  int slips_ended = 0;            ///< sliding -> rolling (or still)
  int stops = 0;                  ///< rolling or spinning -> stationary or spinning, at rest
  int take_offs_at_impact = 0;    ///< impacts whose push off the floor makes a ball fly
  int take_offs_by_bend = 0;      ///< balls the floor cannot hold where it bends away
  int landings = 0;               ///< flying -> on the floor, at the landing's impact
  int restarts_at_impact = 0;     ///< still -> moving at an impact
  int restarts_by_pull = 0;       ///< still -> rolling where the pull beats rolling resistance
  int initially_sliding = 0;      ///< at the start, or landing
  std::vector<std::string> unaccounted;
  int total() const
  {
    return to_sliding_at_impact + to_sliding_by_pull + slips_ended + stops + take_offs_at_impact + take_offs_by_bend +
           landings + restarts_at_impact + restarts_by_pull;
  }
};

/// Whether friction can hold ball k rolling where it is: k |g_t| / (1 + k) <= mu_s g_n
/// under the floor's normal at its foot point.
bool holdsRolling(const World& world, std::size_t k)
{
  const Ball& ball = world.balls()[k];
  const Floor& floor = *world.floor();
  const FloorFoot foot = floor.project(ball.position, Vec2(0.5, 0.5));
  const Vec3 g = world.gravity();
  const double g_n = -g.dot(foot.normal);
  const double g_t = (g + g_n * foot.normal).norm();
  const double inertia = world.inertia(k);
  return inertia * g_t / (1 + inertia) <= world.friction()->sliding * g_n;
}

/// Whether ball k's pull along the floor beats its rolling resistance where it is:
/// |g_t| / (1 + k) > mu_r g_n (so that it cannot stay at rest but for its contacts).
bool pullBeatsResistance(const World& world, std::size_t k)
{
  const Floor& floor = *world.floor();
  const FloorFoot foot = floor.project(world.balls()[k].position, Vec2(0.5, 0.5));
  const Vec3 g = world.gravity();
  const double g_n = -g.dot(foot.normal);
  return (g + g_n * foot.normal).norm() / (1 + world.inertia(k)) > world.friction()->rolling * g_n;
}

/// Whether the last step had an impact of ball `id` at time t, of one of `kinds`.
bool impactAt(const World& world, int id, double t, std::initializer_list<CollisionEvent::Kind> kinds)
{
  for (const CollisionEvent& e : world.lastEvents())
    if ((e.ball == id || (e.kind == CollisionEvent::Kind::kBallBall && e.other == id)) &&
        std::abs(e.time - t) <= 1e-12 * std::max(1.0, t) && std::find(kinds.begin(), kinds.end(), e.kind) != kinds.end())
      return true;
  return false;
}

/// Runs `world` for `seconds` and sorts each transition by its cause.
Tally countTransitions(World& world, double seconds)
{
  Tally tally;
  std::map<int, bool> sliding;
  for (std::size_t k = 0; k < world.balls().size(); ++k)
  {
    sliding[world.balls()[k].id] = world.motionKind(k) == MotionKind::kSliding;
    tally.initially_sliding += sliding[world.balls()[k].id] ? 1 : 0;
  }
  const int steps = static_cast<int>(std::lround(seconds / world.dt()));
  for (int s = 0; s < steps; ++s)
  {
    world.step();
    for (const MotionTransition& t : world.lastTransitions())
    {
      const std::string what = std::string(motionKindName(t.from)) + " -> " + motionKindName(t.to) + " of ball " +
                               std::to_string(t.ball) + " at " + std::to_string(t.time) + " s";
      const std::size_t k = world.indexOf(t.ball);
      const bool impact =
          impactAt(world, t.ball, t.time, {CollisionEvent::Kind::kBallBall, CollisionEvent::Kind::kBallWall});
      if (t.to == MotionKind::kFlying)
      {
        if (impact)
          ++tally.take_offs_at_impact;
        else if (world.floor()->awayCurvature() > 0)
          ++tally.take_offs_by_bend;
        else
          tally.unaccounted.push_back(what + ": no impact, and the floor nowhere bends away");
        sliding[t.ball] = false;
      }
      else if (t.from == MotionKind::kFlying)
      {
        if (impactAt(world, t.ball, t.time, {CollisionEvent::Kind::kBallFloor}))
          ++tally.landings;
        else
          tally.unaccounted.push_back(what + ": no landing");
        sliding[t.ball] = t.to == MotionKind::kSliding;
        tally.initially_sliding += sliding[t.ball] ? 1 : 0;  // (a slip a landing began)
      }
      else if (t.to == MotionKind::kSliding)
      {
        if (impact)
          ++tally.to_sliding_at_impact;
        else if (!holdsRolling(world, k))
          ++tally.to_sliding_by_pull;
        else
          tally.unaccounted.push_back(what + ": no impact, and friction holds rolling there");
        sliding[t.ball] = true;
      }
      else if (t.from == MotionKind::kSliding)
      {
        if (sliding[t.ball])
          ++tally.slips_ended;
        else
          tally.unaccounted.push_back(what + ": a slip that did not begin");
        sliding[t.ball] = false;
      }
      else if ((t.from == MotionKind::kStationary || t.from == MotionKind::kSpinning) && t.to == MotionKind::kRolling)
      {
        if (impact)
          ++tally.restarts_at_impact;
        else if (pullBeatsResistance(world, k))
          ++tally.restarts_by_pull;
        else
          tally.unaccounted.push_back(what + ": no impact, and its rolling resistance holds it");
      }
      else if (t.to == MotionKind::kStationary || t.to == MotionKind::kSpinning)
      {
        // (at rest where the step ends, unless something moved it again within the step)
        const bool moved_again = world.motionKind(k) != t.to;
        if (world.balls()[k].velocity == Vec3::Zero() || moved_again)
          ++tally.stops;
        else
          tally.unaccounted.push_back(what + ": stopped, yet moving");
      }
      else
        tally.unaccounted.push_back(what + ": no law gives it");
    }
  }
  return tally;
}

void expectAccounted(const Tally& tally, const std::string& scene)
{
  for (const std::string& what : tally.unaccounted)
    ADD_FAILURE() << scene << ": " << what;
  std::cout << scene << ": " << tally.total() << " transitions, " << tally.to_sliding_at_impact << " to sliding at impacts, "
            << tally.to_sliding_by_pull << " by the pull, " << tally.slips_ended << " slips ended, " << tally.stops
            << " stops, " << tally.take_offs_at_impact << " take-offs at impacts, " << tally.take_offs_by_bend
            << " by the bend, " << tally.landings << " landings, " << tally.restarts_at_impact << " restarts at impacts, "
            << tally.restarts_by_pull << " by the pull\n";
  // every slip that ended began: at an impact, by the pull or at the start
  EXPECT_LE(tally.slips_ended, tally.to_sliding_at_impact + tally.to_sliding_by_pull + tally.initially_sliding) << scene;
}

/// `count` balls (radius 0.06-0.1 m, 0.5-2 kg, up to 1.2 m/s) rolling on `floor`,
/// walled in on [-1.5, 1.5]^2, at restitution 0.8, with friction that holds rolling on
/// every part of it the balls reach.
Scene rollingBalls(const FloorDef& floor, int count, std::uint64_t seed)
{
  Scene scene;
  scene.floor = floor;
  addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.5, -0.5);  // (the saddle dips to -0.17 m at the walls)
  scene.restitution = 0.8;
  scene.random_balls = randomBalls(count, seed, {0.06, 0.1}, {0.5, 2}, {0, 1.2});
  scene.random_balls->region = RandomBallsDef::Region{Vec2(-1.4, -1.4), Vec2(1.4, 1.4)};  // (inside the walls)
  scene.friction = friction(0.2, 0.01, 0.044);
  return scene;
}
}  // namespace

// Friction holds rolling all over the test floors at these coefficients: the steepest
// slope a ball reaches is 0.4 in the bowl and 0.23 on the saddle, and k tan / (1 + k)
// <= 0.4 * 0.4 / 1.4 = 0.11 < 0.2. So every slide starts at an impact.
TEST(Transitions, EachHasItsCauseInTheBowl)
{
  for (const std::uint64_t seed : {1, 2})
  {
    World world(rollingBalls(bowl(3, 0.3), 8, seed));
    const Tally tally = countTransitions(world, 10.0);
    expectAccounted(tally, "bowl, seed " + std::to_string(seed));
    EXPECT_EQ(tally.to_sliding_by_pull, 0);
    EXPECT_GT(tally.to_sliding_at_impact, 0);  // (the balls meet)
  }
}

TEST(Transitions, EachHasItsCauseOnTheSaddle)
{
  for (const std::uint64_t seed : {1, 2})
  {
    World world(rollingBalls(saddle(0.3), 8, seed));
    const Tally tally = countTransitions(world, 10.0);
    expectAccounted(tally, "saddle, seed " + std::to_string(seed));
    EXPECT_EQ(tally.to_sliding_by_pull, 0);
    EXPECT_EQ(tally.take_offs_by_bend, 0);  // (it bends away at 0.15/m: v^2 / 0.15 < g at these speeds)
    EXPECT_GT(tally.to_sliding_at_impact, 0);
  }
}

// The example scene: four balls released on the bowl's slope, one struck across it with
// side spin, meet near its bottom, slide after each impact and roll again, and stop.
TEST(Transitions, EachHasItsCauseInBowlFriction)
{
  World world(ball_collision_sim::yaml::loadValidScene(std::string(BCS_CONFIG_DIR) + "/bowl_friction.yaml"));
  const Tally tally = countTransitions(world, 10.0);
  expectAccounted(tally, "bowl_friction.yaml");
  EXPECT_EQ(tally.to_sliding_by_pull, 0);
  EXPECT_EQ(tally.initially_sliding, 1);  // (the struck ball)
  EXPECT_EQ(tally.stops, 4);              // (each ball once, at the bottom)
}

// Alone, a ball that rolls where friction holds it never slides: it swings about the
// bowl, short of its walls, until it stops; on the saddle it slides only where it meets
// a wall.
TEST(Transitions, ALoneRollingBallSlidesOnlyAtImpacts)
{
  for (const bool in_bowl : {true, false})
  {
    Scene scene;
    scene.floor = in_bowl ? bowl(3, 0.3) : saddle(0.3);
    addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.5, -0.5);  // (the saddle dips to -0.17 m at the walls)
    scene.friction = friction(0.2, 0.01, 0.044);
    World world(scene);
    ASSERT_TRUE(world.addBall(ball(0.9, 0.3, -0.4, 0.7), Landing::kUnder).ok);
    const Tally tally = countTransitions(world, 40.0);
    expectAccounted(tally, in_bowl ? "a lone ball in the bowl" : "a lone ball on the saddle");
    EXPECT_EQ(tally.to_sliding_by_pull, 0);
    if (in_bowl)
    {
      EXPECT_EQ(world.stats().events, 0u);
      EXPECT_EQ(tally.to_sliding_at_impact, 0);
      EXPECT_EQ(tally.stops, 1);
    }
    else
      EXPECT_GT(tally.to_sliding_at_impact, 0);  // (its walls)
  }
}
