#include "ball_collision_sim/ros/scene_param.hpp"

#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <cmath>
#include <cstdio>
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

std::string real(double value)
{
  if (std::isnan(value))
    return ".nan";
  if (std::isinf(value))
    return value > 0 ? ".inf" : "-.inf";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  std::string text = buffer;
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
      return quoted(static_cast<std::string>(value));
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

core::Scene loadSceneParams(const ros::NodeHandle& nh, std::string* yaml_text)
{
  const std::string source = "parameter server (" + nh.getNamespace() + ")";
  XmlRpc::XmlRpcValue tree;
  if (!nh.getParam(nh.getNamespace(), tree) || tree.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    throw yaml::SceneError(source + ": no scene there (load one with <rosparam command=\"load\" file=\"SCENE.yaml\"/>)");
  const std::string text = toYaml(tree);
  const core::Scene scene = yaml::parseScene(text, source);
  const std::vector<core::SceneIssue> issues = core::validate(scene);
  if (!issues.empty())
    throw yaml::SceneError(source + ": " + core::joinIssues(issues));
  if (yaml_text)
    *yaml_text = text;
  return scene;
}
}  // namespace ball_collision_sim::bridge
