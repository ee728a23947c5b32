#include "scene_sections.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace ball_collision_sim::yaml::sections
{
using namespace values;

// Either floor type: the restitution of ball-floor impacts (checked to be in [0, 1] with the scene).
void readFloorRestitution(const MapFields& fields, core::FloorDef& floor)
{
  if (const YAML::Node* restitution = fields.find("restitution"))
  {
    floor.restitution = readNumber(*restitution, fields.keyOf("restitution"));
  }
}

core::FloorDef readFloor(const YAML::Node& node, const std::string& key)
{
  if (!node.IsMap())
  {
    fail(key, "expected a map, got " + describe(node));
  }
  // The type decides which other keys are allowed, so it is read first.
  core::FloorDef floor;
  const YAML::Node type_node = node["type"];
  if (type_node.IsDefined())
  {
    const std::string type_key = childKey(key, "type");
    if (!type_node.IsScalar() || (type_node.Scalar() != "plane" && type_node.Scalar() != "biquadratic"))
    {
      fail(type_key, "expected plane or biquadratic, got " + describe(type_node));
    }
    floor.type = type_node.Scalar() == "plane" ? core::FloorDef::Type::kPlane : core::FloorDef::Type::kBiquadratic;
  }

  if (floor.type == core::FloorDef::Type::kPlane)
  {
    const MapFields fields(node, key, {"type", "point", "u", "v", "restitution"});
    readFloorRestitution(fields, floor);
    if (const YAML::Node* point = fields.find("point"))
    {
      floor.point = readVec3(*point, fields.keyOf("point"));
    }
    if (const YAML::Node* u = fields.find("u"))
    {
      floor.u = readVec3(*u, fields.keyOf("u"));
    }
    if (const YAML::Node* v = fields.find("v"))
    {
      floor.v = readVec3(*v, fields.keyOf("v"));
    }
    return floor;
  }

  const MapFields fields(node, key, {"type", "control_points", "restitution"});
  readFloorRestitution(fields, floor);
  const std::string points_key = fields.keyOf("control_points");
  const YAML::Node& points = fields.require("control_points");
  if (!points.IsSequence() || points.size() != 3)
  {
    fail(points_key, "expected 3 rows of 3 points [x, y, z], got " + describeSized(points));
  }
  for (std::size_t i = 0; i < 3; ++i)
  {
    const YAML::Node row = points[i];
    const std::string row_key = indexKey(points_key, i);
    if (!row.IsSequence() || row.size() != 3)
    {
      fail(row_key, "expected a row of 3 points [x, y, z], got " + describeSized(row));
    }
    for (std::size_t j = 0; j < 3; ++j)
    {
      floor.control_points[i][j] = readVec3(row[j], indexKey(row_key, j));
    }
  }
  return floor;
}

core::WallDef readWall(const YAML::Node& node, const std::string& key)
{
  const MapFields fields(node, key, {"point", "u", "v", "restitution"});
  core::WallDef wall;
  wall.point = readVec3(fields.require("point"), fields.keyOf("point"));
  wall.u = readVec3(fields.require("u"), fields.keyOf("u"));
  wall.v = readVec3(fields.require("v"), fields.keyOf("v"));
  if (const YAML::Node* restitution = fields.find("restitution"))
  {
    wall.restitution = readNumber(*restitution, fields.keyOf("restitution"));
  }
  return wall;
}

core::PocketDef readPocket(const YAML::Node& node, const std::string& key)
{
  const MapFields fields(node, key, {"position", "radius"});
  core::PocketDef pocket;
  pocket.position = readVec2(fields.require("position"), fields.keyOf("position"));
  pocket.radius = readNumber(fields.require("radius"), fields.keyOf("radius"));
  return pocket;
}

/// `solid` (k = 2/5), `hollow` (k = 2/3) or a number k (checked to be in [0.01, 1] with the scene).
double readInertia(const YAML::Node& node, const std::string& key)
{
  if (node.IsScalar() && node.Scalar() == "solid")
    return core::kSolidInertia;
  if (node.IsScalar() && node.Scalar() == "hollow")
    return core::kHollowInertia;
  try
  {
    return readNumber(node, key);
  }
  catch (const KeyError&)
  {
    fail(key, "expected solid, hollow or a number k in [0.01, 1], got " + describe(node));
  }
}

/// `on_floor` (put on the floor) or `as_given` (the centre and velocity as written).
core::BallPlacement readPlacement(const YAML::Node& node, const std::string& key)
{
  // Any scalar, quoted or not, as for the floor's type: the parameter server passes strings on quoted.
  for (const core::BallPlacement placement : {core::BallPlacement::kOnFloor, core::BallPlacement::kAsGiven})
    if (node.IsScalar() && node.Scalar() == core::placementName(placement))
      return placement;
  fail(key, "expected on_floor or as_given, got " + describe(node));
}

core::FrictionDef readFriction(const YAML::Node& node, const std::string& key)
{
  const MapFields fields(node, key, {"sliding", "rolling", "spinning", "ball_ball", "wall"});
  core::FrictionDef friction;
  for (const auto& [name, value] :
       {std::pair{"sliding", &friction.sliding}, std::pair{"rolling", &friction.rolling},
        std::pair{"spinning", &friction.spinning}, std::pair{"ball_ball", &friction.ball_ball},
        std::pair{"wall", &friction.wall}})
    if (const YAML::Node* found = fields.find(name))
      *value = readNumber(*found, fields.keyOf(name));
  return friction;
}

core::BallDef readBall(const YAML::Node& node, const std::string& key)
{
  const MapFields fields(node, key,
                         {"position", "velocity", "radius", "mass", "angular_velocity", "inertia", "placement"});
  core::BallDef ball;
  ball.position = readVec3(fields.require("position"), fields.keyOf("position"));
  ball.velocity = Vec3::Zero();
  if (const YAML::Node* velocity = fields.find("velocity"))
  {
    ball.velocity = readVec3(*velocity, fields.keyOf("velocity"));
  }
  ball.radius = readNumber(fields.require("radius"), fields.keyOf("radius"));
  ball.mass = 1.0;
  if (const YAML::Node* mass = fields.find("mass"))
  {
    ball.mass = readNumber(*mass, fields.keyOf("mass"));
  }
  if (const YAML::Node* spin = fields.find("angular_velocity"))
  {
    ball.angular_velocity = readVec3(*spin, fields.keyOf("angular_velocity"));
  }
  if (const YAML::Node* inertia = fields.find("inertia"))
  {
    ball.inertia = readInertia(*inertia, fields.keyOf("inertia"));
  }
  if (const YAML::Node* placement = fields.find("placement"))
  {
    ball.placement = readPlacement(*placement, fields.keyOf("placement"));
  }
  return ball;
}

core::RandomBallsDef readRandomBalls(const YAML::Node& node, const std::string& key)
{
  const MapFields fields(node, key, {"count", "seed", "radius", "mass", "speed", "region", "inertia"});
  core::RandomBallsDef random;
  random.count = readInt(fields.require("count"), fields.keyOf("count"));
  if (const YAML::Node* seed = fields.find("seed"))
  {
    random.seed = readUnsigned(*seed, fields.keyOf("seed"));
  }
  if (const YAML::Node* radius = fields.find("radius"))
  {
    random.radius = readRange(*radius, fields.keyOf("radius"));
  }
  if (const YAML::Node* mass = fields.find("mass"))
  {
    random.mass = readRange(*mass, fields.keyOf("mass"));
  }
  if (const YAML::Node* speed = fields.find("speed"))
  {
    random.speed = readRange(*speed, fields.keyOf("speed"));
  }
  if (const YAML::Node* inertia = fields.find("inertia"))
  {
    random.inertia = readInertia(*inertia, fields.keyOf("inertia"));
  }
  if (const YAML::Node* region_node = fields.findSection("region"))
  {
    const MapFields region_fields(*region_node, fields.keyOf("region"), {"min", "max"});
    core::RandomBallsDef::Region region;
    region.min = readVec2(region_fields.require("min"), region_fields.keyOf("min"));
    region.max = readVec2(region_fields.require("max"), region_fields.keyOf("max"));
    random.region = region;
  }
  return random;
}

bool readBool(const YAML::Node& node, const std::string& key)
{
  if (node.IsScalar() && node.Tag() == kPlainTag)
  {
    if (node.Scalar() == "true")
      return true;
    if (node.Scalar() == "false")
      return false;
  }
  fail(key, "expected true or false, got " + describe(node));
}

// The node's own settings: kept in the scene so that one reader and one validate()
// serve the node and the offline tool.
void readNodeSettings(const MapFields& fields, NodeSettings& node)
{
  auto number = [&](const char* name, double& out) {
    if (const YAML::Node* value = fields.find(name))
      out = readNumber(*value, name);
  };
  auto flag = [&](const char* name, bool& out) {
    if (const YAML::Node* value = fields.find(name))
      out = readBool(*value, name);
  };
  number("real_time_factor", node.real_time_factor);
  number("marker_rate", node.marker_rate);
  number("tf_rate", node.tf_rate);
  number("state_rate", node.state_rate);
  number("click_radius", node.click_radius);
  number("click_mass", node.click_mass);
  number("status_period", node.status_period);
  if (const YAML::Node* value = fields.find("tf_max_balls"))
    node.tf_max_balls = readInt(*value, "tf_max_balls");
  if (const YAML::Node* value = fields.find("max_balls"))
    node.max_balls = readInt(*value, "max_balls");
  if (const YAML::Node* value = fields.find("marker_list_threshold"))
    node.marker_list_threshold = readInt(*value, "marker_list_threshold");
  if (const YAML::Node* value = fields.find("play_max_balls"))
    node.play_max_balls = readInt(*value, "play_max_balls");
  if (const YAML::Node* value = fields.find("threads"))
    node.threads = readInt(*value, "threads");
  flag("publish_collisions", node.publish_collisions);
  flag("start_paused", node.start_paused);
  flag("collision_flashes", node.collision_flashes);
  if (const YAML::Node* value = fields.find("publish_clock"))
    node.publish_clock = readBool(*value, "publish_clock");
  if (const YAML::Node* value = fields.find("frame_prefix"))
  {
    node.frame_prefix = readString(*value, "frame_prefix");
    const std::string& prefix = *node.frame_prefix;
    if (!prefix.empty() && prefix.front() == '/')
      fail("frame_prefix", "must not start with '/' (tf2 frame names do not), got \"" + printable(prefix) + "\"");
    if (prefix.find_first_of(" \t\n\r") != std::string::npos)
      fail("frame_prefix", "must not contain blanks, got \"" + printable(prefix) + "\"");
  }
  // How balls are drawn is not physics, so core::validate() does not look at it: the
  // reader checks these two itself, for the node and the offline tool alike.
  if (const YAML::Node* value = fields.find("ball_color"))
  {
    const std::optional<BallColor> color = value->IsScalar() ? ballColorNamed(value->Scalar()) : std::nullopt;
    if (!color)
      fail("ball_color", "expected speed, id or motion, got " + describe(*value));
    node.ball_color = *color;
  }
  if (const YAML::Node* value = fields.find("speed_color_max"))
  {
    node.speed_color_max = readNumber(*value, "speed_color_max");
    if (!(node.speed_color_max >= 0 && node.speed_color_max <= 1e7))
      fail("speed_color_max", "must be in [0, 1e7] m/s (0 = the fastest ball at the start), got " + value->Scalar());
  }
}
}  // namespace ball_collision_sim::yaml::sections
