// Friction at resting contacts against closed forms: a ball pressed against a wall
// across a slope rolls along it turning about the floor's normal as well, held by the
// wall's friction where that can hold it (its effective mass (1 + 2k) m), and slides along
// the wall at the rate Coulomb's law gives where it cannot.
#include "fixtures.hpp"

#include "ball_collision_sim/core/friction.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;

/// A plane `side` [m] square sloped `degrees` downhill along +x, with friction.
struct Slope
{
  Scene scene;
  Vec3 down;       // the fall line, unit
  Vec3 across;     // +y, unit
  Vec3 normal;     // the floor's, up
  double g_t = 0;  // gravity along the floor [m/s^2]

  Slope(double degrees, const FrictionDef& f, double side = 8)
  {
    const double a = degrees * M_PI / 180;
    FloorDef floor;
    floor.point = Vec3(-side / 2, -side / 2, side / 2 * std::tan(a));
    floor.u = Vec3(side, 0, -side * std::tan(a));
    floor.v = Vec3(0, side, 0);
    scene.floor = floor;
    scene.friction = f;
    down = floor.u.normalized();
    across = Vec3::UnitY();
    normal = floor.u.cross(floor.v).normalized();
    g_t = kG * std::sin(a);
  }
  /// The point of the floor over (x, y).
  Vec3 at(double x, double y) const { return Vec3(x, y, -x * (down.z() / down.x())); }
};

/// A wall on `slope` through the floor's point over the origin, along t (downhill, phi
/// from the fall line toward +y), and a ball of radius r at rest on the floor against it
/// on the side gravity presses it to.
struct WallRun
{
  Vec3 t, q, start;
};
WallRun wallAcross(Slope& slope, double phi, double r, double k)
{
  WallRun run;
  run.t = std::cos(phi) * slope.down + std::sin(phi) * slope.across;
  run.q = slope.normal.cross(run.t);  // the wall's normal along the floor
  // (gravity along the floor presses toward -q: the ball lies on the +q side)
  const Vec3 w0 = slope.at(0, 0);
  slope.scene.walls.push_back({w0 - 3 * run.t, 6 * run.t, 0.5 * slope.normal, {}});
  run.start = w0 + r * run.q + r * slope.normal;
  BallDef b = ball(0, 0, 0, 0, r);
  b.position = run.start;
  b.inertia = k;
  slope.scene.balls = {b};
  return run;
}

void runFor(World& world, double t)
{
  while (world.time() < t - 1e-9) world.step();
}
}  // namespace

struct AgainstAWall
{
  double phi;
  double mu_wall;
  double k;
};
class BallAgainstAWall : public ::testing::TestWithParam<AgainstAWall>
{
};

// Pressed with N = m g_t sin(phi), pulled along the wall by m g_t cos(phi). Friction holds
// the wall's touching point where k cos / (1 + 2k) <= mu_w sin: the ball then turns about
// the axis through both of its touching points, a = g_t cos / (1 + 2k), its spin about the
// floor's normal a t / r. Else it slips along the wall, a = g_t (cos - mu_w sin) / (1 + k),
// its spin about the normal growing at mu_w g_t sin / (k r). Velocity to 1e-12 m/s and spin
// to 1e-10 rad/s after 1 s; the position as a group's time step gives it.
TEST_P(BallAgainstAWall, RollsOrSlipsAlongItAsTheLawsSay)
{
  const AgainstAWall c = GetParam();
  const double r = 0.1;
  Slope slope(10, friction(0.5, 0.0));
  slope.scene.friction->wall = c.mu_wall;
  const WallRun run = wallAcross(slope, c.phi, r, c.k);
  World world(slope.scene);
  const double T = 1.0;
  runFor(world, T);
  const double press = slope.g_t * std::sin(c.phi), pull = slope.g_t * std::cos(c.phi);
  const bool holds = c.k * pull / (1 + 2 * c.k) <= c.mu_wall * press;
  const double a = holds ? pull / (1 + 2 * c.k) : (pull - c.mu_wall * press) / (1 + c.k);
  const double spin_rate = holds ? a / r : c.mu_wall * press / (c.k * r);
  const Ball& b = world.balls()[0];
  // (a group's time step moves it with its velocity at the step's end, Moreau's: after N
  // steps of dt from rest, a dt^2 N (N + 1) / 2)
  EXPECT_NEAR((b.position - run.start).dot(run.t), 0.5 * a * T * (T + world.dt()), 1e-12);
  EXPECT_NEAR((b.position - run.start).dot(run.q), 0.0, 1e-12);
  EXPECT_NEAR(b.velocity.dot(run.t), a * T, 1e-12);
  EXPECT_NEAR(std::abs(world.angularVelocity(0).dot(slope.normal)), spin_rate * T, 1e-10);
  EXPECT_EQ(world.stats().unsettled_contacts, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Walls, BallAgainstAWall,
    ::testing::Values(AgainstAWall{M_PI / 6, 0.3, kSolidInertia}, AgainstAWall{M_PI / 4, 0.3, kSolidInertia},
                      AgainstAWall{M_PI / 6, 0.1, kSolidInertia}, AgainstAWall{M_PI / 4, 0.5, kHollowInertia},
                      AgainstAWall{M_PI / 4, 0.05, kHollowInertia}, AgainstAWall{M_PI / 6, 0.0, kSolidInertia}));

// Two balls against the wall, B pressing A (N_ab = m g_t sin, N_w = 2 m g_t sin), over
// the step where their contacts are first solved. Where friction holds at both, A turns
// about the axis through its two touching points on the floor and the wall (spin about
// the normal s_A = -v_A / r) and B rolls on A as a gear does (r s_B = 2 v_A - v_B): with
// g' = g_t cos the kinetic energy (m/2)((1 + 2k) v_A^2 + (1 + k) v_B^2 + k (2 v_A - v_B)^2)
// gives a_A = g' (1 + 4k) / D and a_B = g' (1 + 8k) / D, D = 1 + 8k + 8k^2; that needs
// k m g' / D of friction between them (and less than the wall's bound at the wall). Where
// mu_b N_ab is less, B slips on A, pushed on by F = mu_b N_ab: a_B = (g' + F/m) / (1 + k),
// r s_B' = F / (k m), while A, its touching point on B moving at 2 v_A, is held back by
// 2F: a_A = (g' - 2F/m) / (1 + 2k). Without friction between them B rolls on at
// g' / (1 + k) with no spin about the normal, and A at g' / (1 + 2k).
TEST(TwoBallsAgainstAWall, TurnOrSlipAsTheirFrictionsHold)
{
  const double r = 0.1, k = kSolidInertia, phi = M_PI / 4;
  for (const double mu_ball : {0.6, 0.02, 0.0})
  {
    Slope slope(10, friction(0.5, 0.0));
    slope.scene.friction->wall = 0.6;
    slope.scene.friction->ball_ball = mu_ball;
    const WallRun run = wallAcross(slope, phi, r, k);
    BallDef b = slope.scene.balls[0];
    b.position = run.start + 2 * r * run.q;
    slope.scene.balls.push_back(b);
    World world(slope.scene);
    world.step();
    const double g = slope.g_t * std::cos(phi), D = 1 + 8 * k + 8 * k * k, dt = world.dt();
    const double F = mu_ball * slope.g_t * std::sin(phi);  // (per unit mass)
    const bool holds = k * g / D <= F;
    const double a_a = holds ? g * (1 + 4 * k) / D : (g - 2 * F) / (1 + 2 * k);
    const double a_b = holds ? g * (1 + 8 * k) / D : (g + F) / (1 + k);
    const double spin_b = holds ? (2 * a_a - a_b) / r : F / (k * r);
    const std::size_t ia = world.indexOf(1), ib = world.indexOf(2);
    const Ball& A = world.balls()[ia];
    const Ball& B = world.balls()[ib];
    EXPECT_NEAR(A.velocity.dot(run.t), a_a * dt, 1e-15) << mu_ball;
    EXPECT_NEAR(B.velocity.dot(run.t), a_b * dt, 1e-15) << mu_ball;
    const double s_a = world.angularVelocity(ia).dot(slope.normal), s_b = world.angularVelocity(ib).dot(slope.normal);
    EXPECT_NEAR(s_a, -a_a * dt / r, 1e-14) << mu_ball;
    EXPECT_NEAR(s_b, spin_b * dt, 1e-14) << mu_ball;
    EXPECT_NEAR(A.velocity.dot(run.q), 0.0, 1e-15);
    EXPECT_NEAR(B.velocity.dot(run.q), 0.0, 1e-14);
    EXPECT_EQ(world.stats().unsettled_contacts, 0);
  }
}

// A pile on a 10 degree slope against its low wall, with friction at every contact (0.3
// between balls and at walls): no step raises the energy (rotation counted), no two balls
// overlap, every group's contacts are solved, and the pile comes to rest within 20 s
// (without contact friction it does within 4 s, lower: friction holds it looser).
TEST(SlopePile, SettlesWithFrictionAtItsContacts)
{
  for (const std::uint64_t seed : {1u, 2u})
  {
    Scene scene = slopeWithWall(40, 10, 0.5, seed);
    scene.friction = pileFriction();
    scene.friction->ball_ball = 0.3;
    scene.friction->wall = 0.3;
    World world(scene);
    const double scale = std::abs(world.energy().total()) + 1.0;
    const WorstOfRun worst = stepWatching(world, 2000, [](int) { return true; });
    EXPECT_LE(worst.energy_rise, 1e-9 * scale) << seed;
    EXPECT_LE(worst.overlap, 1e-9) << seed;
    EXPECT_EQ(world.stats().unsettled_contacts, 0) << seed;
    double fastest = 0;
    for (const Ball& b : world.balls()) fastest = std::max(fastest, b.velocity.norm());
    EXPECT_LT(fastest, 1e-6) << seed;
  }
}

// Three balls jammed in a funnel on a 10 degree slope (walls converging downhill at 30
// degrees to the fall line, to an outlet 2.5 r wide): two abreast where it narrows to
// their width, one a little ahead of the other, and one dropped on them. Without friction
// the two slip past each other and all three run out through the outlet; with friction at
// the contacts (0.3, and at walls) the jam holds and comes to rest above the outlet
// within 5 s (the top ball first rolls around one below, turning about the axis through
// its touching points on the floor and on that ball, until it sits in the gap).
TEST(FunnelJam, FrictionHoldsWhatRunsOutWithout)
{
  const double r = 0.1, alpha = M_PI / 6, w0 = 1.25 * r;
  for (const double mu : {0.0, 0.3})
  {
    Slope slope(10, friction(0.5, 0.01, 0.044), 6);
    slope.scene.restitution = 0.5;
    slope.scene.friction->ball_ball = mu;
    slope.scene.friction->wall = mu;
    const Vec3 o = slope.at(0, 0);
    const auto at = [&](double s, double c) { return o + s * slope.down + c * slope.across + r * slope.normal; };
    const Vec3 left = -std::cos(alpha) * slope.down - std::sin(alpha) * slope.across;
    const Vec3 right = -std::cos(alpha) * slope.down + std::sin(alpha) * slope.across;
    slope.scene.walls.push_back({o - w0 * slope.across, 3 * left, 0.5 * slope.normal, {}});
    slope.scene.walls.push_back({o + w0 * slope.across, 3 * right, 0.5 * slope.normal, {}});
    // (where the funnel is 4r wide between the centres' reach: both balls touch a wall and each other)
    const double s_arch = -((r + r / std::cos(alpha)) - w0) / std::tan(alpha);
    BallDef a = ball(0, 0, 0, 0, r);
    BallDef b = a, c = a;
    a.position = at(s_arch, -r);
    b.position = at(s_arch - 0.05, r);
    c.position = at(s_arch - 3.5 * r, 0);
    slope.scene.balls = {a, b, c};
    World world(slope.scene);
    const WorstOfRun worst = stepWatching(world, 500, [](int) { return true; });
    double fastest = 0, lowest = -1e300;
    for (const Ball& x : world.balls())
    {
      fastest = std::max(fastest, x.velocity.norm());
      lowest = std::max(lowest, (x.position - o).dot(slope.down));
    }
    EXPECT_LE(worst.energy_rise, 1e-9) << mu;
    EXPECT_LE(worst.overlap, 1e-9) << mu;
    EXPECT_EQ(world.stats().unsettled_contacts, 0) << mu;
    if (mu > 0)
    {
      EXPECT_LT(lowest, 0.0) << "the jam runs out";
      EXPECT_LT(fastest, 1e-6);
    }
    else
      EXPECT_GT(lowest + world.lostBalls(), 0.5) << "the jam holds without friction";
  }
}
