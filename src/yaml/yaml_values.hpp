// The scene reader's values: numbers, vectors, ranges, strings, lists and maps read from
// YAML nodes, each failing with the key's path and the reason (KeyError), as
// scene_yaml.cpp reads them.
#pragma once

#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ball_collision_sim::yaml::values
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

[[noreturn]] inline void fail(const std::string& key, const std::string& reason)
{
  throw KeyError{key, reason};
}

inline constexpr std::string_view kPlainTag = "?";  // yaml-cpp's tag of an unquoted, untagged scalar
inline constexpr std::string_view kFloatTag = "tag:yaml.org,2002:float";
inline constexpr std::string_view kIntTag = "tag:yaml.org,2002:int";

std::string childKey(const std::string& parent, std::string_view name);
std::string indexKey(const std::string& parent, std::size_t i);
/// `text` as one printable line for a message: control bytes and bytes that are not
/// UTF-8 as \xNN, at most `max_chars` characters, then "...".
std::string printable(std::string_view text, std::size_t max_chars = 40);
/// What a node is, for "expected X, got Y".
std::string describe(const YAML::Node& node);
/// As describe(), with the length of a list.
std::string describeSized(const YAML::Node& node);
double readNumber(const YAML::Node& node, const std::string& key);
int readInt(const YAML::Node& node, const std::string& key);
std::uint64_t readUnsigned(const YAML::Node& node, const std::string& key);
std::string readString(const YAML::Node& node, const std::string& key);
Vec3 readVec3(const YAML::Node& node, const std::string& key);
Vec2 readVec2(const YAML::Node& node, const std::string& key);
core::Range readRange(const YAML::Node& node, const std::string& key);
/// The elements of a list section; null (the section left empty) is an empty list.
std::vector<YAML::Node> readList(const YAML::Node* node, const std::string& key);

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

}  // namespace ball_collision_sim::yaml::values
