#pragma once
// Random requests for the node's services (test_service_fuzz.cpp), drawn from one seeded
// generator: numbers of the table's scale and every awkward double (NaN, inf, 1e300,
// denormals, -0), ids of objects that exist and of none, flags, placements, step counts
// bounded in time, and scene text and paths for load_scene. About half the requests are
// plausible throughout, so that many succeed and the state keeps changing.

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/ApplyImpulse.h>
#include <ball_collision_sim/LoadScene.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ball_collision_sim/SetBallState.h>
#include <ball_collision_sim/Step.h>
#include <ball_collision_sim/Strike.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Vector3.h>
#include <std_srvs/SetBool.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace ball_collision_sim::test
{
class RequestFuzz
{
 public:
  /// `scene_text`: a good scene whose mutations load_scene gets; `paths`: files to offer it.
  RequestFuzz(std::uint64_t seed, std::string scene_text, std::vector<std::string> paths);

  /// Starts a request: plausible throughout, or with awkward values mixed in.
  void begin();

  AddBall::Request addBall();
  AddWall::Request addWall();
  /// An id among `ids` (the objects that exist) or one that names none.
  RemoveObject::Request remove(const std::vector<int>& ids);
  SetBallState::Request setBallState(const std::vector<int>& ids);
  ApplyImpulse::Request applyImpulse(const std::vector<int>& ids);
  Strike::Request strike(const std::vector<int>& ids);
  /// Counts that run quickly (at most kMaxFuzzSteps) or that must be refused.
  Step::Request step();
  std_srvs::SetBool::Request pause();
  LoadScene::Request loadScene();
  dynamic_reconfigure::Reconfigure::Request reconfigure();

  bool coin(double p);

 private:
  /// A number: uniform in [lo, hi] when plausible, else now and then an awkward one.
  double number(double lo, double hi);
  geometry_msgs::Vector3 vector(double scale);
  geometry_msgs::Point point();
  int id(const std::vector<int>& ids);
  std::uint8_t placement();
  std::string mutatedScene();
  std::string bytes();

  std::mt19937_64 rng_;
  std::string scene_text_;
  std::vector<std::string> paths_;
  bool plausible_ = true;
};

/// Steps a fuzzed step request may ask for and run: what keeps a run short.
constexpr std::uint32_t kMaxFuzzSteps = 200;
}  // namespace ball_collision_sim::test
