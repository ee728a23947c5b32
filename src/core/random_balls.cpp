#include "ball_collision_sim/core/broad_phase.hpp"
#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace ball_collision_sim::core
{
namespace
{
/// Uniform in [lo, hi] from the generator's bits: std::uniform_real_distribution is
/// implementation-defined, and the same seed must give the same scene everywhere.
double uniform(std::mt19937_64& rng, double lo, double hi)
{
  const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * unit;
}

/// A unit vector tangent to the floor, and the one 90 degrees from it.
void tangentBasis(const Vec3& n, Vec3& e1, Vec3& e2)
{
  const Vec3 ref = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  e1 = (ref - ref.dot(n) * n).normalized();
  e2 = n.cross(e1);
}

/// Extra clearance kept between placed balls and from walls [m].
constexpr double kClearance = 1e-6;

/// The range of the floor's parameters (u, v) that lies under a region of x and y, with a
/// margin (the floor's parameters need not be linear in x and y).
void parametersUnder(const Floor& floor, const RandomBallsDef::Region& region, Vec2& uv_min, Vec2& uv_max)
{
  const double z = floor.point(Vec2(0.5, 0.5)).z();
  uv_min = Vec2(1, 1);
  uv_max = Vec2(0, 0);
  for (int c = 0; c < 4; ++c)
  {
    const Vec3 corner((c & 1) ? region.max.x() : region.min.x(), (c & 2) ? region.max.y() : region.min.y(), z);
    const Vec2 uv = floor.project(corner, Vec2(0.5, 0.5)).uv;
    uv_min = uv_min.cwiseMin(uv);
    uv_max = uv_max.cwiseMax(uv);
  }
  const Vec2 margin = 0.05 * (uv_max - uv_min) + Vec2::Constant(0.01);
  uv_min = (uv_min - margin).cwiseMax(Vec2::Zero());
  uv_max = (uv_max + margin).cwiseMin(Vec2::Ones());
}
}  // namespace

std::vector<BallDef> placeRandomBalls(const Scene& scene)
{
  if (!scene.random_balls || !scene.floor || scene.random_balls->count <= 0)
    return {};
  const RandomBallsDef& def = *scene.random_balls;
  const Placement placement(scene);
  const Floor& floor = *placement.floor();

  // The explicit balls, placed, are obstacles too; the balls placed here follow them.
  std::vector<BallDef> obstacles;
  double max_radius = def.radius.max;
  for (BallDef ball : scene.balls)
    if (placement.place(ball).empty())
    {
      obstacles.push_back(ball);
      max_radius = std::max(max_radius, ball.radius);
    }
  const std::size_t listed = obstacles.size();
  // Each obstacle is listed in the one cell of its centre; a new ball looks in the cells
  // within reach of any centre that could be too close.
  UniformGrid grid;
  // (sized for the balls asked for up to a point: the grid grows as it fills, and a count
  // far beyond the room is refused without its table)
  grid.reset(2 * max_radius, obstacles.size() + std::min<std::size_t>(static_cast<std::size_t>(def.count), 1 << 16));
  for (std::size_t k = 0; k < obstacles.size(); ++k)
    grid.insert(static_cast<std::uint32_t>(k), sweptBox(obstacles[k].position, obstacles[k].position, 0));

  // Parameters to draw from: the whole floor, or the part under the region.
  Vec2 uv_min(0, 0), uv_max(1, 1);
  if (def.region)
    parametersUnder(floor, *def.region, uv_min, uv_max);

  std::mt19937_64 rng(def.seed);
  const long max_attempts = 100L * def.count + 1000;
  // A full floor fails every attempt: give up after this many misses in a row, or a count
  // far beyond the room (up to 10^7) takes 100 attempts a ball, minutes, to be refused.
  constexpr long kMaxMissesInARow = 100000;
  long misses = 0;
  const auto placed = [&] { return static_cast<long>(obstacles.size() - listed); };
  for (long attempt = 0; attempt < max_attempts && placed() < def.count && misses < kMaxMissesInARow; ++attempt)
  {
    ++misses;  // until this attempt places its ball
    BallDef ball;
    ball.radius = uniform(rng, def.radius.min, def.radius.max);
    ball.mass = uniform(rng, def.mass.min, def.mass.max);
    const Vec2 uv(uniform(rng, uv_min.x(), uv_max.x()), uniform(rng, uv_min.y(), uv_max.y()));
    const Vec3 foot = floor.point(uv);
    const Vec3 n = floor.normal(uv);
    ball.position = foot + ball.radius * n;
    if (def.region && ((ball.position.head<2>().array() < def.region->min.array()).any() ||
                       (ball.position.head<2>().array() > def.region->max.array()).any()))
      continue;
    const auto near_wall = std::any_of(placement.walls().begin(), placement.walls().end(), [&](const Wall& w) {
      return w.distance(ball.position) < ball.radius + kClearance;
    });
    if (near_wall)
      continue;
    bool clear = true;
    const Aabb box = sweptBox(ball.position, ball.position, ball.radius + max_radius + kClearance);
    grid.query(box, [&](std::uint32_t k) {
      const BallDef& o = obstacles[k];
      if ((o.position - ball.position).norm() < o.radius + ball.radius + kClearance)
        clear = false;
    });
    if (!clear)
      continue;
    const double speed = uniform(rng, def.speed.min, def.speed.max);
    const double angle = uniform(rng, 0.0, 2 * M_PI);
    Vec3 e1, e2;
    tangentBasis(n, e1, e2);
    ball.velocity = speed * (std::cos(angle) * e1 + std::sin(angle) * e2);
    obstacles.push_back(ball);
    grid.insert(static_cast<std::uint32_t>(obstacles.size() - 1), sweptBox(ball.position, ball.position, 0));
    misses = 0;
  }
  obstacles.erase(obstacles.begin(), obstacles.begin() + static_cast<std::ptrdiff_t>(listed));
  return obstacles;
}
}  // namespace ball_collision_sim::core
