#pragma once
// The benchmark scenes, built in code so that this package and the peer engines get the
// very same balls. The YAML files beside this one describe the same scenes for users.

#include "ball_collision_sim/core/scene.hpp"

#include <cmath>
#include <cstdint>
#include <random>

namespace ball_collision_sim::bench
{
using core::BallDef;
using core::Scene;
using core::Vec3;

/// A flat floor [0, side]^2 at z = 0 (gravity normal to it), walls of height h around
/// it, dt 0.01 s.
inline Scene squareBox(double side, double h)
{
  Scene s;
  core::FloorDef f;
  f.point = Vec3(0, 0, 0);
  f.u = Vec3(side, 0, 0);
  f.v = Vec3(0, side, 0);
  s.floor = f;
  s.dt = 0.01;
  s.walls = {{Vec3(0, 0, 0), Vec3(side, 0, 0), Vec3(0, 0, h), {}},
             {Vec3(0, side, 0), Vec3(side, 0, 0), Vec3(0, 0, h), {}},
             {Vec3(0, 0, 0), Vec3(0, side, 0), Vec3(0, 0, h), {}},
             {Vec3(side, 0, 0), Vec3(0, side, 0), Vec3(0, 0, h), {}}};
  return s;
}

/// Uniform in [lo, hi] from the generator's bits (the same on every machine).
inline double uniform(std::mt19937_64& rng, double lo, double hi)
{
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// S1 billiards: n balls of radius 0.05 m and 1 kg on a flat floor, gravity normal to it,
/// in a square box sized for a 30 % area fraction; velocity components uniform in
/// [-2, 2] m/s; restitution 1; dt 0.01 s. Balls start on a jittered grid, clear of each
/// other and of the walls.
inline Scene billiards(int n, std::uint64_t seed = 1)
{
  constexpr double r = 0.05;
  const double side = std::sqrt(n * M_PI * r * r / 0.3);
  Scene s = squareBox(side, 0.2);
  s.restitution = 1.0;
  const int per_row = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double pitch = side / per_row;
  const double jitter = 0.49 * (pitch - 2 * r);
  std::mt19937_64 rng(seed);
  for (int k = 0; k < n; ++k)
  {
    BallDef b;
    b.radius = r;
    b.mass = 1.0;
    b.position = Vec3((k % per_row + 0.5) * pitch + uniform(rng, -jitter, jitter),
                      (k / per_row + 0.5) * pitch + uniform(rng, -jitter, jitter), r);
    b.velocity = Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), 0);
    s.balls.push_back(b);
  }
  return s;
}

/// S1 with friction: S1's balls and box with pooltool's cloth (mu_s 0.2, mu_r 0.01,
/// mu_sp 0.044) and ball-ball restitution 0.95; every ball starts sliding without spin
/// (struck through its centre), so that it slides, rolls and, after about 20 s, stops.
inline Scene billiardsFriction(int n, std::uint64_t seed = 1)
{
  Scene s = billiards(n, seed);
  s.restitution = 0.95;
  core::FrictionDef f;
  f.sliding = 0.2;
  f.rolling = 0.01;
  f.spinning = 0.044;
  s.friction = f;
  for (BallDef& b : s.balls)
    b.angular_velocity = Vec3::Zero();
  return s;
}

/// S2 bullets: 100 balls of radius 0.02 m at 200 m/s in a 2 m box of thin walls; 1 s.
inline Scene bullets(std::uint64_t seed = 2)
{
  constexpr int n = 100;
  constexpr double r = 0.02, side = 2.0;
  Scene s = squareBox(side, 0.2);
  std::mt19937_64 rng(seed);
  const double pitch = side / 10;
  for (int k = 0; k < n; ++k)
  {
    BallDef b;
    b.radius = r;
    b.position = Vec3((k % 10 + 0.5) * pitch, (k / 10 + 0.5) * pitch, r);
    const double angle = uniform(rng, 0, 2 * M_PI);
    b.velocity = Vec3(200 * std::cos(angle), 200 * std::sin(angle), 0);
    s.balls.push_back(b);
  }
  return s;
}

/// S3 bowl: n balls on the paraboloid z = (x^2 + y^2) / 8 over [-2, 2]^2 (a biquadratic),
/// inside walls; speeds up to 1 m/s.
inline Scene bowl(int n, std::uint64_t seed = 3)
{
  Scene s;
  core::FloorDef f;
  f.type = core::FloorDef::Type::kBiquadratic;
  const double c[3] = {-2, 0, 2}, h[3] = {0.5, -0.5, 0.5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(c[i], c[j], h[i] + h[j]);
  s.floor = f;
  s.dt = 0.01;
  s.walls = {{Vec3(-2, -2, 0), Vec3(4, 0, 0), Vec3(0, 0, 1.5), {}},
             {Vec3(-2, 2, 0), Vec3(4, 0, 0), Vec3(0, 0, 1.5), {}},
             {Vec3(-2, -2, 0), Vec3(0, 4, 0), Vec3(0, 0, 1.5), {}},
             {Vec3(2, -2, 0), Vec3(0, 4, 0), Vec3(0, 0, 1.5), {}}};
  core::RandomBallsDef rb;
  rb.count = n;
  rb.seed = seed;
  rb.radius = {0.03, 0.03};
  rb.speed = {0, 1};
  s.random_balls = rb;
  return s;
}
/// S4 bowl pile: S3's bowl at restitution 0.5 with n balls of radius 0.05-0.08 m and
/// mass 0.5-2 kg, which settle into a pile at its bottom (measured once settled).
inline Scene bowlPile(int n, std::uint64_t seed = 4)
{
  Scene s = bowl(n, seed);
  s.restitution = 0.5;
  s.random_balls->radius = {0.05, 0.08};
  s.random_balls->mass = {0.5, 2};
  return s;
}
/// S4 at rest: the same pile with friction (sliding 0.2, rolling resistance 0.01, spinning
/// 0.044), which comes to rest and sleeps. (S3's bowl is a paraboloid: without friction a
/// pile's centre of mass swings about its bottom as one body, and no contact inside the
/// pile takes that energy.)
inline Scene bowlPileAtRest(int n, std::uint64_t seed = 4)
{
  Scene s = bowlPile(n, seed);
  core::FrictionDef f;
  f.sliding = 0.2;
  f.rolling = 0.01;
  f.spinning = 0.044;
  s.friction = f;
  return s;
}
/// S5 gas in flight: n balls of radius 0.05 m and 1 kg without a floor, in a closed cube
/// of walls (faces on all six sides) sized for a 2 % volume fraction, under gravity;
/// they start on a cubic lattice, velocity components uniform in [-2, 2] m/s;
/// restitution 1; dt 0.01 s. Balls spread along "up" as much as across.
inline Scene gasInFlight(int n, std::uint64_t seed = 5)
{
  Scene s;
  s.dt = 0.01;
  const double r = 0.05;
  const double side = std::cbrt(n * (4.0 / 3.0) * M_PI * r * r * r / 0.02);
  const Vec3 x(side, 0, 0), y(0, side, 0), z(0, 0, side);
  s.walls = {{Vec3::Zero(), x, z, {}}, {y, x, z, {}}, {Vec3::Zero(), y, z, {}},
             {x, y, z, {}},            {Vec3::Zero(), x, y, {}}, {z, x, y, {}}};
  const int per = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
  const double gap = side / per;
  std::mt19937_64 rng(seed);
  for (int k = 0; k < n; ++k)
  {
    BallDef b;
    b.radius = r;
    b.position = gap * Vec3(0.5 + k % per, 0.5 + (k / per) % per, 0.5 + k / (per * per));
    b.velocity = Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2));
    s.balls.push_back(b);
  }
  return s;
}
}  // namespace ball_collision_sim::bench
