// load_client: calls the node's add_ball and remove_ball at a fixed total rate from a few
// threads, each over persistent connections, for a while; measures the node's real-time
// factor from /clock against wall time meanwhile, then checks on ball_states that every
// ball is there once: the initial ones and the added ones not removed. Run by
// scripts/load_test against a scene with an empty parking strip (slots in it are free).
//   load_client --rate CALLS_PER_S --seconds S --workers W --strip-y0 Y0 --strip-y1 Y1
//               --x0 X0 --x1 X1 --radius R
#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/BallStateArray.h>
#include <ball_collision_sim/RemoveObject.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace bcs = ball_collision_sim;
using Clock = std::chrono::steady_clock;

namespace
{
struct Options
{
  double rate = 1000;
  double seconds = 30;
  int workers = 4;
  double strip_y0 = 0, strip_y1 = 1, x0 = 0, x1 = 10, radius = 0.05;
};

struct Slot
{
  double x, y;
  int id = -1;  ///< the ball parked here, or -1
};

/// What one worker did.
struct Tally
{
  long calls = 0, answered = 0, call_errors = 0, adds = 0, removes = 0, failed = 0;
  std::map<std::string, long> failures;  ///< message -> count
  std::vector<double> latency_ms;
  std::set<int> parked;  ///< ids of the balls it added and has not removed
};

std::mutex g_clock_mutex;
std::vector<std::pair<double, double>> g_clock;  ///< (wall s since start, simulated s)
Clock::time_point g_start;

double since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void onClock(const rosgraph_msgs::Clock& msg)
{
  std::lock_guard<std::mutex> lock(g_clock_mutex);
  g_clock.emplace_back(since(g_start), msg.clock.toSec());
}

double latestSimTime()
{
  std::lock_guard<std::mutex> lock(g_clock_mutex);
  return g_clock.empty() ? 0.0 : g_clock.back().second;
}

/// One ball_states message stamped after `after` [s of simulated time].
bool statesAfter(double after, bcs::BallStateArray& out, double timeout)
{
  ros::NodeHandle nh;
  std::mutex mutex;
  bool got = false;
  ros::Subscriber sub = nh.subscribe<bcs::BallStateArray>(
      "/ball_sim/ball_states", 2,
      [&](const bcs::BallStateArray::ConstPtr& msg) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!got && msg->header.stamp.toSec() > after)
        {
          out = *msg;
          got = true;
        }
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  const auto start = Clock::now();
  while (since(start) < timeout)
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (got)
        break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  sub.shutdown();
  std::lock_guard<std::mutex> lock(mutex);
  return got;
}

void work(const Options& o, std::vector<Slot> slots, Clock::time_point t0, Tally& tally)
{
  ros::NodeHandle nh;
  auto add = nh.serviceClient<bcs::AddBall>("/ball_sim/add_ball", true);
  auto remove = nh.serviceClient<bcs::RemoveObject>("/ball_sim/remove_ball", true);
  const double period = o.workers / o.rate;
  const long total = static_cast<long>(o.seconds / period);
  std::size_t next = 0;
  for (long k = 0; k < total && ros::ok(); ++k)
  {
    std::this_thread::sleep_until(t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(k * period)));
    Slot& slot = slots[next];
    next = (next + 1) % slots.size();
    ++tally.calls;
    const auto start = Clock::now();
    bool ok = false, success = false;
    std::string message;
    if (slot.id < 0)
    {
      if (!add.isValid())
        add = nh.serviceClient<bcs::AddBall>("/ball_sim/add_ball", true);
      bcs::AddBall srv;
      srv.request.position.x = slot.x;
      srv.request.position.y = slot.y;
      srv.request.position.z = o.radius;
      srv.request.radius = o.radius;
      srv.request.mass = 1.0;
      ok = add.call(srv);
      success = ok && srv.response.success;
      message = srv.response.message;
      if (success)
      {
        slot.id = srv.response.id;
        tally.parked.insert(slot.id);
        ++tally.adds;
      }
    }
    else
    {
      if (!remove.isValid())
        remove = nh.serviceClient<bcs::RemoveObject>("/ball_sim/remove_ball", true);
      bcs::RemoveObject srv;
      srv.request.id = slot.id;
      ok = remove.call(srv);
      success = ok && srv.response.success;
      message = srv.response.message;
      if (success)
      {
        tally.parked.erase(slot.id);
        slot.id = -1;
        ++tally.removes;
      }
    }
    tally.latency_ms.push_back(1e3 * since(start));
    if (!ok)
    {
      ++tally.call_errors;
      ++tally.failures["no answer (connection lost)"];
      continue;
    }
    ++tally.answered;
    if (!success)
    {
      ++tally.failed;
      ++tally.failures[message];
    }
  }
}

double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * v.size()))];
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "load_client", ros::init_options::AnonymousName);
  Options o;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string flag = argv[i];
    const double value = std::atof(argv[i + 1]);
    if (flag == "--rate")
      o.rate = value;
    else if (flag == "--seconds")
      o.seconds = value;
    else if (flag == "--workers")
      o.workers = static_cast<int>(value);
    else if (flag == "--strip-y0")
      o.strip_y0 = value;
    else if (flag == "--strip-y1")
      o.strip_y1 = value;
    else if (flag == "--x0")
      o.x0 = value;
    else if (flag == "--x1")
      o.x1 = value;
    else if (flag == "--radius")
      o.radius = value;
    else
    {
      std::fprintf(stderr, "load_client: unknown option %s\n", flag.c_str());
      return 2;
    }
  }
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  g_start = Clock::now();
  ros::Subscriber clock = nh.subscribe("/clock", 1000, onClock, ros::TransportHints().tcpNoDelay());
  if (!ros::service::waitForService("/ball_sim/add_ball", ros::Duration(120)))
  {
    std::fprintf(stderr, "load_client: the node's services did not come up\n");
    return 1;
  }
  bcs::BallStateArray initial;
  if (!statesAfter(-1, initial, 60))
  {
    std::fprintf(stderr, "load_client: no ball_states from the node\n");
    return 1;
  }
  std::set<int> expected_ids;
  for (const auto& b : initial.balls)
    expected_ids.insert(b.id);

  // Free slots in the parking strip, a pitch of four radii, dealt out to the workers.
  const double pitch = 4 * o.radius;
  std::vector<std::vector<Slot>> slots(o.workers);
  int n = 0;
  for (double y = o.strip_y0 + 2 * o.radius; y <= o.strip_y1 - 2 * o.radius; y += pitch)
    for (double x = o.x0 + 2 * o.radius; x <= o.x1 - 2 * o.radius; x += pitch)
      slots[n++ % o.workers].push_back(Slot{x, y});

  std::this_thread::sleep_for(std::chrono::seconds(2));  // clock samples before the load
  std::vector<Tally> tallies(o.workers);
  const auto t0 = Clock::now() + std::chrono::milliseconds(200);
  const double load_start = std::chrono::duration<double>(t0 - g_start).count();
  std::vector<std::thread> threads;
  for (int w = 0; w < o.workers; ++w)
    threads.emplace_back(work, std::cref(o), slots[w], t0, std::ref(tallies[w]));
  for (auto& t : threads)
    t.join();
  const double load_end = since(g_start);
  const double sim_after = latestSimTime();

  // Real-time factor over the load, and the worst one-second window in it.
  std::vector<std::pair<double, double>> samples;
  {
    std::lock_guard<std::mutex> lock(g_clock_mutex);
    for (const auto& s : g_clock)
      if (s.first >= load_start && s.first <= load_end)
        samples.push_back(s);
  }
  double factor = 0, worst_window = 1e9;
  if (samples.size() > 2)
  {
    factor = (samples.back().second - samples.front().second) / (samples.back().first - samples.front().first);
    std::size_t j = 0;
    for (std::size_t i = 0; i < samples.size(); ++i)
    {
      while (j < samples.size() && samples[j].first < samples[i].first + 1.0)
        ++j;
      if (j < samples.size())
        worst_window = std::min(worst_window, (samples[j].second - samples[i].second) / (samples[j].first - samples[i].first));
    }
  }

  Tally total;
  for (const Tally& t : tallies)
  {
    total.calls += t.calls;
    total.answered += t.answered;
    total.call_errors += t.call_errors;
    total.adds += t.adds;
    total.removes += t.removes;
    total.failed += t.failed;
    for (const auto& [m, c] : t.failures)
      total.failures[m] += c;
    total.latency_ms.insert(total.latency_ms.end(), t.latency_ms.begin(), t.latency_ms.end());
    expected_ids.insert(t.parked.begin(), t.parked.end());
  }

  bcs::BallStateArray final_states;
  const bool got = statesAfter(sim_after, final_states, 30);
  std::set<int> seen;
  long doubled = 0;
  for (const auto& b : final_states.balls)
    if (!seen.insert(b.id).second)
      ++doubled;
  long missing = 0, extra = 0;
  for (int id : expected_ids)
    missing += seen.count(id) == 0;
  for (int id : seen)
    extra += expected_ids.count(id) == 0;
  const long expected = static_cast<long>(initial.balls.size()) + total.adds - total.removes;

  for (const auto& [m, c] : total.failures)
    std::printf("load_test: failure x%ld: %s\n", c, m.c_str());
  const bool counts_ok = got && static_cast<long>(final_states.balls.size()) == expected && missing == 0 &&
                         extra == 0 && doubled == 0;
  const bool realtime_ok = factor >= 0.9 && factor <= 1.1;
  const bool pass = counts_ok && realtime_ok && total.failed == 0 && total.call_errors == 0;
  std::printf("load_test: balls_initial=%zu wall_s=%.1f calls=%ld answered=%ld failed=%ld call_errors=%ld "
              "adds=%ld removes=%ld calls_per_s=%.0f latency_ms_median=%.2f latency_ms_p99=%.2f latency_ms_max=%.1f "
              "real_time_factor=%.3f worst_1s_window=%.3f balls_final=%zu balls_expected=%ld missing=%ld extra=%ld "
              "doubled=%ld result=%s\n",
              initial.balls.size(), load_end - load_start, total.calls, total.answered, total.failed,
              total.call_errors, total.adds, total.removes, total.calls / (load_end - load_start),
              percentile(total.latency_ms, 0.5), percentile(total.latency_ms, 0.99), percentile(total.latency_ms, 1.0),
              factor, worst_window, final_states.balls.size(), expected, missing, extra, doubled,
              pass ? "PASS" : "FAIL");
  spinner.stop();
  ros::shutdown();
  return pass ? 0 : 1;
}
