// dynamic_reconfigure's protocol for the node's settings, refusing what is out of range.
#include "ball_collision_sim/ros/reconfigure_server.hpp"

#include "ball_collision_sim/ros/node_settings.hpp"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ball_collision_sim::bridge
{
namespace
{
/// Why `config` cannot be read as the node's: a setting it does not have, one of another
/// type, or one given twice; one "name: reason" each.
std::vector<std::string> checkNames(const dynamic_reconfigure::Config& config)
{
  std::vector<std::string> issues;
  std::set<std::string> seen;
  const auto& settings = SimulatorConfig::__getParamDescriptions__();
  const auto check = [&](const std::string& name, const std::string& type)
  {
    const auto it = std::find_if(settings.begin(), settings.end(), [&](const auto& s) { return s->name == name; });
    if (it == settings.end())
    {
      std::string known;
      for (const auto& setting : settings) known += (known.empty() ? "" : ", ") + setting->name;
      issues.push_back(name + ": no such setting (expected one of: " + known + ")");
    }
    else if ((*it)->type != type)
      issues.push_back(name + ": must be a " + (*it)->type + " (got a " + type + ")");
    else if (!seen.insert(name).second)
      issues.push_back(name + ": given twice");
  };
  for (const auto& p : config.bools) check(p.name, "bool");
  for (const auto& p : config.ints) check(p.name, "int");
  for (const auto& p : config.doubles) check(p.name, "double");
  for (const auto& p : config.strs) check(p.name, "str");
  return issues;
}
}  // namespace

ReconfigureServer::ReconfigureServer(const ros::NodeHandle& pnh, const SimulatorConfig& initial, Apply apply)
    : pnh_(pnh), apply_(std::move(apply)), config_(initial)
{
  const std::lock_guard<std::mutex> guard(mutex_);
  descriptions_pub_ = pnh_.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  descriptions_pub_.publish(SimulatorConfig::__getDescriptionMessage__());
  updates_pub_ = pnh_.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  publish();
  set_service_ = pnh_.advertiseService("set_parameters", &ReconfigureServer::onSet, this);
}

void ReconfigureServer::update(const SimulatorConfig& config)
{
  const std::lock_guard<std::mutex> guard(mutex_);
  config_ = config;
  publish();
}

bool ReconfigureServer::onSet(dynamic_reconfigure::Reconfigure::Request& req,
                              dynamic_reconfigure::Reconfigure::Response& res)
{
  const std::lock_guard<std::mutex> guard(mutex_);
  SimulatorConfig asked = config_;  // (what the request leaves out keeps its value)
  std::vector<std::string> issues = checkNames(req.config);
  if (issues.empty())
    issues = asked.__fromMessage__(req.config) ? checkConfig(asked)
                                               : std::vector<std::string>{"config: cannot be read as the node's"};
  if (!issues.empty())
  {
    std::string message;
    for (const std::string& issue : issues) message += (message.empty() ? "" : "; ") + issue;
    throw std::invalid_argument(message + "; nothing changed");
  }
  apply_(asked);
  config_ = asked;
  publish();
  config_.__toMessage__(res.config);
  return true;
}

void ReconfigureServer::publish()
{
  config_.__toServer__(pnh_);
  dynamic_reconfigure::Config msg;
  config_.__toMessage__(msg);
  updates_pub_.publish(msg);
}
}  // namespace ball_collision_sim::bridge
