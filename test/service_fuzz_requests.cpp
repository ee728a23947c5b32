#include "service_fuzz_requests.hpp"

#include "ball_collision_sim/ros/requests.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>
#include <utility>

namespace ball_collision_sim::test
{
namespace
{
using Limits = std::numeric_limits<double>;

/// Doubles that break careless code: not numbers, infinities, the extremes, denormals,
/// signed zeros, just past the scene's bounds.
const double kAwkward[] = {Limits::quiet_NaN(),
                           -Limits::quiet_NaN(),
                           Limits::infinity(),
                           -Limits::infinity(),
                           1e300,
                           -1e300,
                           Limits::max(),
                           -Limits::max(),
                           Limits::min(),
                           Limits::denorm_min(),
                           -Limits::denorm_min(),
                           1e-310,
                           -1e-320,
                           1e-200,
                           -0.0,
                           0.0,
                           1e6 + 1,
                           -1e7 - 1,
                           1e13};

/// Values written into a scene's text where a number was.
const char* const kAwkwardText[] = {".nan", ".inf", "-.inf",  "1e300", "-1e300", "1e999", "4.9e-324",
                                    "0",    "-0",   "1e-320", "2",     "-1",     "100",   "1e7",
                                    "abc",  "",     "[]",     "{}",    "~",      "[1, 2]"};

/// Setting names of cfg/Simulator.cfg by type, and one the node does not have.
const char* const kDoubleSettings[] = {"real_time_factor", "marker_rate", "tf_rate",       "state_rate",
                                       "click_radius",     "click_mass",  "status_period", "speed_color_max"};
const char* const kIntSettings[] = {"tf_max_balls", "max_balls", "marker_list_threshold"};
const char* const kBoolSettings[] = {"publish_collisions", "collision_flashes"};
}  // namespace

RequestFuzz::RequestFuzz(std::uint64_t seed, std::string scene_text, std::vector<std::string> paths)
    : rng_(seed), scene_text_(std::move(scene_text)), paths_(std::move(paths))
{
}

bool RequestFuzz::coin(double p)
{
  return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p;
}

void RequestFuzz::begin()
{
  plausible_ = coin(0.5);
}

double RequestFuzz::number(double lo, double hi)
{
  const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  if (roll < (plausible_ ? 0.85 : 0.45))
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  if (plausible_ || roll < 0.6)
    return 0.0;  // (the value of a field a request leaves out)
  if (roll < 0.95)
    return kAwkward[std::uniform_int_distribution<std::size_t>(0, std::size(kAwkward) - 1)(rng_)];
  // any bits at all
  const std::uint64_t bits = rng_();
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

geometry_msgs::Vector3 RequestFuzz::vector(double scale)
{
  geometry_msgs::Vector3 v;
  v.x = number(-scale, scale);
  v.y = number(-scale, scale);
  v.z = coin(0.7) ? 0.0 : number(-scale, scale);
  return v;
}

geometry_msgs::Point RequestFuzz::point()
{
  // the fuzz scene's table is [-1.5, 1.5] x [-0.75, 0.75]; a little beyond it too
  geometry_msgs::Point p;
  p.x = number(-1.7, 1.7);
  p.y = number(-0.9, 0.9);
  p.z = number(0.0, 0.4);
  return p;
}

int RequestFuzz::id(const std::vector<int>& ids)
{
  const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  if (!ids.empty() && roll < 0.7)
    return ids[std::uniform_int_distribution<std::size_t>(0, ids.size() - 1)(rng_)];
  if (roll < 0.8)
    return 0;
  if (roll < 0.9)
    return std::uniform_int_distribution<int>(-3, 60)(rng_);
  const int extremes[] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::min(), -1,
                          std::uniform_int_distribution<int>()(rng_)};
  return extremes[std::uniform_int_distribution<std::size_t>(0, std::size(extremes) - 1)(rng_)];
}

std::uint8_t RequestFuzz::placement()
{
  if (coin(0.9))
    return coin(0.7) ? AddBall::Request::ON_FLOOR : AddBall::Request::AS_GIVEN;
  return static_cast<std::uint8_t>(std::uniform_int_distribution<int>(2, 255)(rng_));
}

AddBall::Request RequestFuzz::addBall()
{
  AddBall::Request req;
  req.position = point();
  req.velocity = vector(3.0);
  req.radius = number(0.01, 0.15);
  req.mass = number(0.05, 5.0);
  req.placement = placement();
  req.set_angular_velocity = coin(0.3);
  req.angular_velocity = coin(0.6) ? geometry_msgs::Vector3() : vector(60.0);
  req.inertia = coin(0.6) ? 0.0 : number(0.0, 1.0);
  return req;
}

AddWall::Request RequestFuzz::addWall()
{
  AddWall::Request req;
  req.point = point();
  req.u = vector(1.0);
  req.v = vector(0.3);
  return req;
}

RemoveObject::Request RequestFuzz::remove(const std::vector<int>& ids)
{
  RemoveObject::Request req;
  req.id = id(ids);
  return req;
}

SetBallState::Request RequestFuzz::setBallState(const std::vector<int>& ids)
{
  SetBallState::Request req;
  req.id = id(ids);
  req.set_position = coin(0.5);
  req.set_velocity = coin(0.5);
  req.set_angular_velocity = coin(0.3);
  // a field is given mostly with its flag, now and then without it
  if (req.set_position || coin(0.1))
    req.position = point();
  if (req.set_velocity || coin(0.1))
    req.velocity = vector(3.0);
  if (req.set_angular_velocity || coin(0.1))
    req.angular_velocity = vector(60.0);
  req.placement = placement();
  req.inertia = coin(0.7) ? 0.0 : number(0.0, 1.0);
  return req;
}

ApplyImpulse::Request RequestFuzz::applyImpulse(const std::vector<int>& ids)
{
  ApplyImpulse::Request req;
  req.id = id(ids);
  req.impulse = vector(1.0);
  return req;
}

Strike::Request RequestFuzz::strike(const std::vector<int>& ids)
{
  Strike::Request req;
  req.id = id(ids);
  req.impulse = vector(1.0);
  req.offset = coin(0.3) ? geometry_msgs::Vector3() : vector(0.06);
  return req;
}

Step::Request RequestFuzz::step()
{
  Step::Request req;
  const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  if (roll < 0.1)
    req.steps = 0;
  else if (roll < 0.65)
    req.steps = std::uniform_int_distribution<std::uint32_t>(1, 10)(rng_);
  else if (roll < 0.8)
    req.steps = std::uniform_int_distribution<std::uint32_t>(11, kMaxFuzzSteps)(rng_);
  else if (roll < 0.85)
    req.steps = std::numeric_limits<std::uint32_t>::max();
  else if (roll < 0.9)
    req.steps = bridge::kMaxStepsPerCall + 1;
  else  // (counts the node takes past kMaxFuzzSteps would run too long: only refused ones)
    req.steps = std::uniform_int_distribution<std::uint32_t>(bridge::kMaxStepsPerCall + 1,
                                                             std::numeric_limits<std::uint32_t>::max())(rng_);
  return req;
}

std_srvs::SetBool::Request RequestFuzz::pause()
{
  std_srvs::SetBool::Request req;
  req.data = coin(0.7);
  return req;
}

std::string RequestFuzz::bytes()
{
  static const char kYamlish[] = "{}[]:,-#&*!|>'\"%@`?~ \n\t.0123456789eEabcxyz_";
  std::string text(std::uniform_int_distribution<std::size_t>(0, 120)(rng_), ' ');
  const bool binary = coin(0.3);
  for (char& c : text)
    c = binary ? static_cast<char>(rng_() & 0xff)
               : kYamlish[std::uniform_int_distribution<std::size_t>(0, sizeof(kYamlish) - 2)(rng_)];
  return text;
}

std::string RequestFuzz::mutatedScene()
{
  std::string text = scene_text_;
  const int mutations = std::uniform_int_distribution<int>(0, 3)(rng_);
  for (int m = 0; m < mutations && !text.empty(); ++m)
  {
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, text.size() - 1)(rng_);
    const int kind = std::uniform_int_distribution<int>(0, 4)(rng_);
    if (kind <= 1)
    {
      // the number at or after `at`, replaced
      std::size_t begin = at;
      while (begin < text.size() && !std::isdigit(static_cast<unsigned char>(text[begin]))) ++begin;
      std::size_t end = begin;
      while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.' ||
                                   text[end] == 'e' || text[end] == '-'))
        ++end;
      if (begin > 0 && text[begin - 1] == '-')
        --begin;
      text.replace(begin, end - begin,
                   kAwkwardText[std::uniform_int_distribution<std::size_t>(0, std::size(kAwkwardText) - 1)(rng_)]);
    }
    else if (kind == 2)
    {
      // a line removed, or doubled
      const std::size_t begin = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
      const std::size_t end = std::min(text.find('\n', at), text.size() - 1) + 1;
      if (coin(0.5))
        text.erase(begin, end - begin);
      else
        text.insert(end, text.substr(begin, end - begin));
    }
    else if (kind == 3)
      text.resize(at);
    else
      text.insert(at, 1, static_cast<char>(rng_() & 0xff));
  }
  return text;
}

LoadScene::Request RequestFuzz::loadScene()
{
  LoadScene::Request req;
  const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  if (roll < 0.3)
    req.path = paths_[std::uniform_int_distribution<std::size_t>(0, paths_.size() - 1)(rng_)];
  else if (roll < 0.75)
    req.yaml = mutatedScene();
  else if (roll < 0.9)
    req.yaml = bytes();
  else if (roll < 0.95)
  {
    req.path = paths_[0];
    req.yaml = scene_text_;  // both: refused
  }                          // else neither: refused
  return req;
}

dynamic_reconfigure::Reconfigure::Request RequestFuzz::reconfigure()
{
  dynamic_reconfigure::Reconfigure::Request req;
  const int changes = std::uniform_int_distribution<int>(1, 3)(rng_);
  for (int k = 0; k < changes; ++k)
  {
    const int kind = std::uniform_int_distribution<int>(0, 19)(rng_);
    if (kind < 10)
    {
      dynamic_reconfigure::DoubleParameter p;
      p.name = kDoubleSettings[std::uniform_int_distribution<std::size_t>(0, std::size(kDoubleSettings) - 1)(rng_)];
      // (plausibly a status line every 1 to 5 s at the most: the node's log stays short)
      p.value = p.name == "status_period" && plausible_ ? (coin(0.5) ? 0.0 : number(1.0, 5.0)) : number(0.0, 60.0);
      req.config.doubles.push_back(p);
    }
    else if (kind < 15)
    {
      dynamic_reconfigure::IntParameter p;
      p.name = kIntSettings[std::uniform_int_distribution<std::size_t>(0, std::size(kIntSettings) - 1)(rng_)];
      p.value = plausible_ || coin(0.5) ? std::uniform_int_distribution<int>(0, 40)(rng_) : id({});
      req.config.ints.push_back(p);
    }
    else if (kind < 17)
    {
      dynamic_reconfigure::BoolParameter p;
      p.name = kBoolSettings[std::uniform_int_distribution<std::size_t>(0, std::size(kBoolSettings) - 1)(rng_)];
      p.value = coin(0.5);
      req.config.bools.push_back(p);
    }
    else if (kind < 19)
    {
      static const char* const kColors[] = {"speed", "id", "motion", "", "purple", "Speed"};
      dynamic_reconfigure::StrParameter p;
      p.name = "ball_color";
      p.value =
          coin(0.9) ? kColors[std::uniform_int_distribution<std::size_t>(0, std::size(kColors) - 1)(rng_)] : bytes();
      req.config.strs.push_back(p);
    }
    else
    {
      dynamic_reconfigure::DoubleParameter p;
      p.name = "no_such_setting";
      p.value = 1.0;
      req.config.doubles.push_back(p);
    }
  }
  return req;
}
}  // namespace ball_collision_sim::test
