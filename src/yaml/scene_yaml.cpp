#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include "ball_collision_sim/core/format.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ball_collision_sim::yaml
{
namespace
{
using core::Vec2;
using core::Vec3;

// A problem at a key path. Thrown inside the reader and turned into a SceneError with the
// source name in front by parseScene(), so the helpers need not carry the source around.
struct KeyError
{
  std::string key;  // empty: the document itself
  std::string reason;
};

[[noreturn]] void fail(const std::string& key, const std::string& reason)
{
  throw KeyError{key, reason};
}

constexpr std::string_view kPlainTag = "?";  // yaml-cpp's tag of an unquoted, untagged scalar
constexpr std::string_view kFloatTag = "tag:yaml.org,2002:float";
constexpr std::string_view kIntTag = "tag:yaml.org,2002:int";

std::string childKey(const std::string& parent, std::string_view name)
{
  return parent.empty() ? std::string(name) : parent + "." + std::string(name);
}

std::string indexKey(const std::string& parent, std::size_t i)
{
  return parent + "[" + std::to_string(i) + "]";
}

// `text` as one printable line for a message: control bytes and bytes that are not UTF-8
// as \xNN, at most `max_chars` characters, then "...". The file may be anything at all.
std::string printable(std::string_view text, std::size_t max_chars = 40)
{
  std::string out;
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size(); ++chars)
  {
    if (chars == max_chars)
    {
      return out + "...";
    }
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = c < 0x80 ? 1 : (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
    if (c == 0xc0 || c == 0xc1 || c > 0xf4 || i + length > text.size())
    {
      length = 0;
    }
    for (std::size_t k = 1; k < length; ++k)
    {
      if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80)
      {
        length = 0;
      }
    }
    if (length == 0 || c < 0x20 || c == 0x7f)
    {
      static const char* const kHex = "0123456789abcdef";
      out += c == '\n' || c == '\r' || c == '\t' ? std::string(" ") : std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
      ++i;
      continue;
    }
    out.append(text.substr(i, length));
    i += length;
  }
  return out;
}

// What a node is, for "expected X, got Y". A scalar is shown as written (shortened, one
// line), quoted when it was a string in the YAML so that `"1.0"` is not mistaken for 1.0.
std::string describe(const YAML::Node& node)
{
  switch (node.Type())
  {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null:
      return "null";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Scalar:
      break;
  }
  const std::string text = printable(node.Scalar());
  return node.Tag() == kPlainTag ? text : "the string \"" + text + "\"";
}

// As describe(), with the length of a list: for "expected a list of 3 numbers".
std::string describeSized(const YAML::Node& node)
{
  if (node.IsSequence())
  {
    return "a list of " + std::to_string(node.size()) + (node.size() == 1 ? " item" : " items");
  }
  return describe(node);
}

bool isDigit(char c)
{
  return c >= '0' && c <= '9';
}

// YAML 1.2 core schema float: [-+]? ( \.[0-9]+ | [0-9]+ ( \. [0-9]* )? ) ( [eE] [-+]? [0-9]+ )?
// Checked by hand because from_chars alone would also take "nan", "inf" and trailing junk.
bool isDecimalNumber(std::string_view s)
{
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-'))
  {
    ++i;
  }
  std::size_t digits = 0;
  while (i < s.size() && isDigit(s[i]))
  {
    ++i;
    ++digits;
  }
  if (i < s.size() && s[i] == '.')
  {
    ++i;
    while (i < s.size() && isDigit(s[i]))
    {
      ++i;
      ++digits;
    }
  }
  if (digits == 0)
  {
    return false;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E'))
  {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-'))
    {
      ++i;
    }
    std::size_t exponent_digits = 0;
    while (i < s.size() && isDigit(s[i]))
    {
      ++i;
      ++exponent_digits;
    }
    if (exponent_digits == 0)
    {
      return false;
    }
  }
  return i == s.size();
}

bool isInteger(std::string_view s)
{
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i == s.size())
  {
    return false;
  }
  for (; i < s.size(); ++i)
  {
    if (!isDigit(s[i]))
    {
      return false;
    }
  }
  return true;
}

// The YAML spellings of NaN and infinity. They are numbers here; core::validate() is the
// one place that rejects non-finite values, with the key's name.
std::optional<double> specialNumber(std::string_view s)
{
  if (s == ".nan" || s == ".NaN" || s == ".NAN")
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double sign = 1.0;
  if (!s.empty() && (s[0] == '+' || s[0] == '-'))
  {
    sign = s[0] == '-' ? -1.0 : 1.0;
    s.remove_prefix(1);
  }
  if (s == ".inf" || s == ".Inf" || s == ".INF")
  {
    return sign * std::numeric_limits<double>::infinity();
  }
  return std::nullopt;
}

double readNumber(const YAML::Node& node, const std::string& key)
{
  const std::string expected = "expected a number, got ";
  if (!node.IsScalar() || (node.Tag() != kPlainTag && node.Tag() != kFloatTag && node.Tag() != kIntTag))
  {
    fail(key, expected + describe(node));
  }
  const std::string& text = node.Scalar();
  if (const std::optional<double> special = specialNumber(text))
  {
    return *special;
  }
  if (!isDecimalNumber(text))
  {
    fail(key, expected + describe(node));
  }
  // from_chars takes no '+' and ignores the locale (strtod would read "0,5" in de_DE).
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  double value = 0.0;
  const std::from_chars_result result = std::from_chars(first, last, value);
  if (result.ec == std::errc::result_out_of_range)
  {
    fail(key, "number out of range of a double, got " + text);
  }
  if (result.ec != std::errc() || result.ptr != last)
  {
    fail(key, expected + describe(node));
  }
  return value;
}

bool isIntegerScalar(const YAML::Node& node)
{
  return node.IsScalar() && (node.Tag() == kPlainTag || node.Tag() == kIntTag) && isInteger(node.Scalar());
}

int readInt(const YAML::Node& node, const std::string& key)
{
  if (!isIntegerScalar(node))
  {
    fail(key, "expected an integer, got " + describe(node));
  }
  const std::string& text = node.Scalar();
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  int value = 0;
  const std::from_chars_result result = std::from_chars(first, last, value);
  if (result.ec != std::errc() || result.ptr != last)
  {
    fail(key, "integer out of range, got " + text);
  }
  return value;
}

std::uint64_t readUnsigned(const YAML::Node& node, const std::string& key)
{
  if (!isIntegerScalar(node) || node.Scalar()[0] == '-')
  {
    fail(key, "expected an integer >= 0, got " + describe(node));
  }
  const std::string& text = node.Scalar();
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  std::uint64_t value = 0;
  const std::from_chars_result result = std::from_chars(first, last, value);
  if (result.ec != std::errc() || result.ptr != last)
  {
    fail(key, "integer out of range (at most 18446744073709551615), got " + text);
  }
  return value;
}

std::string readString(const YAML::Node& node, const std::string& key)
{
  if (!node.IsScalar())
  {
    fail(key, "expected a string, got " + describe(node));
  }
  return node.Scalar();
}

Vec3 readVec3(const YAML::Node& node, const std::string& key)
{
  if (!node.IsSequence() || node.size() != 3)
  {
    fail(key, "expected a list of 3 numbers, got " + describeSized(node));
  }
  Vec3 v;
  for (std::size_t i = 0; i < 3; ++i)
  {
    v[static_cast<Eigen::Index>(i)] = readNumber(node[i], indexKey(key, i));
  }
  return v;
}

Vec2 readVec2(const YAML::Node& node, const std::string& key)
{
  if (!node.IsSequence() || node.size() != 2)
  {
    fail(key, "expected a list of 2 numbers [x, y], got " + describeSized(node));
  }
  return Vec2(readNumber(node[0], indexKey(key, 0)), readNumber(node[1], indexKey(key, 1)));
}

core::Range readRange(const YAML::Node& node, const std::string& key)
{
  if (!node.IsSequence() || node.size() != 2)
  {
    fail(key, "expected a list [min, max] of 2 numbers, got " + describeSized(node));
  }
  core::Range range;
  range.min = readNumber(node[0], indexKey(key, 0));
  range.max = readNumber(node[1], indexKey(key, 1));
  return range;
}

// A YAML map whose keys have been checked against the allowed names (unknown and
// duplicate keys are errors: yaml-cpp keeps both copies of a duplicate and a lookup
// would silently take one).
class MapFields
{
public:
  MapFields(const YAML::Node& node, std::string key, const std::vector<std::string_view>& allowed)
    : key_(std::move(key))
  {
    if (!node.IsMap())
    {
      fail(key_, "expected a map, got " + describe(node));
    }
    for (const auto& entry : node)
    {
      if (!entry.first.IsScalar())
      {
        fail(key_, "keys must be names, got " + describe(entry.first) + " as a key");
      }
      const std::string& name = entry.first.Scalar();
      bool known = false;
      for (const std::string_view candidate : allowed)
      {
        known = known || candidate == name;
      }
      if (!known)
      {
        std::string list;
        for (const std::string_view candidate : allowed)
        {
          list += (list.empty() ? "" : ", ") + std::string(candidate);
        }
        fail(childKey(key_, printable(name)), "unknown key (expected one of: " + list + ")");
      }
      if (find(name) != nullptr)
      {
        fail(childKey(key_, name), "duplicate key");
      }
      fields_.emplace_back(name, entry.second);
    }
  }

  /// The value of `name`, or nullptr when the key is absent.
  const YAML::Node* find(std::string_view name) const
  {
    for (const auto& field : fields_)
    {
      if (field.first == name)
      {
        return &field.second;
      }
    }
    return nullptr;
  }

  /// The value of `name`, or nullptr when it is absent or null (an empty section).
  const YAML::Node* findSection(std::string_view name) const
  {
    const YAML::Node* node = find(name);
    return (node != nullptr && !node->IsNull()) ? node : nullptr;
  }

  const YAML::Node& require(std::string_view name) const
  {
    const YAML::Node* node = find(name);
    if (node == nullptr)
    {
      fail(keyOf(name), "required");
    }
    return *node;
  }

  std::string keyOf(std::string_view name) const { return childKey(key_, name); }

private:
  std::string key_;
  std::vector<std::pair<std::string, YAML::Node>> fields_;
};

// The elements of a list section; null (the section left empty) is an empty list.
std::vector<YAML::Node> readList(const YAML::Node* node, const std::string& key)
{
  std::vector<YAML::Node> items;
  if (node == nullptr || node->IsNull())
  {
    return items;
  }
  if (!node->IsSequence())
  {
    fail(key, "expected a list, got " + describe(*node));
  }
  for (const auto& item : *node)
  {
    items.push_back(item);
  }
  return items;
}

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

/// `solid` (k = 2/5), `hollow` (k = 2/3) or a number k (checked to be in (0, 1] with the scene).
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
    fail(key, "expected solid, hollow or a number k in (0, 1], got " + describe(node));
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

SceneFile readSceneFile(const YAML::Node& root)
{
  if (!root.IsMap())
  {
    fail("", "the scene must be a YAML map, got " + (root.IsNull() ? std::string("an empty document") : describe(root)));
  }
  std::vector<std::string_view> allowed{"frame_id", "dt",    "gravity", "restitution", "floor",
                                        "friction", "walls", "balls",   "random_balls"};
  allowed.insert(allowed.end(), kNodeOnlyKeys.begin(), kNodeOnlyKeys.end());
  const MapFields fields(root, "", allowed);

  SceneFile file;
  core::Scene& scene = file.scene;
  if (const YAML::Node* frame_id = fields.find("frame_id"))
  {
    scene.frame_id = readString(*frame_id, "frame_id");
  }
  if (const YAML::Node* dt = fields.find("dt"))
  {
    scene.dt = readNumber(*dt, "dt");
  }
  if (const YAML::Node* gravity = fields.find("gravity"))
  {
    scene.gravity = readVec3(*gravity, "gravity");
  }
  if (const YAML::Node* restitution = fields.find("restitution"))
  {
    scene.restitution = readNumber(*restitution, "restitution");
  }
  if (const YAML::Node* floor = fields.findSection("floor"))
  {
    scene.floor = readFloor(*floor, "floor");
  }
  if (const YAML::Node* friction = fields.findSection("friction"))
  {
    scene.friction = readFriction(*friction, "friction");
  }
  const std::vector<YAML::Node> walls = readList(fields.find("walls"), "walls");
  for (std::size_t i = 0; i < walls.size(); ++i)
  {
    scene.walls.push_back(readWall(walls[i], indexKey("walls", i)));
  }
  const std::vector<YAML::Node> balls = readList(fields.find("balls"), "balls");
  for (std::size_t i = 0; i < balls.size(); ++i)
  {
    scene.balls.push_back(readBall(balls[i], indexKey("balls", i)));
  }
  if (const YAML::Node* random = fields.findSection("random_balls"))
  {
    scene.random_balls = readRandomBalls(*random, "random_balls");
  }
  readNodeSettings(fields, file.node);
  for (const auto& item : root)
  {
    const std::string key = item.first.Scalar();
    if (std::find(kNodeOnlyKeys.begin(), kNodeOnlyKeys.end(), key) != kNodeOnlyKeys.end())
      file.node_keys.push_back(key);
  }
  return file;
}

// Sees a document's events and ignores them: for counting documents.
class DocumentCounter : public YAML::EventHandler
{
public:
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

struct FileCloser
{
  void operator()(std::FILE* file) const { std::fclose(file); }
};

std::string withMark(const std::string& source, const YAML::Mark& mark)
{
  if (mark.is_null())
  {
    return source + ": ";
  }
  // yaml-cpp counts from 0; editors and compilers count from 1.
  return source + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) + ": ";
}
}  // namespace

SceneFile parseSceneFile(const std::string& yaml_text, const std::string& source_name)
{
  // YAML allows no NUL; yaml-cpp stops reading at one and then yields empty documents
  // without end, so a binary file is refused here, by the offset of its first NUL.
  if (const std::size_t nul = yaml_text.find('\0'); nul != std::string::npos)
  {
    throw SceneError(source_name + ": byte " + std::to_string(nul) + " is NUL: not a YAML text file");
  }
  YAML::Node root;
  try
  {
    // Count the documents, but no further than two: yaml-cpp's LoadAll() never returns on
    // some malformed input (an endless run of empty documents).
    std::istringstream in(yaml_text);
    YAML::Parser parser(in);
    DocumentCounter counter;
    int documents = 0;
    while (documents < 2 && parser.HandleNextDocument(counter))
    {
      ++documents;
    }
    if (documents > 1)
    {
      throw SceneError(source_name + ": expected one YAML document, found more");
    }
    if (documents == 1)
    {
      root = YAML::Load(yaml_text);
    }
  }
  catch (const YAML::ParserException& e)
  {
    throw SceneError(withMark(source_name, e.mark) + printable(e.msg, 200));
  }
  catch (const YAML::Exception& e)
  {
    throw SceneError(withMark(source_name, e.mark) + printable(e.msg, 200));
  }
  try
  {
    return readSceneFile(root);
  }
  catch (const KeyError& e)
  {
    throw SceneError(source_name + ": " + (e.key.empty() ? "" : e.key + ": ") + e.reason);
  }
  catch (const YAML::Exception& e)
  {
    // Not expected (every access is checked first), but keep the one-line contract.
    throw SceneError(withMark(source_name, e.mark) + printable(e.msg, 200));
  }
}

core::Scene parseScene(const std::string& yaml_text, const std::string& source_name)
{
  return parseSceneFile(yaml_text, source_name).scene;
}

std::vector<core::SceneIssue> validateNodeSettings(const NodeSettings& node)
{
  using core::formatNumber;
  std::vector<core::SceneIssue> issues;
  const auto fail = [&](const char* key, const std::string& reason) { issues.push_back({key, reason}); };
  const auto finite = [&](const char* key, double value) {
    if (!std::isfinite(value))
      fail(key, "must be finite (got " + formatNumber(value) + ")");
    return std::isfinite(value);
  };
  // > 0 and within [least, most]
  const auto positive = [&](const char* key, double value, double least, double most, const char* unit) {
    if (!finite(key, value))
      return;
    if (!(value > 0))
      fail(key, "must be > 0 (got " + formatNumber(value) + ")");
    else if (value < least)
      fail(key, "must be >= " + formatNumber(least) + " " + unit + " (got " + formatNumber(value) + ")");
    else if (value > most)
      fail(key, "must be <= " + formatNumber(most) + " " + unit + " (got " + formatNumber(value) + ")");
  };
  if (finite("real_time_factor", node.real_time_factor) && node.real_time_factor < 0)
    fail("real_time_factor", "must be >= 0 (0 = as fast as possible)");
  for (const auto& [key, rate] : {std::pair{"marker_rate", node.marker_rate}, std::pair{"tf_rate", node.tf_rate},
                                  std::pair{"state_rate", node.state_rate}})
    if (finite(key, rate) && !(rate >= 0 && rate <= 1e6))
      fail(key, "must be in [0, 1e6] Hz (got " + formatNumber(rate) + ")");
  if (node.marker_list_threshold < 0)
    fail("marker_list_threshold", "must be >= 0 (got " + std::to_string(node.marker_list_threshold) + ")");
  if (node.max_balls < 1)
    fail("max_balls", "must be >= 1 (got " + std::to_string(node.max_balls) + ")");
  if (node.tf_max_balls < 0)
    fail("tf_max_balls", "must be >= 0 (got " + std::to_string(node.tf_max_balls) + ")");
  if (finite("status_period", node.status_period) && !(node.status_period >= 0 && node.status_period <= 1e6))
    fail("status_period", "must be in [0, 1e6] s (0 = no status line; got " + formatNumber(node.status_period) + ")");
  positive("click_radius", node.click_radius, core::kMinLength, core::kMaxLength, "m");
  positive("click_mass", node.click_mass, core::kMinMass, core::kMaxMass, "kg");
  return issues;
}

std::string readTextFile(const std::string& path)
{
  errno = 0;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file)
  {
    const int open_errno = errno;  // before anything else can change it
    throw SceneError(path + ": cannot open file (" + std::strerror(open_errno) + ")");
  }
  std::string text;
  char buffer[1 << 16];
  for (;;)
  {
    const std::size_t n = std::fread(buffer, 1, sizeof(buffer), file.get());
    text.append(buffer, n);
    if (n == sizeof(buffer))
    {
      continue;
    }
    // A directory opens fine with fopen and fails only on read (EISDIR).
    if (std::ferror(file.get()) != 0)
    {
      const int read_errno = errno;
      throw SceneError(path + ": cannot read file (" + std::strerror(read_errno) + ")");
    }
    break;
  }
  return text;
}

core::Scene loadSceneFile(const std::string& path)
{
  return parseScene(readTextFile(path), path);
}

std::vector<core::SceneIssue> check(SceneFile& file)
{
  file.checked = core::check(file.scene);
  std::vector<core::SceneIssue> issues = file.checked.issues;
  const std::vector<core::SceneIssue> node_issues = validateNodeSettings(file.node);
  issues.insert(issues.end(), node_issues.begin(), node_issues.end());
  return issues;
}

SceneFile loadValidSceneFile(const std::string& path)
{
  SceneFile file = parseSceneFile(readTextFile(path), path);
  const std::vector<core::SceneIssue> issues = check(file);
  if (!issues.empty())
    throw SceneError(path + ": " + core::joinIssues(issues));
  return file;
}

core::Scene loadValidScene(const std::string& path)
{
  return loadValidSceneFile(path).scene;
}
}  // namespace ball_collision_sim::yaml
