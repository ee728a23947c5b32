// dynamic_reconfigure's protocol for the node's settings, refusing what is out of range.
#include "ball_collision_sim/ros/reconfigure_server.hpp"

#include "ball_collision_sim/ros/node_settings.hpp"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ball_collision_sim::bridge
{
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
  std::vector<std::string> issues;
  if (!asked.__fromMessage__(req.config))
    issues.push_back("config: names a parameter this node does not have");
  for (const std::string& issue : checkConfig(asked))
    issues.push_back(issue);
  if (!issues.empty())
  {
    std::string message;
    for (const std::string& issue : issues)
      message += (message.empty() ? "" : "; ") + issue;
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
