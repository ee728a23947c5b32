#pragma once

#include <ball_collision_sim/SimulatorConfig.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/node_handle.h>

#include <functional>
#include <mutex>

namespace ball_collision_sim::bridge
{
/// dynamic_reconfigure's protocol for the node's run-time settings (SimulatorConfig) in its
/// private namespace, as dynamic_reconfigure::Server speaks it: the service set_parameters,
/// the latched topics parameter_descriptions and parameter_updates, and the values written
/// back to the parameters. Unlike that server, it refuses a request with a value out of
/// its range or enum (checkConfig()): the call fails with every "name: reason", so that the
/// caller is told (`dynparam set` prints it and exits 1), and nothing changes.
/// dynamic_reconfigure::Server clamps numbers into their range, takes any string, and its
/// callback cannot refuse: it logs what the callback throws and takes the values anyway.
class ReconfigureServer
{
 public:
  /// Takes a checked configuration: what the node runs with from then on.
  using Apply = std::function<void(const SimulatorConfig&)>;

  /// Publishes `initial` (the settings in use) and starts answering.
  ReconfigureServer(const ros::NodeHandle& pnh, const SimulatorConfig& initial, Apply apply);
  ReconfigureServer(const ReconfigureServer&) = delete;
  ReconfigureServer& operator=(const ReconfigureServer&) = delete;

  /// A configuration set another way (load_scene): published and written back.
  void update(const SimulatorConfig& config);

 private:
  /// Throws std::invalid_argument with the reasons of a refusal: roscpp answers the call
  /// with that text as its error (a `false` return would carry none).
  bool onSet(dynamic_reconfigure::Reconfigure::Request& req, dynamic_reconfigure::Reconfigure::Response& res);
  void publish();  // config_, with mutex_ held

  ros::NodeHandle pnh_;
  Apply apply_;
  std::mutex mutex_;  // guards config_, and keeps one request's check and apply together
  SimulatorConfig config_;
  ros::Publisher descriptions_pub_;
  ros::Publisher updates_pub_;
  ros::ServiceServer set_service_;
};
}  // namespace ball_collision_sim::bridge
