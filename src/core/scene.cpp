#include "ball_collision_sim/core/scene.hpp"

#include "scene_checker.hpp"

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ball_collision_sim::core
{
namespace
{
using scene_checks::Checker;
using scene_checks::index;

bool checkFloor(Checker& check, const FloorDef& floor)
{
  if (floor.restitution)
    check.unitInterval("floor.restitution", *floor.restitution);
  if (floor.type == FloorDef::Type::kPlane)
  {
    const bool point_ok = check.bounded("floor.point", floor.point, kMaxLength, "m");
    return check.edges("floor.", floor.u, floor.v) && point_ok;
  }
  bool ok = true;
  double scale = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
    {
      const std::string key = index(index("floor.control_points", i), j);
      ok = check.bounded(key, floor.control_points[i][j], kMaxLength, "m") && ok;
      if (ok)
        scale = std::max(scale, (floor.control_points[i][j] - floor.control_points[0][0]).norm());
    }
  if (!ok)
    return false;
  // A regular surface has a normal everywhere on [0, 1]^2: sample it densely.
  const Floor surface(floor, Vec3(0, 0, -1));
  constexpr int kSamples = 16;
  for (int a = 0; a <= kSamples; ++a)
    for (int b = 0; b <= kSamples; ++b)
    {
      const Vec2 uv(double(a) / kSamples, double(b) / kSamples);
      const double h = 1e-6;
      const Vec3 su = surface.point(uv + Vec2(h, 0)) - surface.point(uv - Vec2(h, 0));
      const Vec3 sv = surface.point(uv + Vec2(0, h)) - surface.point(uv - Vec2(0, h));
      if (!(su.cross(sv).norm() > 1e-9 * scale * scale * h * h) || scale == 0)
      {
        check.fail("floor.control_points",
                   "degenerate surface (no normal at u = " + formatNumber(uv.x()) + ", v = " + formatNumber(uv.y()) + ")");
        return false;
      }
    }
  return true;
}

bool checkBall(Checker& check, const std::string& prefix, const BallDef& ball)
{
  bool ok = check.bounded(prefix + "position", ball.position, kMaxLength, "m");
  ok = check.bounded(prefix + "velocity", ball.velocity, kMaxSpeed, "m/s") && ok;
  ok = check.positive(prefix + "radius", ball.radius, kMinLength, kMaxLength, "m") && ok;
  ok = check.positive(prefix + "mass", ball.mass, kMinMass, kMaxMass, "kg") && ok;
  if (ball.angular_velocity)
    ok = check.bounded(prefix + "angular_velocity", *ball.angular_velocity, kMaxSpin, "rad/s") && ok;
  ok = check.inertia(prefix + "inertia", ball.inertia) && ok;
  return ok;
}

bool checkWall(Checker& check, const std::string& prefix, const WallDef& wall)
{
  bool ok = check.bounded(prefix + "point", wall.point, kMaxLength, "m");
  ok = check.edges(prefix, wall.u, wall.v) && ok;
  if (wall.restitution)
    ok = check.unitInterval(prefix + "restitution", *wall.restitution) && ok;
  return ok;
}

/// A pocket: its radius > 0, its centre over the floor (`floor`, where it is sound).
void checkPocket(Checker& check, const std::string& prefix, const PocketDef& pocket, const std::optional<FloorDef>& floor,
                 const Vec3& gravity)
{
  const Vec3 centre(pocket.position.x(), pocket.position.y(), 0.0);
  const bool placed = check.bounded(prefix + "position", centre, kMaxLength, "m");
  check.positive(prefix + "radius", pocket.radius, kMinLength, kMaxLength, "m");
  if (!placed || !floor)
    return;
  // (over the floor: a point dropped along gravity from there lands on it)
  BallDef probe;
  probe.position = centre;
  probe.radius = kMinLength;
  const std::optional<Floor> surface(std::in_place, *floor, gravity);
  if (const std::string why = placeOnFloor(probe, surface, nullptr, Landing::kUnder); !why.empty())
    check.fail(prefix + "position", "must be over the floor: " + why);
}

/// Explicit balls that overlap one another, by a sweep over x (no all-pairs loop).
void checkOverlaps(Checker& check, const std::vector<BallDef>& placed, const std::vector<bool>& usable)
{
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < placed.size(); ++i)
    if (usable[i])
      order.push_back(i);
  auto low = [&](std::size_t i) { return placed[i].position.x() - placed[i].radius; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return low(a) < low(b) || (low(a) == low(b) && a < b);
  });
  std::vector<std::size_t> active;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i : order)
  {
    const BallDef& bi = placed[i];
    active.erase(std::remove_if(active.begin(), active.end(),
                                [&](std::size_t j) {
                                  return placed[j].position.x() + placed[j].radius < low(i);
                                }),
                 active.end());
    for (std::size_t j : active)
    {
      const double gap = (bi.position - placed[j].position).norm() - bi.radius - placed[j].radius;
      if (gap < -kContactTolerance)
        pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
    active.push_back(i);
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [a, b] : pairs)
  {
    const double depth = placed[a].radius + placed[b].radius - (placed[a].position - placed[b].position).norm();
    check.fail(index("balls", b), overlapMessage(index("balls", a), depth));
  }
}

/// The explicit balls that are sound in themselves (`usable`) put on the floor: off the
/// floor, overlapping a wall or another ball.
void checkPlacement(Checker& check, const Scene& scene, std::vector<bool>& usable)
{
  const Placement placement(scene);
  std::vector<BallDef> placed = scene.balls;
  for (std::size_t i = 0; i < scene.balls.size(); ++i)
  {
    if (!usable[i])
      continue;
    const std::string why = placement.place(placed[i]);
    if (!why.empty())
    {
      check.fail(index("balls", i) + (why.rfind("overlaps", 0) == 0 ? "" : ".position"), why);
      usable[i] = false;
    }
  }
  checkOverlaps(check, placed, usable);
}

/// The random balls' definition, and (when the rest of the scene is fine) whether they
/// all fit: the balls placed.
std::vector<Ball> checkRandomBalls(Checker& check, const Scene& scene, bool fine_so_far)
{
  std::vector<Ball> random;
  const RandomBallsDef& rb = *scene.random_balls;
  bool ok = true;
  if (rb.count < 0 || rb.count > 10'000'000)
  {
    check.fail("random_balls.count", "must be in [0, 10000000] (got " + std::to_string(rb.count) + ")");
    ok = false;
  }
  ok = check.range("random_balls.radius", rb.radius, kMinLength, false, kMaxLength) && ok;
  ok = check.range("random_balls.mass", rb.mass, kMinMass, false, kMaxMass) && ok;
  ok = check.range("random_balls.speed", rb.speed, 0, false, kMaxSpeed) && ok;
  ok = check.inertia("random_balls.inertia", rb.inertia) && ok;
  if (rb.region)
  {
    const bool fin = check.finite("random_balls.region.min", Vec3(rb.region->min.x(), rb.region->min.y(), 0)) &&
                     check.finite("random_balls.region.max", Vec3(rb.region->max.x(), rb.region->max.y(), 0));
    if (fin && !(rb.region->min.array() < rb.region->max.array()).all())
    {
      check.fail("random_balls.region", "min must be below max in x and y");
      ok = false;
    }
    ok = ok && fin;
  }
  if (!scene.floor)
  {
    check.fail("random_balls", "needs a floor to place the balls on");
    ok = false;
  }
  if (ok && fine_so_far && rb.count > 0)
  {
    random = placeRandomBallRecords(scene);
    if (random.size() < static_cast<std::size_t>(rb.count))
      check.fail("random_balls.count", "room for only " + std::to_string(random.size()) + " of " +
                                           std::to_string(rb.count) +
                                           " balls (use fewer or smaller balls, or a larger region)");
  }
  return random;
}

}  // namespace

const char* placementName(BallPlacement placement)
{
  return placement == BallPlacement::kAsGiven ? "as_given" : "on_floor";
}

std::vector<SceneIssue> validateBall(const BallDef& ball, const std::string& prefix)
{
  std::vector<SceneIssue> issues;
  Checker check(issues);
  checkBall(check, prefix, ball);
  return issues;
}

std::vector<SceneIssue> validateWall(const WallDef& wall, const std::string& prefix)
{
  std::vector<SceneIssue> issues;
  Checker check(issues);
  checkWall(check, prefix, wall);
  return issues;
}

std::string joinIssues(const std::vector<SceneIssue>& issues)
{
  std::string out;
  for (const SceneIssue& issue : issues)
    out += (out.empty() ? "" : "; ") + issue.str();
  return out;
}

namespace
{
/// The scene's explicit balls, and then `random` ones, each put on the floor: in the
/// list of the random ones, which has room for the others ahead of them.
PlacedBalls land(const Scene& scene, std::vector<Ball> random)
{
  std::optional<Floor> floor;
  if (scene.floor)
    floor.emplace(*scene.floor, scene.gravity);
  const std::size_t own = scene.balls.size();
  PlacedBalls out;
  out.feet.assign(own + random.size(), Vec2(0.5, 0.5));  // (the first guess of each foot point)
  const auto put = [&](BallDef def, Ball& ball, Vec2& foot) {
    bool flying = false;
    placeOnFloor(def, floor, &foot, landingOf(def.placement), &flying);
    ball = ballRecord(def);
    ball.support = flying ? Ball::Support::kAir : Ball::Support::kFloor;
  };
  for (std::size_t k = 0; k < random.size(); ++k)
    put(randomBallDef(scene, random[k]), random[k], out.feet[own + k]);
  random.insert(random.begin(), own, Ball{});
  for (std::size_t k = 0; k < own; ++k)
    put(scene.balls[k], random[k], out.feet[k]);
  out.balls = std::move(random);
  return out;
}
}  // namespace

std::vector<SceneIssue> validate(const Scene& scene)
{
  return check(scene).issues;
}

PlacedBalls placeBalls(const Scene& scene)
{
  return land(scene, placeRandomBallRecords(scene));
}

SceneCheck check(const Scene& scene)
{
  SceneCheck out;
  std::vector<SceneIssue>& issues = out.issues;
  Checker check(issues);

  if (scene.frame_id.empty())
    check.fail("frame_id", "must not be empty");
  if (check.finite("dt", scene.dt) && !(scene.dt > 0 && scene.dt <= 10))
    check.fail("dt", "must be in (0, 10] s (got " + formatNumber(scene.dt) + ")");
  const bool gravity_ok = check.bounded("gravity", scene.gravity, 1e6, "m/s^2");
  check.unitInterval("restitution", scene.restitution);

  const bool floor_ok = !scene.floor || checkFloor(check, *scene.floor);
  if (scene.friction)
  {
    const FrictionDef& f = *scene.friction;
    for (const auto& [key, value] : {std::pair{"friction.sliding", f.sliding}, std::pair{"friction.rolling", f.rolling},
                                     std::pair{"friction.spinning", f.spinning},
                                     std::pair{"friction.ball_ball", f.ball_ball}, std::pair{"friction.wall", f.wall}})
      check.nonNegative(key, value, kMaxFriction);
    if (!scene.floor)
      check.fail("friction", "needs a floor (friction acts between the balls and the floor)");
  }

  bool walls_ok = true;
  for (std::size_t i = 0; i < scene.walls.size(); ++i)
    walls_ok = checkWall(check, index("walls", i) + ".", scene.walls[i]) && walls_ok;

  for (std::size_t i = 0; i < scene.pockets.size(); ++i)
    checkPocket(check, index("pockets", i) + ".", scene.pockets[i], floor_ok && gravity_ok ? scene.floor : std::nullopt,
                scene.gravity);
  if (!scene.pockets.empty() && !scene.floor)
    check.fail("pockets", "needs a floor (a pocket is a hole in it)");

  std::vector<bool> usable(scene.balls.size(), false);
  for (std::size_t i = 0; i < scene.balls.size(); ++i)
    usable[i] = checkBall(check, index("balls", i) + ".", scene.balls[i]);

  // Geometry only once the objects themselves are sound, so one mistake gives one issue.
  if (gravity_ok && floor_ok && walls_ok)
    checkPlacement(check, scene, usable);
  std::vector<Ball> random =
      scene.random_balls ? checkRandomBalls(check, scene, issues.empty()) : std::vector<Ball>();
  if (issues.empty())
    out.balls = land(scene, std::move(random));
  return out;
}

std::vector<BallDef> allBalls(const Scene& scene)
{
  std::vector<BallDef> balls = scene.balls;
  const std::vector<BallDef> random = placeRandomBalls(scene);
  balls.insert(balls.end(), random.begin(), random.end());
  return balls;
}
}  // namespace ball_collision_sim::core
