#include "fuzz_checks.hpp"

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/wall.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace ball_collision_sim::fuzz
{
namespace
{
using core::Vec2;
using core::Vec3;

constexpr const char* kSource = "fuzz.yaml";
/// Longest error message accepted: one line a person can read.
constexpr std::size_t kMaxMessage = 1000;
/// Scenes with more random balls than this are left out of the reader target: placing
/// them is slow by design (the soak script runs big scenes).
constexpr int kMaxRandomBalls = 2000;

std::string str(double value)
{
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

/// Why `text` is not one printable line of valid UTF-8, or "".
std::string notOneLine(const std::string& text)
{
  if (text.size() > kMaxMessage)
    return "longer than " + std::to_string(kMaxMessage) + " bytes (" + std::to_string(text.size()) + ")";
  for (std::size_t i = 0; i < text.size();)
  {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f)
      return "control byte " + std::to_string(c) + " at " + std::to_string(i);
    if (c < 0x80)
    {
      ++i;
      continue;
    }
    // a UTF-8 sequence: lead byte, then continuation bytes 10xxxxxx
    const std::size_t length = (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
    if (length == 0 || c == 0xc0 || c == 0xc1 || c > 0xf4 || i + length > text.size())
      return "invalid UTF-8 at byte " + std::to_string(i);
    for (std::size_t k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80)
        return "invalid UTF-8 at byte " + std::to_string(i);
    i += length;
  }
  return "";
}

/// Why the world's balls are not all finite, or "".
std::string nonFinite(const core::World& world)
{
  for (std::size_t k = 0; k < world.balls().size(); ++k)
  {
    const core::Ball& b = world.balls()[k];
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.orientation.coeffs().allFinite() ||
        !world.angularVelocity(k).allFinite())
      return "ball " + std::to_string(b.id) + " is not finite (position " + str(b.position.x()) + ", " +
             str(b.position.y()) + ", " + str(b.position.z()) + ", velocity " + str(b.velocity.x()) + ", " +
             str(b.velocity.y()) + ", " + str(b.velocity.z()) + ")";
  }
  return "";
}

// ---- bytes to numbers ----------------------------------------------------------------

/// Reads numbers from the fuzz bytes; past their end every read gives 0.
class Bytes
{
public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint16_t u16()
  {
    std::uint16_t v = 0;
    for (int k = 0; k < 2; ++k)
      v = static_cast<std::uint16_t>((v << 8) | (pos_ < size_ ? data_[pos_++] : 0));
    return v;
  }
  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  /// [0, 1], in 65536 steps (both ends reachable)
  double unit() { return u16() / 65535.0; }
  double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// log-uniform in [lo, hi], lo > 0
  double logRange(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  int integer(int lo, int hi) { return lo + static_cast<int>(u8() % (hi - lo + 1)); }
  bool flag() { return (u8() & 1) != 0; }

private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// Signed distance of q from the wall's plane, positive on the side of `inside`.
double insideDistance(const core::Wall& wall, const Vec3& inside, const Vec3& q)
{
  const double side = (inside - wall.def.point).dot(wall.normal) >= 0 ? 1.0 : -1.0;
  return side * (q - wall.def.point).dot(wall.normal);
}

/// Kinetic and potential energy and the scale that round-off is measured against.
struct EnergyScale
{
  double total = 0.0;
  double scale = 0.0;
};

EnergyScale energyOf(const core::World& world)
{
  EnergyScale e;
  for (std::size_t k = 0; k < world.balls().size(); ++k)
  {
    const core::Ball& b = world.balls()[k];
    double kinetic = 0.5 * b.mass * b.velocity.squaredNorm();
    if (world.friction())  // (the spins' too, where balls have their own)
      kinetic += 0.5 * world.inertia(k) * b.mass * b.radius * b.radius * world.angularVelocity(k).squaredNorm();
    const double potential = -b.mass * world.gravity().dot(b.position);
    e.total += kinetic + potential;
    e.scale += kinetic + std::abs(potential);
  }
  return e;
}
}  // namespace

std::string checkSceneReader(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  core::Scene scene;
  try
  {
    scene = yaml::parseScene(text, kSource);
  }
  catch (const yaml::SceneError& e)
  {
    const std::string message = e.what();
    if (message.rfind(std::string(kSource) + ":", 0) != 0)
      return "error message does not start with the source name: " + message;
    if (message.size() <= std::strlen(kSource) + 2)
      return "error message gives no reason: " + message;
    if (const std::string why = notOneLine(message); !why.empty())
      return "error message is not one printable line (" + why + "): " + message.substr(0, 200);
    return "";
  }
  catch (const std::exception& e)
  {
    return std::string("parseScene threw an exception other than SceneError: ") + e.what();
  }

  if (scene.random_balls && scene.random_balls->count > kMaxRandomBalls)
    return "";
  std::vector<core::SceneIssue> issues;
  try
  {
    issues = core::validate(scene);
  }
  catch (const std::exception& e)
  {
    return std::string("validate threw: ") + e.what();
  }
  for (const core::SceneIssue& issue : issues)
  {
    if (issue.key.empty() || issue.reason.empty())
      return "an issue without key or reason: " + issue.str();
    if (const std::string why = notOneLine(issue.str()); !why.empty())
      return "issue is not one printable line (" + why + "): " + issue.str().substr(0, 200);
  }
  if (!issues.empty())
    return "";

  // Valid: it must build a world, with finite states. (Stepping is the step target's
  // job: a valid scene may take long per step, e.g. dt 5 s with 200 balls in a 4 m box.)
  try
  {
    const core::World world(scene);
    if (const std::string bad = nonFinite(world); !bad.empty())
      return "a valid scene starts with " + bad;
  }
  catch (const std::exception& e)
  {
    return std::string("World refused a scene that validate() accepted: ") + e.what();
  }
  return "";
}

StepCase decodeStepCase(const std::uint8_t* data, std::size_t size)
{
  Bytes in(data, size);
  StepCase out;
  core::Scene& scene = out.scene;

  const double side = in.range(0.5, 8.0);  // the floor spans [-side/2, side/2]^2 in x and y
  const double x0 = -side / 2;
  const bool curved = in.flag();
  const bool closed = in.u8() % 8 != 0;  // a box of walls around the floor, most of the time

  // gravity: mostly straight down, sometimes tilted or none
  const double g = in.u8() % 8 == 0 ? 0.0 : in.range(0.0, 20.0);
  const bool tilted = in.u8() % 4 == 0;
  // (one read per statement: the order in which a call's arguments are evaluated is up to
  // the compiler, and gcc and clang must decode the same scene)
  const double gx = tilted ? in.range(-0.3, 0.3) * g : 0.0;
  const double gy = tilted ? in.range(-0.3, 0.3) * g : 0.0;
  scene.gravity = Vec3(gx, gy, -g);

  core::FloorDef floor;
  double z_min = 0, z_max = 0;
  if (curved)
  {
    floor.type = core::FloorDef::Type::kBiquadratic;
    // x and y on a regular grid, so the surface is regular and its edges lie in the
    // planes x, y = +-side/2; heights free
    const double relief = in.range(0.0, 0.4) * side;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        const double z = in.range(-relief, relief);
        floor.control_points[i][j] = Vec3(x0 + 0.5 * side * i, x0 + 0.5 * side * j, z);
        z_min = std::min(z_min, z);
        z_max = std::max(z_max, z);
      }
  }
  else
  {
    floor.type = core::FloorDef::Type::kPlane;
    const double sx = in.range(-0.5, 0.5), sy = in.range(-0.5, 0.5);  // slopes
    floor.point = Vec3(x0, x0, 0);
    floor.u = Vec3(side, 0, side * sx);
    floor.v = Vec3(0, side, side * sy);
    z_min = std::min({0.0, side * sx, side * sy, side * (sx + sy)});
    z_max = std::max({0.0, side * sx, side * sy, side * (sx + sy)});
  }
  scene.floor = floor;

  scene.restitution = in.u8() % 4 == 0 ? 1.0 : in.unit();
  scene.dt = in.logRange(1e-4, 0.05);
  out.steps = 1 + in.u8() % 200;

  const double max_radius = in.range(0.01, 0.3) * std::min(1.0, side / 4);
  // walls reach well below and above the floor, so no ball passes over or under them
  const double reach = 1.0 + 4 * max_radius;
  const double low = z_min - reach, high = z_max + reach;
  const auto wallRestitution = [&]() -> std::optional<double> {
    if (in.u8() % 4 != 0)
      return std::nullopt;
    return in.unit();
  };
  if (closed)
  {
    const Vec3 up(0, 0, high - low);
    scene.walls.push_back({Vec3(x0, x0, low), Vec3(side, 0, 0), up, wallRestitution()});
    scene.walls.push_back({Vec3(x0, -x0, low), Vec3(side, 0, 0), up, wallRestitution()});
    scene.walls.push_back({Vec3(x0, x0, low), Vec3(0, side, 0), up, wallRestitution()});
    scene.walls.push_back({Vec3(-x0, x0, low), Vec3(0, side, 0), up, wallRestitution()});
    out.box_walls = 4;
  }
  // a few walls inside, of any height and lean
  const int inner = in.integer(0, 2);
  for (int k = 0; k < inner; ++k)
  {
    const double px = in.range(x0, -x0);
    const double py = in.range(x0, -x0);
    const Vec3 point(px, py, low);
    const double angle = in.range(0, 2 * M_PI);
    const Vec3 u = in.range(0.05, 1.0) * side * Vec3(std::cos(angle), std::sin(angle), 0);
    const double lean_x = in.range(-0.5, 0.5);
    const double lean_y = in.range(-0.5, 0.5);
    const Vec3 v(lean_x, lean_y, in.range(0.05, 1.0) * (high - low));
    scene.walls.push_back({point, u, v, wallRestitution()});
  }

  // balls on the floor, dropped when they would overlap one placed before or a wall
  const core::Floor surface(floor, scene.gravity);
  std::vector<core::Wall> walls;
  for (std::size_t k = 0; k < scene.walls.size(); ++k)
    walls.emplace_back(static_cast<int>(k), scene.walls[k], scene.restitution);
  const int count = in.integer(1, 8);
  for (int k = 0; k < count; ++k)
  {
    core::BallDef ball;
    ball.radius = in.range(0.2, 1.0) * max_radius;
    ball.mass = in.logRange(0.01, 100.0);
    const double foot_u = in.range(0.0, 1.0);
    const Vec2 uv(foot_u, in.range(0.0, 1.0));
    ball.position = surface.point(uv) + ball.radius * surface.normal(uv);
    double speed = in.flag() ? in.range(0.0, 3.0) : in.logRange(1e-3, 1e3);
    if (curved)
      speed = std::min(speed, kCurvedFloorStepFraction * side / scene.dt);
    const double heading = in.range(0, 2 * M_PI);
    ball.velocity = speed * Vec3(std::cos(heading), std::sin(heading), in.range(-0.2, 0.2));
    bool clear = true;
    for (const core::BallDef& other : scene.balls)
      clear = clear && (other.position - ball.position).norm() >= other.radius + ball.radius;
    for (const core::Wall& wall : walls)
      clear = clear && wall.distance(ball.position) >= ball.radius;
    if (clear)
      scene.balls.push_back(ball);
  }
  // Friction, from bytes after the rest (inputs kept from before it decode as they did):
  // coefficients up to 1 (some exactly 0), and each ball's spin and inertia.
  if (in.u8() % 2 == 1)
  {
    core::FrictionDef f;
    for (double* mu : {&f.sliding, &f.rolling, &f.spinning, &f.ball_ball, &f.wall})
      *mu = in.u8() % 4 == 0 ? 0.0 : in.range(0.0, 1.0);
    scene.friction = f;
    for (core::BallDef& ball : scene.balls)
    {
      ball.inertia = in.u8() % 2 == 0 ? core::kSolidInertia : in.range(0.05, 1.0);
      if (in.flag())
      {
        const double spin = in.logRange(1e-3, 1e3);
        const double wx = in.range(-1, 1), wy = in.range(-1, 1), wz = in.range(-1, 1);
        ball.angular_velocity = spin * Vec3(wx, wy, wz);
      }
    }
  }
  // Pockets, from bytes after those: up to three, anywhere over the floor, of up to a
  // quarter of its side.
  const int pockets = in.u8() % 4;
  for (int k = 0; k < pockets; ++k)
  {
    const double pu = in.range(0.0, 1.0);
    const Vec3 at = surface.point(Vec2(pu, in.range(0.0, 1.0)));
    scene.pockets.push_back({Vec2(at.x(), at.y()), in.range(0.01, 0.25) * side});
  }
  return out;
}

std::string checkStepping(const std::uint8_t* data, std::size_t size)
{
  const StepCase c = decodeStepCase(data, size);
  if (!core::validate(c.scene).empty())
    return "";
  core::World world(c.scene);
  const std::vector<core::Wall> walls = world.walls();
  std::size_t count = world.balls().size();
  const Vec3 centre = world.floor()->point(Vec2(0.5, 0.5));
  // Balls that have flown (a curved floor throws fast ones off its crests) may clear the
  // box's walls, whose height is finite: they are held to every check but staying in it.
  std::set<int> flown;
  if (const std::string bad = nonFinite(world); !bad.empty())
    return "at the start: " + bad;
  EnergyScale before = energyOf(world);

  for (int k = 1; k <= c.steps; ++k)
  {
    world.step();
    const std::string at = "step " + std::to_string(k) + ": ";
    if (const std::string bad = nonFinite(world); !bad.empty())
      return at + bad;
    // A ball that drops into a pocket leaves with its energy at the drop (taken), its
    // centre on the circle (or inside it, where it started the step there).
    double taken = 0.0;
    for (const core::PocketedBall& out : world.lastPocketed())
    {
      const core::Ball& b = out.ball;
      taken += 0.5 * b.mass * b.velocity.squaredNorm() - b.mass * world.gravity().dot(b.position);
      if (world.friction())
        taken += 0.5 * out.inertia * b.mass * b.radius * b.radius * out.angular_velocity.squaredNorm();
      const core::PocketDef& pocket = c.scene.pockets.at(static_cast<std::size_t>(out.pocket));
      const double off = (Vec2(out.ball.position.x(), out.ball.position.y()) - pocket.position).norm();
      if (!(off <= pocket.radius * (1 + 1e-9) + kOverlapTolerance))
        return at + "ball " + std::to_string(out.ball.id) + " dropped into pocket " + std::to_string(out.pocket) +
               " " + str(off - pocket.radius) + " m outside its circle";
      if (world.findBall(out.ball.id) != nullptr)
        return at + "ball " + std::to_string(out.ball.id) + " dropped into a pocket and is still in the world";
    }
    count -= world.lastPocketed().size();
    const core::BallList balls = world.balls();
    if (balls.size() != count)
      return at + "the ball count changed";
    for (std::size_t i = 0; i < balls.size(); ++i)
    {
      const core::Ball& a = balls[i];
      if (a.flying())
        flown.insert(a.id);
      const bool may_leave = flown.count(a.id) > 0;
      for (std::size_t j = i + 1; j < balls.size(); ++j)
      {
        const double depth = a.radius + balls[j].radius - (a.position - balls[j].position).norm();
        if (depth > kOverlapTolerance)
          return at + "balls " + std::to_string(a.id) + " and " + std::to_string(balls[j].id) + " overlap by " +
                 str(depth) + " m";
      }
      for (std::size_t w = 0; w < walls.size(); ++w)
      {
        const double depth = a.radius - walls[w].distance(a.position);
        if (depth > kOverlapTolerance)
          return at + "ball " + std::to_string(a.id) + " overlaps wall " + std::to_string(w) + " by " + str(depth) +
                 " m";
        if (w < c.box_walls && !may_leave && insideDistance(walls[w], centre, a.position) < a.radius - kOverlapTolerance)
          return at + "ball " + std::to_string(a.id) + " is outside wall " + std::to_string(w) + " of the box";
      }
    }
    if (c.box_walls == 4 && flown.empty() && world.lostBalls() != 0)
      return at + std::to_string(world.lostBalls()) + " balls left the walled floor";
    const EnergyScale after = energyOf(world);
    const double allowed = kEnergyRelativeTolerance * before.scale + kEnergyAbsoluteTolerance;
    if (!(after.total + taken - before.total <= allowed))
      return at + "energy rose from " + str(before.total) + " J to " + str(after.total + taken) + " J (by " +
             str(after.total + taken - before.total) + " J, allowed " + str(allowed) + " J; " + str(taken) +
             " J of it dropped into pockets)";
    before = after;
    // Lost balls are taken out after each step, as the node and `simulate` do: a ball past
    // the edge of a floor without walls would otherwise go on down the surface's
    // polynomial beyond it, ever faster, each step dearer to follow than the last.
    if (const std::size_t lost = world.removeLostBalls().size(); lost > 0)
    {
      count -= lost;
      before = energyOf(world);
    }
  }
  return "";
}

std::vector<std::string> filesIn(const std::string& dir)
{
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file())
      files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
}  // namespace ball_collision_sim::fuzz
