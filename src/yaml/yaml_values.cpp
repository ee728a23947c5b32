#include "yaml_values.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace ball_collision_sim::yaml::values
{
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
std::string printable(std::string_view text, std::size_t max_chars)
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

namespace
{
bool isDigit(char c)
{
  return c >= '0' && c <= '9';
}
}  // namespace

// YAML 1.2 core schema float: [-+]? ( \.[0-9]+ | [0-9]+ ( \. [0-9]* )? ) ( [eE] [-+]? [0-9]+ )?
// Checked by hand because from_chars alone would also take "nan", "inf" and trailing junk.
namespace
{
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
}  // namespace

namespace
{
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
}  // namespace

// The YAML spellings of NaN and infinity. They are numbers here; core::validate() is the
// one place that rejects non-finite values, with the key's name.
namespace
{
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
}  // namespace

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

namespace
{
bool isIntegerScalar(const YAML::Node& node)
{
  return node.IsScalar() && (node.Tag() == kPlainTag || node.Tag() == kIntTag) && isInteger(node.Scalar());
}
}  // namespace

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

}  // namespace ball_collision_sim::yaml::values
