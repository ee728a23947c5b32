// A scene as YAML text: block style, every key with its value (defaults included), and
// each real in the fewest digits that read back to the same double.
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace ball_collision_sim::yaml
{
namespace
{
/// The shortest text that reads back to `value` (std::to_chars), kept a real in YAML 1.1
/// too (rosparam's reader): a decimal point, and a signed exponent after one.
std::string real(double value)
{
  if (std::isnan(value))
    return ".nan";
  if (std::isinf(value))
    return value > 0 ? ".inf" : "-.inf";
  char buffer[64];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  const std::size_t e = text.find('e');
  const std::string mantissa = text.substr(0, e);
  std::string exponent = e == std::string::npos ? "" : text.substr(e + 1);
  std::string out = mantissa.find('.') == std::string::npos ? mantissa + ".0" : mantissa;
  if (!exponent.empty())
    out += "e" + std::string(exponent[0] == '-' || exponent[0] == '+' ? "" : "+") + exponent;
  return out;
}

std::string vec(const core::Vec3& v)
{
  return "[" + real(v.x()) + ", " + real(v.y()) + ", " + real(v.z()) + "]";
}

std::string vec(const core::Vec2& v)
{
  return "[" + real(v.x()) + ", " + real(v.y()) + "]";
}

std::string range(const core::Range& r)
{
  return "[" + real(r.min) + ", " + real(r.max) + "]";
}

/// A double-quoted YAML string.
std::string quoted(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

void writeFloor(std::ostream& out, const core::FloorDef& floor)
{
  out << "floor:\n";
  if (floor.type == core::FloorDef::Type::kPlane)
  {
    out << "  type: plane\n  point: " << vec(floor.point) << "\n  u: " << vec(floor.u) << "\n  v: " << vec(floor.v)
        << "\n";
  }
  else
  {
    out << "  type: biquadratic\n  control_points:\n";
    for (const auto& row : floor.control_points)
      out << "    - [" << vec(row[0]) << ", " << vec(row[1]) << ", " << vec(row[2]) << "]\n";
  }
  if (floor.restitution)
    out << "  restitution: " << real(*floor.restitution) << "\n";
}

void writeRandomBalls(std::ostream& out, const core::RandomBallsDef& random)
{
  out << "random_balls:\n  count: " << random.count << "\n  seed: " << random.seed << "\n  radius: " << range(random.radius)
      << "\n  mass: " << range(random.mass) << "\n  speed: " << range(random.speed) << "\n";
  if (random.inertia != core::kSolidInertia)
    out << "  inertia: " << real(random.inertia) << "\n";
  if (random.region)
    out << "  region: {min: " << vec(random.region->min) << ", max: " << vec(random.region->max) << "}\n";
}

void writeNodeSettings(std::ostream& out, const NodeSettings& node)
{
  auto flag = [](bool value) { return value ? "true" : "false"; };
  out << "real_time_factor: " << real(node.real_time_factor) << "\nmarker_rate: " << real(node.marker_rate)
      << "\ntf_rate: " << real(node.tf_rate) << "\ntf_max_balls: " << node.tf_max_balls
      << "\nstate_rate: " << real(node.state_rate) << "\npublish_collisions: " << flag(node.publish_collisions)
      << "\nstart_paused: " << flag(node.start_paused) << "\nclick_radius: " << real(node.click_radius)
      << "\nclick_mass: " << real(node.click_mass) << "\nstatus_period: " << real(node.status_period)
      << "\nmax_balls: " << node.max_balls << "\nmarker_list_threshold: " << node.marker_list_threshold
      << "\nplay_max_balls: " << node.play_max_balls
      << "\nball_color: " << ballColorName(node.ball_color)
      << "\nspeed_color_max: " << real(node.speed_color_max)
      << "\ncollision_flashes: " << flag(node.collision_flashes) << "\nthreads: " << node.threads << "\n";
  if (node.publish_clock)
    out << "publish_clock: " << flag(*node.publish_clock) << "\n";
  if (node.frame_prefix)
    out << "frame_prefix: " << quoted(*node.frame_prefix) << "\n";
}
}  // namespace

std::string writeScene(const core::Scene& scene, const NodeSettings& node)
{
  std::ostringstream out;
  out << "frame_id: " << quoted(scene.frame_id) << "\ndt: " << real(scene.dt) << "\ngravity: " << vec(scene.gravity)
      << "\nrestitution: " << real(scene.restitution) << "\n";
  if (scene.floor)
    writeFloor(out, *scene.floor);
  if (scene.friction)
  {
    const core::FrictionDef& f = *scene.friction;
    out << "friction: {sliding: " << real(f.sliding) << ", rolling: " << real(f.rolling)
        << ", spinning: " << real(f.spinning) << ", ball_ball: " << real(f.ball_ball) << ", wall: " << real(f.wall)
        << "}\n";
  }
  out << "walls:" << (scene.walls.empty() ? " []" : "") << "\n";
  for (const core::WallDef& wall : scene.walls)
  {
    out << "  - {point: " << vec(wall.point) << ", u: " << vec(wall.u) << ", v: " << vec(wall.v);
    if (wall.restitution)
      out << ", restitution: " << real(*wall.restitution);
    out << "}\n";
  }
  out << "balls:" << (scene.balls.empty() ? " []" : "") << "\n";
  for (const core::BallDef& ball : scene.balls)
  {
    out << "  - {position: " << vec(ball.position) << ", velocity: " << vec(ball.velocity)
        << ", radius: " << real(ball.radius) << ", mass: " << real(ball.mass);
    if (ball.angular_velocity)
      out << ", angular_velocity: " << vec(*ball.angular_velocity);
    if (ball.inertia != core::kSolidInertia)
      out << ", inertia: " << real(ball.inertia);
    if (ball.placement != core::BallPlacement::kOnFloor)
      out << ", placement: " << core::placementName(ball.placement);
    out << "}\n";
  }
  if (scene.random_balls)
    writeRandomBalls(out, *scene.random_balls);
  if (!scene.pockets.empty())
    out << "pockets:\n";
  for (const core::PocketDef& pocket : scene.pockets)
    out << "  - {position: " << vec(pocket.position) << ", radius: " << real(pocket.radius) << "}\n";
  writeNodeSettings(out, node);
  return out.str();
}
}  // namespace ball_collision_sim::yaml
