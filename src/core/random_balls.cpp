#include "ball_collision_sim/core/broad_phase.hpp"
#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>

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


/// The balls placed so far (the scene's own first), each listed in the one cell of its
/// centre: a new ball looks in the cells within reach of any centre that could be too close.
class Obstacles
{
public:
  Obstacles(const Placement& placement, const Scene& scene, std::size_t asked) : placement_(placement)
  {
    // The explicit balls, placed, are obstacles too; the balls placed here follow them.
    max_radius_ = scene.random_balls->radius.max;
    // (room for all asked for, and for the scene's own balls again ahead of them, up to a
    // point: memory reserved and not filled is not touched; past it the list grows)
    balls_.reserve(2 * scene.balls.size() + std::min<std::size_t>(asked, kReservedUpTo));
    for (BallDef ball : scene.balls)
      if (placement.place(ball).empty())
      {
        record(ball);
        max_radius_ = std::max(max_radius_, ball.radius);
      }
    listed_ = balls_.size();
    // (sized for the balls asked for up to a point: the grid grows as it fills, and a count
    // far beyond the room is refused without its table)
    grid_.reset(2 * max_radius_, balls_.size() + std::min<std::size_t>(asked, 1 << 16));
    for (std::size_t k = 0; k < balls_.size(); ++k)
      grid_.insert(static_cast<std::uint32_t>(k), sweptBox(balls_[k].position, balls_[k].position, 0));
  }
  /// Whether `ball` keeps its clearance from every wall and every ball placed so far.
  bool clear(const BallDef& ball) const
  {
    const auto& walls = placement_.walls();
    if (std::any_of(walls.begin(), walls.end(),
                    [&](const Wall& w) { return w.distance(ball.position) < ball.radius + kClearance; }))
      return false;
    bool clear = true;
    const Aabb box = sweptBox(ball.position, ball.position, ball.radius + max_radius_ + kClearance);
    grid_.query(box, [&](std::uint32_t k) {
      const Ball& o = balls_[k];
      if ((o.position - ball.position).norm() < o.radius + ball.radius + kClearance)
        clear = false;
    });
    return clear;
  }
  void add(const BallDef& def)
  {
    const Ball& ball = record(def);
    grid_.insert(static_cast<std::uint32_t>(balls_.size() - 1), sweptBox(ball.position, ball.position, 0));
  }
  long placed() const { return static_cast<long>(balls_.size() - listed_); }
  /// The balls placed here, without the scene's own.
  std::vector<Ball> take()
  {
    balls_.erase(balls_.begin(), balls_.begin() + static_cast<std::ptrdiff_t>(listed_));
    return std::move(balls_);
  }

private:
  /// The ball's record at the end of the list.
  const Ball& record(const BallDef& def) { return balls_.emplace_back(ballRecord(def)); }

  const Placement& placement_;
  static constexpr std::size_t kReservedUpTo = std::size_t{1} << 20;  ///< 104 MiB of room at most
  std::vector<Ball> balls_;
  std::size_t listed_ = 0;
  double max_radius_ = 0.0;
  UniformGrid grid_;
};

/// One ball drawn at random on the part of the floor the definition asks for: its size,
/// mass and foot point; no velocity yet (drawn only for a ball that fits, so that the
/// draws stay as they are). Empty where the ball's centre falls outside the region.
std::optional<BallDef> drawBall(std::mt19937_64& rng, const RandomBallsDef& def, const Floor& floor,
                                const Vec2& uv_min, const Vec2& uv_max, Vec3& normal)
{
  BallDef ball;
  ball.radius = uniform(rng, def.radius.min, def.radius.max);
  ball.mass = uniform(rng, def.mass.min, def.mass.max);
  const Vec2 uv(uniform(rng, uv_min.x(), uv_max.x()), uniform(rng, uv_min.y(), uv_max.y()));
  normal = floor.normal(uv);
  ball.position = floor.point(uv) + ball.radius * normal;
  if (def.region && ((ball.position.head<2>().array() < def.region->min.array()).any() ||
                     (ball.position.head<2>().array() > def.region->max.array()).any()))
    return std::nullopt;
  return ball;
}
}  // namespace

std::vector<BallDef> placeRandomBalls(const Scene& scene)
{
  std::vector<BallDef> out;
  for (const Ball& ball : placeRandomBallRecords(scene))
    out.push_back(randomBallDef(scene, ball));
  return out;
}

Ball ballRecord(const BallDef& def)
{
  Ball ball;
  ball.position = def.position;
  ball.velocity = def.velocity;
  ball.radius = def.radius;
  ball.mass = def.mass;
  return ball;
}

BallDef randomBallDef(const Scene& scene, const Ball& ball)
{
  BallDef def;
  def.position = ball.position;
  def.velocity = ball.velocity;
  def.radius = ball.radius;
  def.mass = ball.mass;
  def.inertia = scene.random_balls ? scene.random_balls->inertia : kSolidInertia;
  return def;
}

std::vector<Ball> placeRandomBallRecords(const Scene& scene)
{
  if (!scene.random_balls || !scene.floor || scene.random_balls->count <= 0)
    return {};
  const RandomBallsDef& def = *scene.random_balls;
  const Placement placement(scene);
  const Floor& floor = *placement.floor();
  Obstacles obstacles(placement, scene, static_cast<std::size_t>(def.count));

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
  for (long attempt = 0; attempt < max_attempts && obstacles.placed() < def.count && misses < kMaxMissesInARow;
       ++attempt)
  {
    ++misses;  // until this attempt places its ball
    Vec3 n;
    std::optional<BallDef> ball = drawBall(rng, def, floor, uv_min, uv_max, n);
    if (!ball || !obstacles.clear(*ball))
      continue;
    const double speed = uniform(rng, def.speed.min, def.speed.max);
    const double angle = uniform(rng, 0.0, 2 * M_PI);
    Vec3 e1, e2;
    tangentBasis(n, e1, e2);
    ball->velocity = speed * (std::cos(angle) * e1 + std::sin(angle) * e2);
    obstacles.add(*ball);
    misses = 0;
  }
  return obstacles.take();
}
}  // namespace ball_collision_sim::core
