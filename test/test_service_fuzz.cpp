// Random requests to every service of a running node (rostest test/service_fuzz.test on
// test/data/fuzz_scene.yaml), through persistent clients: after every request the node
// answers get_state, every number in it is finite, and a refused request (success false,
// or a failed call where that is how a service refuses: set_parameters) changed nothing:
// the state is the same bits (time, steps, balls, walls, ...), and for set_parameters and
// load_scene the node's parameters too. The seed is fixed and printed; BCS_FUZZ_SEED
// replaces it. kRequestsPerService requests go to each service (BCS_FUZZ_REQUESTS
// replaces the number), in a shuffled order: 280,000 in all, about 95 s on the 2-core CI
// machine (a request with its checks takes about 0.3 ms on average). Under the
// sanitizers (BCS_SLOWDOWN, e.g. 4), whose requests take several times as long and which
// look for what the requests do to memory, 5 x BCS_SLOWDOWN times fewer (1,000 to each
// service at 4), to keep the time.
#include "service_fuzz_requests.hpp"

#include <ball_collision_sim/GetState.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace bcs = ball_collision_sim;

namespace
{
constexpr std::uint64_t kSeed = 20240611;
constexpr int kRequestsPerService = 20000;
const std::string kNode = "/ball_sim/";

std::uint64_t seed()
{
  const char* given = std::getenv("BCS_FUZZ_SEED");
  return given ? std::strtoull(given, nullptr, 10) : kSeed;
}

int slowdown()
{
  const char* given = std::getenv("BCS_SLOWDOWN");
  return given ? std::max(1, std::atoi(given)) : 1;
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The state's bits: the whole answer but its message (which a paused flag changes).
std::vector<std::uint8_t> bitsOf(bcs::GetState::Response state)
{
  state.message.clear();
  const ros::SerializedMessage m = ros::serialization::serializeMessage(state);
  return std::vector<std::uint8_t>(m.buf.get(), m.buf.get() + m.num_bytes);
}

/// The first number of the state that is not finite, or "".
std::string nonFinite(const bcs::GetState::Response& s)
{
  std::vector<std::pair<std::string, double>> numbers = {{"time", s.time}};
  for (const bcs::BallState& b : s.balls)
  {
    const std::string ball = "ball " + std::to_string(b.id) + " ";
    const auto& p = b.pose;
    const auto& t = b.twist;
    for (const auto& [name, value] : {std::pair{"radius", b.radius},
                                      {"mass", b.mass},
                                      {"inertia", b.inertia},
                                      {"x", p.position.x},
                                      {"y", p.position.y},
                                      {"z", p.position.z},
                                      {"qx", p.orientation.x},
                                      {"qy", p.orientation.y},
                                      {"qz", p.orientation.z},
                                      {"qw", p.orientation.w},
                                      {"vx", t.linear.x},
                                      {"vy", t.linear.y},
                                      {"vz", t.linear.z},
                                      {"wx", t.angular.x},
                                      {"wy", t.angular.y},
                                      {"wz", t.angular.z}})
      numbers.emplace_back(ball + name, value);
  }
  for (const bcs::Wall& w : s.walls)
    for (const auto& [name, value] : {std::pair{"point.x", w.point.x},
                                      {"point.y", w.point.y},
                                      {"point.z", w.point.z},
                                      {"u.x", w.u.x},
                                      {"u.y", w.u.y},
                                      {"u.z", w.u.z},
                                      {"v.x", w.v.x},
                                      {"v.y", w.v.y},
                                      {"v.z", w.v.z},
                                      {"restitution", w.restitution}})
      numbers.emplace_back("wall " + std::to_string(w.id) + " " + name, value);
  for (const auto& [name, value] : numbers)
    if (!std::isfinite(value))
      return name + " = " + std::to_string(value);
  return "";
}

/// The node's parameters as text (XML-RPC's), to see that a refusal left them alone.
std::string paramsNow()
{
  XmlRpc::XmlRpcValue tree;
  ros::param::get(kNode, tree);
  return tree.toXml();
}

/// What one request did: whether the node answered, whether it took the request, and the
/// request as text for the report.
struct Outcome
{
  bool answered = false;
  bool success = false;
  std::string request;
};

template <class Request>
std::string text(const Request& req)
{
  std::ostringstream out;
  out.precision(17);  // (every bit of a double, to send the request again)
  out << req;
  return out.str();
}

class ServiceFuzz
{
 public:
  ServiceFuzz(std::uint64_t seed, const std::string& scene_text, const std::vector<std::string>& paths)
      : seed_(seed), fuzz_(seed, scene_text, paths)
  {
  }

  /// The services, each a function that sends one random request.
  std::vector<std::pair<std::string, std::function<Outcome()>>> services()
  {
    return {
        {"get_state", [this] { return call<bcs::GetState>("get_state", {}); }},
        {"add_ball", [this] { return call<bcs::AddBall>("add_ball", fuzz_.addBall()); }},
        {"add_wall", [this] { return call<bcs::AddWall>("add_wall", fuzz_.addWall()); }},
        {"remove_ball", [this] { return call<bcs::RemoveObject>("remove_ball", fuzz_.remove(ballIds())); }},
        {"remove_wall", [this] { return call<bcs::RemoveObject>("remove_wall", fuzz_.remove(wallIds())); }},
        {"set_ball_state", [this] { return call<bcs::SetBallState>("set_ball_state", fuzz_.setBallState(ballIds())); }},
        {"apply_impulse", [this] { return call<bcs::ApplyImpulse>("apply_impulse", fuzz_.applyImpulse(ballIds())); }},
        {"strike", [this] { return call<bcs::Strike>("strike", fuzz_.strike(ballIds())); }},
        {"step", [this] { return call<bcs::Step>("step", fuzz_.step()); }},
        {"pause", [this] { return call<std_srvs::SetBool>("pause", fuzz_.pause()); }},
        {"reset", [this] { return call<std_srvs::Trigger>("reset", {}); }},
        {"cancel_step", [this] { return call<std_srvs::Trigger>("cancel_step", {}); }},
        {"load_scene", [this] { return call<bcs::LoadScene>("load_scene", fuzz_.loadScene()); }},
        {"set_parameters",
         [this] { return call<dynamic_reconfigure::Reconfigure>("set_parameters", fuzz_.reconfigure()); }},
    };
  }

  /// Sends requests[k] (an index into services()) for every k, checking each.
  void run(const std::vector<std::size_t>& requests)
  {
    auto all = services();
    state_ = getState();
    params_ = paramsNow();
    for (std::size_t k = 0; k < requests.size(); ++k)
    {
      if (!state_.paused)  // (a running world changes by itself: pause it to compare)
      {
        std_srvs::SetBool pause;
        pause.request.data = true;
        ASSERT_TRUE(client<std_srvs::SetBool>("pause").call(pause)) << "the node died";
        state_ = getState();
      }
      const auto& [name, send] = all[requests[k]];
      fuzz_.begin();
      const auto sent = std::chrono::steady_clock::now();
      const Outcome outcome = send();
      const std::string where =
          "request " + std::to_string(k) + " (seed " + std::to_string(seed_) + ") to " + name + ":\n" + outcome.request;
      // a refused set_parameters fails its call; any other failed call is a dead node
      ASSERT_TRUE(outcome.answered || name == "set_parameters") << "no answer (the node died?) to " << where;
      const bcs::GetState::Response after = getState();
      ASSERT_TRUE(after.success) << "get_state failed (the node died?) after " << where;
      const std::string bad = nonFinite(after);
      ASSERT_EQ(bad, "") << "not finite after " << where;
      if (!outcome.success && state_.paused)
      {
        ASSERT_TRUE(bitsOf(after) == bitsOf(state_)) << "refused but changed the state: " << where;
      }
      if (name == "set_parameters" || name == "load_scene")
      {
        const std::string params = paramsNow();
        if (!outcome.success)
        {
          ASSERT_EQ(params, params_) << "refused but changed the parameters: " << where;
        }
        params_ = params;
      }
      ++(outcome.success ? taken_ : refused_)[name];
      seconds_[name] += std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
      state_ = after;
    }
  }

  std::map<std::string, int> taken_, refused_;
  std::map<std::string, double> seconds_;  ///< wall time of the requests and their checks

 private:
  template <class Srv>
  ros::ServiceClient& client(const std::string& name)
  {
    ros::ServiceClient& c = clients_[name];
    if (!c.isValid())  // (first use; or a refusal by a failed call closed it)
      c = nh_.serviceClient<Srv>(kNode + name, true);
    return c;
  }

  template <class Srv>
  Outcome call(const std::string& name, const typename Srv::Request& request)
  {
    Srv srv;
    srv.request = request;
    Outcome outcome;
    outcome.request = text(request);
    outcome.answered = client<Srv>(name).call(srv);
    if constexpr (std::is_same_v<Srv, dynamic_reconfigure::Reconfigure>)
      outcome.success = outcome.answered;  // (it refuses by failing the call)
    else
      outcome.success = outcome.answered && srv.response.success;
    return outcome;
  }

  bcs::GetState::Response getState()
  {
    bcs::GetState srv;
    if (!client<bcs::GetState>("get_state").call(srv))
      srv.response.success = false;
    return srv.response;
  }

  std::vector<int> ballIds() const
  {
    std::vector<int> ids;
    for (const bcs::BallState& b : state_.balls) ids.push_back(b.id);
    return ids;
  }

  std::vector<int> wallIds() const
  {
    std::vector<int> ids;
    for (const bcs::Wall& w : state_.walls) ids.push_back(w.id);
    return ids;
  }

  std::uint64_t seed_;
  ros::NodeHandle nh_;
  std::map<std::string, ros::ServiceClient> clients_;
  bcs::test::RequestFuzz fuzz_;
  bcs::GetState::Response state_;
  std::string params_;
};
}  // namespace

TEST(ServiceFuzz, RefusedRequestsChangeNothingAndTheStateStaysFinite)
{
  const std::string data = BCS_TEST_DATA_DIR;
  const std::vector<std::string> paths = {data + "/fuzz_scene.yaml",
                                          data + "/node_scene.yaml",
                                          data + "/good_small.yaml",
                                          data + "/empty.yaml",
                                          data + "/bad_nan.yaml",
                                          data + "/bad_overlap.yaml",
                                          data + "/bad_unknown_key.yaml",
                                          data + "/bad_malformed.yaml",
                                          data + "/bad_ball_color.yaml",
                                          data + "/garbage.bin",
                                          data + "/no_such_file.yaml",
                                          data,
                                          "",
                                          "/",
                                          "package://ball_collision_sim/test/data/node_scene.yaml",
                                          "package://no_such_package/x.yaml",
                                          "package://",
                                          "relative/scene.yaml"};
  const std::uint64_t s = seed();
  const char* count = std::getenv("BCS_FUZZ_REQUESTS");
  const int per_service = (count ? std::atoi(count) : kRequestsPerService) / (slowdown() > 1 ? 5 * slowdown() : 1);
  ServiceFuzz fuzz(s, readFile(data + "/fuzz_scene.yaml"), paths);
  const std::size_t services = fuzz.services().size();
  std::vector<std::size_t> requests;
  for (std::size_t k = 0; k < services; ++k) requests.insert(requests.end(), per_service, k);
  std::shuffle(requests.begin(), requests.end(), std::mt19937_64(s));
  std::printf("service fuzz: seed %llu (BCS_FUZZ_SEED), %d requests to each of %zu services\n",
              static_cast<unsigned long long>(s), per_service, services);
  const auto start = std::chrono::steady_clock::now();
  fuzz.run(requests);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("service fuzz: %zu requests in %.1f s\n", requests.size(), seconds);
  for (const auto& [name, send] : fuzz.services())
    std::printf("  %-15s %6d taken, %6d refused, %5.2f s\n", name.c_str(), fuzz.taken_[name], fuzz.refused_[name],
                fuzz.seconds_[name]);
  // the requests were what they were meant to be: of each kind that can go either way,
  // some taken and some refused
  for (const char* name : {"add_ball", "add_wall", "remove_ball", "remove_wall", "set_ball_state", "apply_impulse",
                           "strike", "step", "load_scene", "set_parameters"})
  {
    EXPECT_GT(fuzz.taken_[name], 0) << name;
    EXPECT_GT(fuzz.refused_[name], 0) << name;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_service_fuzz");
  // (a refused set_parameters fails its call, and roscpp logs an error for each)
  if (ros::console::set_logger_level(ROSCONSOLE_ROOT_LOGGER_NAME ".roscpp", ros::console::levels::Fatal))
    ros::console::notifyLoggerLevelsChanged();
  ros::AsyncSpinner spinner(1);
  spinner.start();
  if (!ros::service::waitForService(kNode + "set_parameters", ros::Duration(20.0)))
  {
    ADD_FAILURE() << "the node's services did not come up";
    return 1;
  }
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
