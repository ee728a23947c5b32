#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include "scene_sections.hpp"
#include "yaml_values.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/step_settings.hpp"

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
#include <map>
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

using namespace values;

using namespace sections;

/// The scene's most common ball, by radius and mass: of its balls, the pair most of them
/// share (the first such where several tie); with random balls only, the middle of their
/// ranges; none without balls.
std::optional<std::pair<double, double>> mostCommonBall(const core::Scene& scene)
{
  std::optional<std::pair<double, double>> best;
  // (counted once each, so that a scene of many balls loads as fast as ever; then the
  // first ball of the most common kind)
  std::map<std::pair<double, double>, int> counts;
  for (const core::BallDef& ball : scene.balls)
    ++counts[{ball.radius, ball.mass}];
  int most = 0;
  for (const core::BallDef& ball : scene.balls)
  {
    const std::pair<double, double> kind{ball.radius, ball.mass};
    if (counts[kind] > most)
    {
      most = counts[kind];
      best = kind;
    }
  }
  if (!best && scene.random_balls && scene.random_balls->count > 0)
  {
    const core::RandomBallsDef& rb = *scene.random_balls;
    best = std::pair{0.5 * (rb.radius.min + rb.radius.max), 0.5 * (rb.mass.min + rb.mass.max)};
  }
  return best;
}

SceneFile readSceneFile(const YAML::Node& root)
{
  if (!root.IsMap())
  {
    fail("",
         "the scene must be a YAML map, got " + (root.IsNull() ? std::string("an empty document") : describe(root)));
  }
  std::vector<std::string_view> allowed{"frame_id", "dt",    "gravity", "restitution", "floor",
                                        "friction", "walls", "balls",   "random_balls", "pockets"};
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
  const std::vector<YAML::Node> pockets = readList(fields.find("pockets"), "pockets");
  for (std::size_t i = 0; i < pockets.size(); ++i)
  {
    scene.pockets.push_back(readPocket(pockets[i], indexKey("pockets", i)));
  }
  readNodeSettings(fields, file.node);
  // (balls added by clicks are, unless the scene says, its most common ball: a pool
  // table's clicks add pool balls)
  if (const auto common = mostCommonBall(scene))
  {
    if (!fields.find("click_radius"))
      file.node.click_radius = common->first;
    if (!fields.find("click_mass"))
      file.node.click_mass = common->second;
  }
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
  const auto finite = [&](const char* key, double value)
  {
    if (!std::isfinite(value))
      fail(key, "must be finite (got " + formatNumber(value) + ")");
    return std::isfinite(value);
  };
  // > 0 and within [least, most]
  const auto positive = [&](const char* key, double value, double least, double most, const char* unit)
  {
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
  if (node.play_max_balls < 0)
    fail("play_max_balls", "must be >= 0 (0 = no ball markers to play with; got " +
                               std::to_string(node.play_max_balls) + ")");
  if (node.max_balls < 1)
    fail("max_balls", "must be >= 1 (got " + std::to_string(node.max_balls) + ")");
  if (node.tf_max_balls < 0)
    fail("tf_max_balls", "must be >= 0 (got " + std::to_string(node.tf_max_balls) + ")");
  if (node.threads < 0 || node.threads > static_cast<int>(core::kMaxThreads))
    fail("threads", "must be in [0, " + std::to_string(core::kMaxThreads) + "] (0 = every core; got " +
                        std::to_string(node.threads) + ")");
  if (finite("status_period", node.status_period) &&
      !(node.status_period == 0 || (node.status_period >= kMinStatusPeriod && node.status_period <= 1e6)))
    fail("status_period", "must be 0 (no status line) or in [" + formatNumber(kMinStatusPeriod) + ", 1e6] s (got " +
                              formatNumber(node.status_period) + ")");
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
