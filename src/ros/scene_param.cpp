#include "ball_collision_sim/ros/scene_param.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <ros/param.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <regex>
#include <string>

namespace ball_collision_sim::bridge
{
namespace
{
std::string quoted(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    if (c == '"' || c == '\\')
      out += '\\';
    if (c == '\n')
    {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

/// rosparam reads files as YAML 1.1 (PyYAML), where a real with an exponent needs a
/// decimal point and a signed exponent, and a signed real a digit before its point:
/// `1e-3`, `1.5e3` and `-.5` arrive as strings. The reader and `simulate` follow YAML
/// 1.2, where they are numbers. So a string that is a number in YAML 1.2 but would not
/// have been one in YAML 1.1 was a number in the file: it goes on unquoted. (A string
/// that YAML 1.1 reads as a number was quoted in the file, and stays a string.)
bool numberReadAsString(const std::string& text)
{
  static const std::regex yaml12(R"([-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?)");
  static const std::regex yaml11(
      R"([-+]?[0-9][0-9_]*\.[0-9_]*([eE][-+][0-9]+)?|\.[0-9][0-9_]*([eE][-+][0-9]+)?|[-+]?(0|[1-9][0-9_]*)|[-+]?0[0-7_]+)");
  return std::regex_match(text, yaml12) && !std::regex_match(text, yaml11);
}

std::string real(double value)
{
  if (std::isnan(value))
    return ".nan";
  if (std::isinf(value))
    return value > 0 ? ".inf" : "-.inf";
  std::string text = core::formatNumber(value);  // (the shortest that reads back the same)
  if (text.find_first_of(".e") == std::string::npos)
    text += ".0";  // a real stays a real: `count: 3.0` must still be refused
  return text;
}
}  // namespace

std::string toYaml(XmlRpc::XmlRpcValue& value)
{
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return real(static_cast<double>(value));
    case XmlRpc::XmlRpcValue::TypeString:
    {
      const std::string text = static_cast<std::string>(value);
      return numberReadAsString(text) ? text : quoted(text);
    }
    case XmlRpc::XmlRpcValue::TypeArray:
    {
      std::string out = "[";
      for (int i = 0; i < value.size(); ++i)
        out += (i ? ", " : "") + toYaml(value[i]);
      return out + "]";
    }
    case XmlRpc::XmlRpcValue::TypeStruct:
    {
      std::string out = "{";
      bool first = true;
      for (auto& [key, child] : value)
      {
        out += (first ? "" : ", ") + quoted(key) + ": " + toYaml(child);
        first = false;
      }
      return out + "}";
    }
    default:
      return "null";  // invalid, date-time, base64: the reader names the key and the type
  }
}

yaml::SceneFile loadSceneParams(const ros::NodeHandle& nh)
{
  const std::string source = "parameter server (" + nh.getNamespace() + ")";
  XmlRpc::XmlRpcValue tree;
  if (!nh.getParam(nh.getNamespace(), tree) || tree.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    throw yaml::SceneError(source + ": no scene there (load one with <rosparam command=\"load\" file=\"SCENE.yaml\"/>)");
  yaml::SceneFile file = yaml::parseSceneFile(toYaml(tree), source);
  const std::vector<core::SceneIssue> issues = yaml::check(file);
  if (!issues.empty())
    throw yaml::SceneError(source + ": " + core::joinIssues(issues));
  return file;
}
namespace
{
XmlRpc::XmlRpcValue toXmlRpc(const YAML::Node& node)
{
  XmlRpc::XmlRpcValue out;
  if (node.IsMap())
  {
    out.begin();  // an empty struct, not an invalid value
    for (const auto& item : node)
      out[item.first.as<std::string>()] = toXmlRpc(item.second);
    return out;
  }
  if (node.IsSequence())
  {
    out.setSize(static_cast<int>(node.size()));
    for (std::size_t i = 0; i < node.size(); ++i)
      out[static_cast<int>(i)] = toXmlRpc(node[i]);
    return out;
  }
  if (!node.IsScalar())
    return out;
  const std::string& text = node.Scalar();
  if (node.Tag() == "!")
    return XmlRpc::XmlRpcValue(text);  // quoted
  if (text == "true" || text == "false")
    return XmlRpc::XmlRpcValue(text == "true");
  static const std::regex integer(R"([-+]?[0-9]+)");
  if (std::regex_match(text, integer))
  {
    const long long value = std::stoll(text);
    if (value >= INT32_MIN && value <= INT32_MAX)
      return XmlRpc::XmlRpcValue(static_cast<int>(value));
    return XmlRpc::XmlRpcValue(text);
  }
  if (text == ".nan" || text == ".inf" || text == "-.inf")
    return XmlRpc::XmlRpcValue(text == ".nan" ? std::nan("") : text == ".inf" ? HUGE_VAL : -HUGE_VAL);
  double value = 0.0;  // from_chars: the writer's digits, whatever the locale
  const char* end = text.data() + text.size();
  const std::from_chars_result read = std::from_chars(text.data(), end, value);
  if (read.ec == std::errc() && read.ptr == end)
    return XmlRpc::XmlRpcValue(value);
  return XmlRpc::XmlRpcValue(text);  // a plain word: plane, speed
}
}  // namespace

XmlRpc::XmlRpcValue toXmlRpc(const std::string& yaml_text)
{
  return toXmlRpc(YAML::Load(yaml_text));
}

void writeSceneParams(const ros::NodeHandle& nh, const core::Scene& scene, const NodeSettings& node)
{
  ros::param::set(nh.getNamespace(), toXmlRpc(yaml::writeScene(scene, node)));
}
}  // namespace ball_collision_sim::bridge
