#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace ball_collision_sim::test
{
using core::BallDef;
using core::FloorDef;
using core::Scene;
using core::Vec3;
using core::WallDef;

/// A flat floor [x0, x1] x [y0, y1] at z = 0, gravity straight down, no walls or balls.
inline Scene flatScene(double x0 = -2, double x1 = 2, double y0 = -2, double y1 = 2)
{
  Scene s;
  FloorDef f;
  f.type = FloorDef::Type::kPlane;
  f.point = Vec3(x0, y0, 0);
  f.u = Vec3(x1 - x0, 0, 0);
  f.v = Vec3(0, y1 - y0, 0);
  s.floor = f;
  return s;
}

/// Four walls of the given height around [x0, x1] x [y0, y1], standing on z = base.
inline void addBox(Scene& s, double x0, double x1, double y0, double y1, double height = 0.5, double base = 0.0)
{
  const double w = x1 - x0, d = y1 - y0;
  s.walls.push_back({Vec3(x0, y0, base), Vec3(w, 0, 0), Vec3(0, 0, height), {}});
  s.walls.push_back({Vec3(x0, y1, base), Vec3(w, 0, 0), Vec3(0, 0, height), {}});
  s.walls.push_back({Vec3(x0, y0, base), Vec3(0, d, 0), Vec3(0, 0, height), {}});
  s.walls.push_back({Vec3(x1, y0, base), Vec3(0, d, 0), Vec3(0, 0, height), {}});
}

inline BallDef ball(double x, double y, double vx, double vy, double radius = 0.1, double mass = 1.0)
{
  BallDef b;
  b.position = Vec3(x, y, radius);
  b.velocity = Vec3(vx, vy, 0);
  b.radius = radius;
  b.mass = mass;
  return b;
}

/// `count` random balls drawn with `seed`, their radius, mass and speed uniform in the
/// given ranges.
inline core::RandomBallsDef randomBalls(int count, std::uint64_t seed, core::Range radius, core::Range mass,
                                        core::Range speed)
{
  core::RandomBallsDef rb;
  rb.count = count;
  rb.seed = seed;
  rb.radius = radius;
  rb.mass = mass;
  rb.speed = speed;
  return rb;
}

/// The biquadratic with control z = f_i + f_j, f = (h, -h, h), over [-L/2, L/2]^2: its
/// height is exactly the paraboloid z = 4 h (x^2 + y^2) / L^2.
inline FloorDef bowl(double L, double h)
{
  FloorDef f;
  f.type = FloorDef::Type::kBiquadratic;
  const double c[3] = {-L / 2, 0, L / 2};
  const double z[3] = {h, -h, h};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(c[i], c[j], z[i] + z[j]);
  return f;
}

/// The saddle z = (x^2 - y^2) h / 4 over [-2, 2]^2 (control z = f_i - f_j, f = (h, -h, h)).
inline FloorDef saddle(double h)
{
  FloorDef f;
  f.type = FloorDef::Type::kBiquadratic;
  const double c[3] = {-2, 0, 2};
  const double z[3] = {h, -h, h};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(c[i], c[j], z[i] - z[j]);
  return f;
}

/// A dome: corners at height 0, the edges' middles and the centre at 8, over [-4, 4]^2.
/// Along its diagonal x = y its section is z(w) = 6 - 16 w^2 - 32 w^4 (w = s - 1/2 on the
/// diagonal's parameter s, xi = 8 sqrt(2) w along it), a crest of curvature 1/4 at the top
/// that bends more the further down: a ball on it leaves the floor part way down.
inline FloorDef dome()
{
  FloorDef f;
  f.type = FloorDef::Type::kBiquadratic;
  const double c[3] = {-4, 0, 4};
  const double z[3][3] = {{0, 8, 0}, {8, 8, 8}, {0, 8, 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f.control_points[i][j] = Vec3(c[i], c[j], z[i][j]);
  return f;
}

/// A friction block of these coefficients (the others 0).
inline core::FrictionDef friction(double sliding, double rolling, double spinning = 0.0)
{
  core::FrictionDef f;
  f.sliding = sliding;
  f.rolling = rolling;
  f.spinning = spinning;
  return f;
}

/// Friction for piles in a bowl (sliding 0.2, rolling resistance 0.01, spinning 0.044):
/// what takes their energy as they come to rest. The test bowls are paraboloids, where a
/// frictionless pile's centre of mass swings as one body for good (every ball is pulled
/// toward the bottom in proportion to its distance from it, and no contact inside the
/// pile closes for that motion).
inline core::FrictionDef pileFriction()
{
  return friction(0.2, 0.01, 0.044);
}

/// 60 balls (radius 0.05-0.08 m, 0.5-2 kg, up to 1 m/s) dropped in a 3 m square bowl
/// 0.6 m deep, walled in on its rim, at restitution 0.5: they settle into a pile at its
/// bottom.
inline Scene bowlPile(std::uint32_t seed)
{
  Scene scene;
  scene.floor = bowl(3, 0.3);
  addBox(scene, -1.5, 1.5, -1.5, 1.5, 1.0);  // walls on the rim: past it a ball falls off the floor
  scene.restitution = 0.5;
  scene.random_balls = randomBalls(60, seed, {0.05, 0.08}, {0.5, 2}, {0, 1});
  return scene;
}

/// 80 balls (radius 0.05-0.08 m, 0.5-2 kg, up to 1 m/s) dropped on a 2 m square slope
/// falling 0.4 m along +x, walled in, at restitution 0.5: they settle into a pile.
inline Scene slopePile()
{
  Scene scene;
  FloorDef f;
  f.point = Vec3(-1, -1, 0);
  f.u = Vec3(2, 0, -0.4);  // downhill along +x
  f.v = Vec3(0, 2, 0);
  scene.floor = f;
  scene.restitution = 0.5;
  const Vec3 up = f.u.cross(f.v).normalized();
  scene.walls = {{f.point, f.u, 0.5 * up, {}},
                 {f.point + f.v, f.u, 0.5 * up, {}},
                 {f.point, f.v, 0.5 * up, {}},
                 {f.point + f.u, f.v, 0.5 * up, {}}};
  scene.random_balls = randomBalls(80, 4, {0.05, 0.08}, {0.5, 2}, {0, 1});
  return scene;
}

/// `count` balls (radius 0.05-0.08 m, 0.5-2 kg, up to 1 m/s) dropped on a square plane
/// of `side` [m] sloped `degrees` along +x, walled in with walls of the balls'
/// restitution: they gather against the wall at the low end.
inline Scene slopeWithWall(int count, double degrees, double restitution, std::uint64_t seed, double side = 2)
{
  Scene scene;
  const double t = std::tan(degrees * M_PI / 180);
  FloorDef f;
  f.point = Vec3(-side / 2, -side / 2, 0);
  f.u = Vec3(side, 0, -side * t);  // downhill along +x
  f.v = Vec3(0, side, 0);
  scene.floor = f;
  scene.restitution = restitution;
  const Vec3 up = f.u.cross(f.v).normalized();
  scene.walls = {{f.point, f.u, 0.5 * up, {}},
                 {f.point + f.v, f.u, 0.5 * up, {}},
                 {f.point, f.v, 0.5 * up, {}},
                 {f.point + f.u, f.v, 0.5 * up, {}}};
  scene.random_balls = randomBalls(count, seed, {0.05, 0.08}, {0.5, 2}, {0, 1});
  return scene;
}

/// No floor: `count` balls of 0.1 m and 1 kg dropped in a column (0.25 m apart, from
/// 0.2 m up, at random across a 0.9 m square and drifting up to 0.45 m/s sideways) into a
/// 1.2 m square box of five walls, 30 m tall, its bottom wall at z = 0; restitution e
/// everywhere. They pile on the bottom wall, a few layers deep.
inline Scene floorlessBoxDrop(int count, double e, std::uint64_t seed)
{
  Scene scene;
  scene.restitution = e;
  const double half = 0.6, height = 30;
  scene.walls.push_back({Vec3(-half, -half, 0), Vec3(2 * half, 0, 0), Vec3(0, 2 * half, 0), {}});
  addBox(scene, -half, half, -half, half, height);
  for (WallDef& wall : scene.walls)
    wall.restitution = e;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  for (int k = 0; k < count; ++k)
  {
    BallDef b;
    b.radius = 0.1;
    b.mass = 1;
    b.position = Vec3(u(rng), u(rng), 0.2 + 0.25 * k);
    b.velocity = Vec3(u(rng), u(rng), 0);
    scene.balls.push_back(b);
  }
  return scene;
}

/// A tight jam: balls of radius 0.1 m and 1 kg stacked in square packing, layers of
/// `base` x `base`, then (base - 1)^2 on their hollows, down to `top` x `top` (base 7 and
/// top 1: 140 balls; 8: 204), in a floorless box of five walls that they fill, each
/// ball off its place by up to 1e-6 of its radius (and the packing opened by 2e-6 so
/// that none overlaps) and moving at up to 0.1 m/s, as `seed` gives; restitution 0.5.
inline Scene squareJam(int base, int top, std::uint64_t seed)
{
  Scene scene;
  scene.restitution = 0.5;
  const double r = 0.1, open = 1 + 2e-6, side = 2 * r * base * open;
  scene.walls.push_back({Vec3(0, 0, 0), Vec3(side, 0, 0), Vec3(0, side, 0), {}});
  addBox(scene, 0, side, 0, side, 2 * r * base);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int layer = 0; base - layer >= top; ++layer)
    for (int i = 0; i < base - layer; ++i)
      for (int j = 0; j < base - layer; ++j)
      {
        BallDef b;
        b.radius = r;
        b.mass = 1;
        b.position = open * r * Vec3(2 * i + 1 + layer, 2 * j + 1 + layer, 1 + layer * std::sqrt(2.0)) +
                     1e-6 * r * Vec3(unit(rng), unit(rng), unit(rng));
        b.velocity = 0.1 * Vec3(unit(rng), unit(rng), unit(rng)) / std::sqrt(3.0);
        scene.balls.push_back(b);
      }
  return scene;
}

/// Adds a ball of radius 0.01 m, on the floor, at the first free place of a 20 x 20 grid
/// over [x0, x1] x [y0, y1] and removes it again; false when there was no room.
inline bool addAndRemoveABall(core::World& world, double x0, double x1, double y0, double y1)
{
  for (int k = 0; k < 400; ++k)
  {
    BallDef b = ball(x0 + (x1 - x0) * (k % 20 + 0.5) / 20, y0 + (y1 - y0) * (k / 20 + 0.5) / 20, 0, 0, 0.01);
    if (world.floor())
      b.position = world.floor()->ballCentre(world.floor()->project(b.position, core::Vec2(0.5, 0.5)), b.radius);
    const core::AddResult added = world.addBall(b);
    if (added.ok)
      return world.removeBall(added.id);
  }
  return false;
}

/// Steps the world `steps` times: the largest rise of its total energy in one step.
inline double largestEnergyRise(core::World& world, int steps)
{
  double before = world.energy().total();
  double largest = 0;
  for (int k = 0; k < steps; ++k)
  {
    world.step();
    const double now = world.energy().total();
    largest = std::max(largest, now - before);
    before = now;
  }
  return largest;
}

/// Deepest overlap between any two balls [m] (<= 0 when none overlap), by a sweep in x.
template <class Balls>
double deepestOverlap(const Balls& balls)
{
  std::vector<std::size_t> order(balls.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return balls[a].position.x() - balls[a].radius < balls[b].position.x() - balls[b].radius;
  });
  double deepest = -1e300;
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    const auto& a = balls[order[k]];
    for (std::size_t l = k + 1; l < order.size(); ++l)
    {
      const auto& b = balls[order[l]];
      if (b.position.x() - b.radius > a.position.x() + a.radius)
        break;
      deepest = std::max(deepest, a.radius + b.radius - (a.position - b.position).norm());
    }
  }
  return deepest;
}

/// The worst that stepping showed: the largest rise of the total energy in one step [J],
/// and the deepest overlap between two balls after any step [m].
struct WorstOfRun
{
  double energy_rise = 0;
  double overlap = -1e300;
};

/// Steps the world `steps` times, calling after_step(k) after step k (from 0), and returns
/// the worst of the run; stops early where after_step returns false.
template <class AfterStep>
WorstOfRun stepWatching(core::World& world, int steps, AfterStep&& after_step)
{
  WorstOfRun worst;
  double before = world.energy().total();
  for (int k = 0; k < steps; ++k)
  {
    world.step();
    const double now = world.energy().total();
    worst.energy_rise = std::max(worst.energy_rise, now - before);
    before = now;
    worst.overlap = std::max(worst.overlap, deepestOverlap(world.balls()));
    if (!after_step(k))
      break;
  }
  return worst;
}
}  // namespace ball_collision_sim::test
