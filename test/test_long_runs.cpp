#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
/// Under the sanitizers (`make sanitize` sets BCS_SLOWDOWN), which run the core about 30
/// times slower and look for what it does to memory, not for the physics of one more
/// start: there a test that repeats one run over several starts takes its `first` only.
template <class T>
std::vector<T> startsToRun(std::vector<T> all, std::size_t first = 1)
{
  if (std::getenv("BCS_SLOWDOWN") != nullptr && all.size() > first)
    all.resize(first);
  return all;
}

Scene closedBox(int count, double half)
{
  Scene scene = flatScene(-half, half, -half, half);
  addBox(scene, -half, half, -half, half);
  scene.random_balls = randomBalls(count, 2024, {0.05, 0.1}, {0.5, 3}, {0, 2});
  return scene;
}
}  // namespace

// 1000 balls in a closed box for 100 s at restitution 1: kinetic energy to 1e-9
// relative, no overlap deeper than 1e-9 m, nobody leaves.
TEST(LongRun, ThousandBallsHundredSeconds)
{
  const double half = 5;
  World world(closedBox(1000, half));
  ASSERT_EQ(world.balls().size(), 1000u);
  const double e0 = world.energy().kinetic;
  double worst_energy = 0, worst_overlap = -1;
  for (int k = 1; k <= 10000; ++k)
  {
    world.step();
    if (k % 50 != 0)
      continue;
    worst_energy = std::max(worst_energy, std::abs(world.energy().kinetic / e0 - 1));
    worst_overlap = std::max(worst_overlap, deepestOverlap(world.balls()));
    for (const Ball& b : world.balls())
    {
      ASSERT_TRUE(b.position.allFinite() && b.velocity.allFinite());
      ASSERT_LE(b.position.head<2>().cwiseAbs().maxCoeff(), half - b.radius + 1e-9) << "step " << k;
    }
  }
  EXPECT_LT(worst_energy, 1e-9);
  EXPECT_LT(worst_overlap, 1e-9);
  EXPECT_EQ(world.lostBalls(), 0);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  // it was a gas, not a still life
  EXPECT_GT(world.stats().events, 100000u);
  RecordProperty("events", std::to_string(world.stats().events));
  char drift[32];
  std::snprintf(drift, sizeof(drift), "%.3g", worst_energy);
  RecordProperty("kinetic_energy_drift", drift);
  std::snprintf(drift, sizeof(drift), "%.3g", worst_overlap);
  RecordProperty("deepest_overlap_m", drift);
}

// Without a floor, balls fly on parabolas in a closed box of six walls at e = 1 for 60 s:
// every impact on them (quadratic ball-ball, accelerated sweeps of faces, edges, corners)
// keeps the energy, no ball gets into another or out of the box.
TEST(LongRun, BallisticBallsInAClosedBoxKeepTheirEnergy)
{
  Scene scene;  // no floor
  const double side = 2;
  addBox(scene, 0, side, 0, side, side);
  scene.walls.push_back({Vec3(0, 0, 0), Vec3(side, 0, 0), Vec3(0, side, 0), {}});
  scene.walls.push_back({Vec3(0, 0, side), Vec3(side, 0, 0), Vec3(0, side, 0), {}});
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 40; ++k)
  {
    BallDef b;
    b.radius = 0.08;
    b.mass = 1 + u(rng);
    b.position = Vec3(0.2 + 0.4 * (k % 4), 0.2 + 0.4 * ((k / 4) % 4), 0.3 + 0.5 * (k / 16));
    b.velocity = Vec3(4 * u(rng) - 2, 4 * u(rng) - 2, 4 * u(rng) - 2);
    scene.balls.push_back(b);
  }
  World world(scene);
  const double e0 = world.energy().total();
  double drift = 0, overlap = -1;
  for (int k = 0; k < 6000; ++k)
  {
    world.step();
    drift = std::max(drift, std::abs(world.energy().total() - e0) / e0);
    overlap = std::max(overlap, deepestOverlap(world.balls()));
  }
  EXPECT_GT(world.stats().events, 10000u);
  // at e = 1 on exact paths every impact bounces (chords across the parabolas made some
  // 8,000 of them look like resting contacts here)
  EXPECT_EQ(world.stats().resting_events, 0u);
  EXPECT_LT(drift, 1e-12);
  EXPECT_LT(overlap, 1e-9);
  for (const Ball& b : world.balls())
    EXPECT_TRUE((b.position.array() >= 0).all() && (b.position.array() <= side).all()) << b.id;
  EXPECT_EQ(world.stats().frozen_balls, 0u);
}

// Without walls, ball-ball collisions alone: total momentum is kept to round-off.
TEST(LongRun, MomentumWithoutWalls)
{
  Scene scene = flatScene(-50, 50, -50, 50);
  RandomBallsDef rb = randomBalls(1000, 5, {0.05, 0.1}, {0.5, 3}, {0, 2});
  rb.region = RandomBallsDef::Region{Vec2(-4, -4), Vec2(4, 4)};
  scene.random_balls = rb;
  World world(scene);
  const Vec3 p0 = world.momentum();
  double scale = 0;
  for (const Ball& b : world.balls())
    scale += b.mass * b.velocity.norm();
  for (int k = 0; k < 1000; ++k)
    world.step();
  EXPECT_GT(world.stats().events, 1000u);
  EXPECT_LT((world.momentum() - p0).norm(), 1e-12 * scale);
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
}

// A dissipative gas on a slope settles into a pile against the lower wall: the pile stays
// inside and unbroken, comes (all but) to rest, and costs about one event per contact per step.
TEST(LongRun, PileSettlesOnASlope)
{
  const Scene scene = slopePile();
  World world(scene);
  for (int k = 0; k < 1000; ++k)
    world.step();
  std::size_t most = 0;
  for (int k = 0; k < 100; ++k)
  {
    world.step();
    most = std::max(most, world.lastEvents().size());
  }
  EXPECT_LE(most, 3 * world.balls().size());
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
  EXPECT_EQ(world.lostBalls(), 0);
  // all but still: speeds of a few mm/s at most, from a starting kinetic energy of ~10 J
  EXPECT_LT(world.energy().kinetic, 1e-4);
  for (const Ball& b : world.balls())
    EXPECT_GT(b.position.x(), 1 - 12 * 0.08 * 2) << "ball " << b.id << " is not in the pile";
}

// A dissipative gas in a bowl settles into a pile at its bottom, where balls on either
// side of one can hold it off the floor: with friction (pileFriction()), no step makes
// energy, the pile comes to rest within 20 s, and then costs at most a few events per
// ball and step; nor does any ball reach the event cap on the way (which stops it dead).
TEST(LongRun, PileSettlesInABowl)
{
  for (const std::uint32_t seed : startsToRun<std::uint32_t>({3u, 5u, 7u}))
  {
    Scene scene = bowlPile(seed);
    scene.friction = pileFriction();
    World world(scene);
    const double largest_rise = largestEnergyRise(world, 1900);
    const std::uint64_t events = world.stats().events;
    for (int k = 0; k < 100; ++k)
      world.step();
    const double per_ball_step = static_cast<double>(world.stats().events - events) / (100.0 * world.balls().size());
    // (round-off of a total of about 60 J)
    EXPECT_LT(largest_rise, 1e-11) << "seed " << seed;
    EXPECT_LT(world.energy().kinetic, 1e-4) << "seed " << seed;
    EXPECT_LT(per_ball_step, 3.0) << "seed " << seed;
    EXPECT_LT(deepestOverlap(world.balls()), 1e-9) << "seed " << seed;
    EXPECT_EQ(world.lostBalls(), 0) << "seed " << seed;
    EXPECT_EQ(world.stats().frozen_balls, 0u) << "seed " << seed;
    EXPECT_GT(world.stats().resting_contacts, 0u) << "seed " << seed;
  }
}

// Three balls in a ring at the bottom of a bowl, each pressed by the floor into the two
// others while they still move: answering one contact pushes a ball into its other
// neighbour. Their contacts are solved together, as constraints, so no step comes near
// the event cap and none is stopped dead; they settle without making energy or
// overlapping.
TEST(LongRun, RingOfThreeInABowlSettlesWithoutTheCap)
{
  Scene scene;
  scene.floor = bowl(4, 0.5);
  scene.restitution = 0.5;
  const double r = 0.1, circle = 2 * r / std::sqrt(3.0);  // neighbours 2r apart
  for (int k = 0; k < 3; ++k)
  {
    BallDef b;
    b.radius = r;
    const double a = 2 * M_PI * k / 3;
    b.position = Vec3(circle * std::cos(a), circle * std::sin(a), 0.2);
    scene.balls.push_back(b);
  }
  World world(scene);
  std::size_t most = 0;
  double rise = 0;
  for (int k = 0; k < 500; ++k)
  {
    const double before = world.energy().total();
    world.step();
    rise = std::max(rise, world.energy().total() - before);
    most = std::max(most, world.lastEvents().size());
  }
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_LT(most, 64u);
  EXPECT_GT(world.stats().resting_contacts, 0u);
  EXPECT_LT(rise, 1e-12);
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
  EXPECT_LT(world.energy().kinetic, 1e-9);
}

// Balls in a bowl pile pressed on all sides, whose motions kept out of what they lean on
// point off the floor: no step lifts one higher than its energy reaches.
TEST(LongRun, NoStepMakesEnergyInBowlPiles)
{
  for (const std::uint32_t seed : startsToRun<std::uint32_t>({8u, 18u}))
  {
    World world(bowlPile(seed));
    const double largest_rise = largestEnergyRise(world, 1000);
    EXPECT_GT(world.stats().resting_contacts, 10000u) << "seed " << seed;
    EXPECT_LT(largest_rise, 1e-11) << "seed " << seed;
    EXPECT_LT(deepestOverlap(world.balls()), 1e-9) << "seed " << seed;
    EXPECT_EQ(world.lostBalls(), 0) << "seed " << seed;
  }
}

// Restitution 1 keeps the total energy to 1e-9 of the energies in play over 60 s, also
// where balls gather under gravity and touch again and again: 60 balls in the bowl of
// S3, and 60 against the wall at the foot of a 10 degree slope. The bounces of an elastic
// contact never end, so none is summed to rest, and leaning on something turns a ball's
// velocity without taking its speed.
TEST(LongRun, ElasticPilesKeepTheirEnergyForAMinute)
{
  Scene bowl_scene;
  bowl_scene.floor = bowl(4, 0.5);
  addBox(bowl_scene, -2, 2, -2, 2, 1.5);  // as S3: walls on the rim
  bowl_scene.random_balls = randomBalls(60, 3, {0.03, 0.03}, {1, 1}, {0, 1});
  for (const Scene& scene : {bowl_scene, slopeWithWall(60, 10, 1.0, 4)})
  {
    World world(scene);
    const double e0 = world.energy().total();
    // the energies in play: kinetic at the start, and potential over the balls' heights
    double lowest = 1e300, highest = -1e300, mass = 0;
    for (const Ball& b : world.balls())
    {
      const double h = -world.gravity().normalized().dot(b.position);
      lowest = std::min(lowest, h);
      highest = std::max(highest, h);
      mass += b.mass;
    }
    const double scale = world.energy().kinetic + mass * world.gravity().norm() * (highest - lowest);
    double worst = 0;
    for (int k = 0; k < 6000; ++k)
    {
      world.step();
      worst = std::max(worst, std::abs(world.energy().total() - e0));
    }
    EXPECT_LT(worst / scale, 1e-9);
    EXPECT_GT(world.stats().events, 3000u);  // they met, often
    EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
    EXPECT_EQ(world.lostBalls(), 0);
    EXPECT_EQ(world.stats().frozen_balls, 0u);
    RecordProperty("energy_drift_" + std::to_string(world.balls().size()), std::to_string(worst / scale));
  }
}

// Dissipative piles come to rest and sleep: 60 and 200 balls at restitution 0.5 and 0.9
// in a walled bowl (with friction, pileFriction()) and against the wall at the foot of a
// 10 degree slope (without). No step makes
// energy (beyond round-off of the energies in play), no two balls overlap by more than
// 1e-9 m at any step, every ball is asleep after 30 s with no kinetic energy left, and
// asleep they make at most 0.01 events per ball and step. Twice the same: the same bits.
// Under the sanitizers (startsToRun()), the 60-ball piles only: the 200-ball ones run the
// same code for 30 times as long.
TEST(LongRun, DissipativePilesComeToRestAndSleep)
{
  const std::vector<int> sizes = startsToRun<int>({60, 200});
  for (const double e : startsToRun<double>({0.5, 0.9}))
    for (const int n : sizes)
      for (const bool slope : {false, true})
      {
        Scene scene;
        if (slope)
          scene = slopeWithWall(n, 10, e, 4, n > 100 ? 3.0 : 2.0);
        else
        {
          scene.floor = bowl(3, 0.3);
          addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.0);
          scene.restitution = e;
          scene.random_balls = randomBalls(n, 4, {0.05, 0.08}, {0.5, 2}, {0, 1});
          scene.friction = pileFriction();
        }
        const std::string what = std::string(slope ? "slope" : "bowl") + " n=" + std::to_string(n) + " e=" + std::to_string(e);
        World world(scene);
        ASSERT_EQ(world.balls().size(), static_cast<std::size_t>(n)) << what;
        const double k0 = world.energy().kinetic;
        double mass = 0;
        for (const Ball& b : world.balls())
          mass += b.mass;
        const double scale = k0 + mass * world.gravity().norm() * 1.0;  // heights span under a metre
        const WorstOfRun worst = stepWatching(world, 3000, [](int) { return true; });
        EXPECT_LT(worst.energy_rise / scale, 1e-9) << what;
        EXPECT_LT(worst.overlap, 1e-9) << what;
        EXPECT_EQ(world.stats().sleeping_balls, static_cast<std::uint64_t>(n)) << what;
        EXPECT_LE(world.energy().kinetic, 1e-12 * k0) << what;
        const std::uint64_t events = world.stats().events;
        for (int k = 0; k < 100; ++k)
          world.step();
        EXPECT_LE(static_cast<double>(world.stats().events - events) / (100.0 * n), 0.01) << what;
        EXPECT_EQ(world.lostBalls(), 0) << what;
        EXPECT_EQ(world.stats().frozen_balls, 0u) << what;
        if (n == 60 && e == 0.5)
        {
          World again(scene);
          for (int k = 0; k < 3100; ++k)
            again.step();
          EXPECT_EQ(again.stateHash(), world.stateHash()) << what;
        }
      }
}

// Without a floor, balls dropped in a column into a box of five walls pile on its bottom
// wall, three and four layers deep, and come to rest: the same resting groups, solved in
// space. At restitution 0.5 and 0.9, 100 balls, and 60 whose contacts often say the same
// (the exact stage's matrix near singular; its pivoting alone does not settle): no
// step makes energy, no overlap deeper than 1e-9 m, every group's contacts solved, none
// leaves the box or is stopped by the event cap, all asleep after 30 s with no kinetic
// energy, and then at most 0.01 events per ball and step.
TEST(LongRun, PilesWithoutAFloorComeToRestAndSleep)
{
  struct Case
  {
    double e;
    int n;
    std::uint64_t seed;
  };
  // (the last first: its contacts say nearly the same, where the exact stage works hardest)
  for (const Case c : startsToRun<Case>({Case{0.9, 60, 6}, Case{0.5, 100, 7}, Case{0.9, 100, 7}}))
  {
    const double half = 0.6;
    const Scene scene = floorlessBoxDrop(c.n, c.e, c.seed);
    const std::string what = "e=" + std::to_string(c.e) + " n=" + std::to_string(c.n);
    World world(scene);
    const double scale = world.energy().total() - c.n * 9.81 * 0.1;  // above the lowest it can reach
    const WorstOfRun worst = stepWatching(world, 3000, [&](int k) {
      for (const Ball& b : world.balls())
        if (!(b.position.z() >= b.radius - 1e-9))
        {
          ADD_FAILURE() << what << " step " << k << " ball " << b.id << " below the bottom wall";
          return false;
        }
      return true;
    });
    EXPECT_LT(worst.energy_rise / scale, 1e-9) << what;
    EXPECT_LT(worst.overlap, 1e-9) << what;
    EXPECT_EQ(world.stats().unsettled_contacts, 0u) << what;
    EXPECT_EQ(world.stats().sleeping_balls, static_cast<std::uint64_t>(c.n)) << what;
    EXPECT_EQ(world.energy().kinetic, 0.0) << what;
    const std::uint64_t events = world.stats().events;
    for (int k = 0; k < 100; ++k)
      world.step();
    EXPECT_LE(static_cast<double>(world.stats().events - events) / (100.0 * c.n), 0.01) << what;
    for (const Ball& b : world.balls())
      EXPECT_LE(b.position.head<2>().cwiseAbs().maxCoeff(), half - b.radius + 1e-9) << what << " ball " << b.id;
    EXPECT_EQ(world.stats().frozen_balls, 0u) << what;
  }
}

// Without friction, a dissipative pile in the bowl (a paraboloid, z = a (x^2 + y^2)) does
// not come to rest: once its balls have stopped moving against one another, its centre
// of mass swings about the bottom as one body, as a ball alone would, with the period
// 2 pi / sqrt(2 a g) (the centres' surface is flatter than the floor by about 2 a^2 r:
// 3.92 s here), and keeps doing so: no rule stops it. No step makes energy.
TEST(LongRun, FrictionlessPileInABowlSwingsAsOneBody)
{
  Scene scene;
  scene.floor = bowl(3, 0.3);
  addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.0);
  scene.restitution = 0.5;
  scene.random_balls = randomBalls(60, 4, {0.05, 0.08}, {0.5, 2}, {0, 1});
  World world(scene);
  const double a = 4 * 0.3 / (3 * 3), r = 0.065, g = world.gravity().norm();
  const double period = 2 * M_PI / std::sqrt(2 * (a - 2 * a * a * r) * g);
  double mass = 0;
  for (const Ball& b : world.balls())
    mass += b.mass;
  const auto centre = [&] {
    Vec3 c = Vec3::Zero();
    for (const Ball& b : world.balls())
      c += b.mass * b.position;
    return Vec3(c / mass);
  };
  const double rise = largestEnergyRise(world, 1000);  // 10 s: the balls settle into a pile
  std::vector<double> x, y;
  double worst = rise, first_swing = 0, last_swing = 0;  // the most kinetic energy [J]
  for (int k = 0; k < 2000; ++k)
  {
    worst = std::max(worst, largestEnergyRise(world, 1));
    x.push_back(centre().x());
    y.push_back(centre().y());
    (k < 500 ? first_swing : last_swing) = std::max(k < 500 ? first_swing : last_swing, world.energy().kinetic);
  }
  // (the period from the times the centre of mass crosses its mean, along the axis it
  // swings most along)
  const auto crossings = [&](const std::vector<double>& s) {
    double mean = 0;
    for (const double v : s)
      mean += v / static_cast<double>(s.size());
    std::vector<double> at;
    for (std::size_t k = 1; k < s.size(); ++k)
      if ((s[k - 1] - mean) * (s[k] - mean) < 0)
        at.push_back(static_cast<double>(k) - (s[k] - mean) / (s[k] - s[k - 1]));
    return at;
  };
  const auto span = [](const std::vector<double>& s) {
    return *std::max_element(s.begin(), s.end()) - *std::min_element(s.begin(), s.end());
  };
  const std::vector<double> at = crossings(span(x) > span(y) ? x : y);
  ASSERT_GE(at.size(), 6u);
  const double measured = 2 * (at.back() - at.front()) / static_cast<double>(at.size() - 1) * world.dt();
  EXPECT_NEAR(measured, period, 0.05 * period);
  EXPECT_GT(std::max(span(x), span(y)), 0.05);  // [m]: it swings
  EXPECT_GT(last_swing, 0.5 * first_swing);       // and keeps doing so
  EXPECT_LT(worst, 1e-12 * std::abs(world.energy().total()) + 1e-12);
  EXPECT_EQ(world.stats().sleeping_balls, 0u);
  EXPECT_EQ(world.stats().frozen_balls, 0u);
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
}

// The same 200-ball pile at restitution 0.5 in the walled bowl, from five other random
// starts: each comes to rest and sleeps within 30 s, whichever ball happens to end up
// on the pile's edge (where a ball its neighbours hold still must not keep a speed it
// does not move with, which kept the group awake for good). Skipped under the sanitizers
// (BCS_SLOWDOWN): DissipativePilesComeToRestAndSleep's 60-ball piles in the same walled
// bowl with the same friction run the same code there, in a fifth of the time.
TEST(LongRun, BowlPilesSleepFromAnyStart)
{
  if (std::getenv("BCS_SLOWDOWN") != nullptr)
    GTEST_SKIP() << "the same code as DissipativePilesComeToRestAndSleep's bowl piles, 5 times as long";
  for (const std::uint64_t seed : {5, 6, 7, 8, 9})
  {
    Scene scene;
    scene.floor = bowl(3, 0.3);
    addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.0);
    scene.restitution = 0.5;
    scene.random_balls = randomBalls(200, seed, {0.05, 0.08}, {0.5, 2}, {0, 1});
    scene.friction = pileFriction();
    World world(scene);
    const double k0 = world.energy().kinetic;
    const double rise = largestEnergyRise(world, 3000);
    EXPECT_LT(rise, 1e-12 * std::abs(world.energy().total()) + 1e-12) << "seed " << seed;
    EXPECT_EQ(world.stats().sleeping_balls, 200u) << "seed " << seed;
    EXPECT_LE(world.energy().kinetic, 1e-12 * k0) << "seed " << seed;
    EXPECT_LT(deepestOverlap(world.balls()), 1e-9) << "seed " << seed;
    EXPECT_EQ(world.stats().frozen_balls, 0u) << "seed " << seed;
  }
}

// A sleeping pile wakes where it is hit, and only the group it rests in. Two piles lie
// asleep at the foot of a slope, parted by a wall down its middle; a ball sent uphill on
// one side (an edit, which wakes only what the new ball touches: nothing) comes back
// down into its pile, whose balls wake while the other pile sleeps on; then both sleep.
TEST(Sleep, AnImpactWakesTheGroupItHits)
{
  const double slope = std::tan(10 * M_PI / 180);
  Scene scene = slopeWithWall(40, 10, 0.5, 4, 3.0);
  const Vec3 up = scene.floor->u.cross(scene.floor->v).normalized();
  scene.walls.push_back({Vec3(-1.5, 0, 0) - 0.1 * up, Vec3(3, 0, -3 * slope), 0.5 * up, {}});
  World world(scene);
  for (int k = 0; k < 3000; ++k)
    world.step();
  ASSERT_EQ(world.stats().sleeping_balls, world.balls().size());
  const auto onSide = [&](bool positive) {
    std::size_t asleep = 0, all = 0;
    for (const Ball& b : world.balls())
      if ((b.position.y() > 0) == positive && b.position.x() > 0)
      {
        ++all;
        asleep += b.asleep() ? 1 : 0;
      }
    return std::pair{asleep, all};
  };
  BallDef bowler = ball(0.0, 0.7, -2.0, 0, 0.05, 1.0);  // uphill, on the y > 0 side
  const AddResult added = world.addBall(bowler, Landing::kUnder);
  ASSERT_TRUE(added.ok) << added.error;
  bool other_slept_through = true, hit_woke = false;
  std::uint64_t woken_before = world.stats().woken_balls;
  for (int k = 0; k < 600; ++k)
  {
    world.step();
    const auto [asleep_other, all_other] = onSide(false);
    other_slept_through = other_slept_through && asleep_other == all_other;
    hit_woke = hit_woke || world.stats().woken_balls > woken_before;
  }
  EXPECT_TRUE(hit_woke);
  EXPECT_TRUE(other_slept_through);
  EXPECT_GT(onSide(false).second, 5u);
  for (int k = 0; k < 3000; ++k)
    world.step();
  EXPECT_EQ(world.stats().sleeping_balls, world.balls().size());
  EXPECT_LT(deepestOverlap(world.balls()), 1e-9);
}
