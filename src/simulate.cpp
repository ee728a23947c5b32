// simulate: runs a scene offline as fast as possible (design.md section 6).
// stdout carries exactly one line, the summary, so that scripts can take `tail -n1`;
// every error goes to stderr as one "simulate: error: ..." line.

#include "simulate_options.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/world.hpp"
#include "ball_collision_sim/ros/run_bag.hpp"
#include "ball_collision_sim/yaml/scene_yaml.hpp"

#include <rosbag/exceptions.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <csignal>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <sstream>
#include <unistd.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using ball_collision_sim::core::Ball;
using ball_collision_sim::core::formatNumber;
using ball_collision_sim::core::Scene;
using ball_collision_sim::core::World;
using ball_collision_sim::tools::SimulateOptions;

constexpr int kExitInternalError = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it

volatile std::sig_atomic_t g_interrupted = 0;

void onInterrupt(int)
{
  g_interrupted = 1;
}

/// A progress bar on stderr, only when stderr is a terminal: done, ETA, and how much
/// faster than real time the run goes. At most ten updates a second.
class Progress
{
public:
  Progress(std::uint64_t total_steps, double dt)
      : enabled_(isatty(fileno(stderr)) != 0 && total_steps > 0), total_(total_steps), dt_(dt)
  {
  }
  void update(std::uint64_t step, double wall_seconds)
  {
    if (!enabled_ || (wall_seconds - last_ < 0.1 && step != total_))
      return;
    last_ = wall_seconds;
    const double done = static_cast<double>(step) / static_cast<double>(total_);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(done * kWidth);
    const double eta = done > 0 ? wall_seconds * (1 - done) / done : 0.0;
    const double ratio = wall_seconds > 0 ? static_cast<double>(step) * dt_ / wall_seconds : 0.0;
    std::fprintf(stderr, "\r[%.*s%.*s] %3.0f%%  t = %.2f / %.2f s  ETA %.1f s  %.1fx real time ", filled,
                 "##############################", kWidth - filled, "..............................", 100 * done,
                 static_cast<double>(step) * dt_, static_cast<double>(total_) * dt_, eta, ratio);
    std::fflush(stderr);
    shown_ = true;
  }
  /// Ends the bar's line so that what follows starts on a fresh one.
  void finish()
  {
    if (shown_)
      std::fputc('\n', stderr);
  }

private:
  bool enabled_;
  std::uint64_t total_;
  double dt_;
  double last_ = -1.0;
  bool shown_ = false;
};

// Steps are counted in floating point first; beyond this a run could never finish and the
// count would lose integer precision.
constexpr double kMaxSteps = 1e15;

int reportBadInput(const std::string& message)
{
  std::fprintf(stderr, "simulate: error: %s\n", message.c_str());
  return kExitBadInput;
}

/// The same for a command line that asks for what cannot be, with the usage hint.
int reportBadCommandLine(const std::string& message)
{
  std::fprintf(stderr, "simulate: error: %s\nTry 'simulate --help' for usage.\n", message.c_str());
  return kExitBadInput;
}

// One row per ball per sample, each number the shortest that reads back to the same bits:
// the CSV is ground truth, not a plot.
class CsvWriter
{
public:
  /// Opens the file and writes the header; the error text when it cannot be opened.
  /// With `spin` (a scene with friction, where balls have their own spin) each row ends
  /// with the angular velocity, wx,wy,wz.
  std::string open(const std::string& path, bool spin)
  {
    path_ = path;
    spin_ = spin;
    file_.reset(std::fopen(path.c_str(), "w"));
    if (!file_)
    {
      const int open_errno = errno;  // before the message's allocations can change it
      return path + ": cannot open for writing (" + std::strerror(open_errno) + ")";
    }
    // A large buffer: a sample per step of many balls is a lot of small writes.
    buffer_.resize(1 << 20);
    std::setvbuf(file_.get(), buffer_.data(), _IOFBF, buffer_.size());
    std::fputs(spin ? "t,id,x,y,z,vx,vy,vz,wx,wy,wz\n" : "t,id,x,y,z,vx,vy,vz\n", file_.get());
    return "";
  }

  bool isOpen() const { return file_ != nullptr; }

  void writeSample(const World& world)
  {
    const std::string t = formatNumber(world.time());
    const auto put = [&](const ball_collision_sim::core::Vec3& v) {
      for (int c = 0; c < 3; ++c)
      {
        std::fputc(',', file_.get());
        std::fputs(formatNumber(v[c]).c_str(), file_.get());
      }
    };
    for (std::size_t k = 0; k < world.balls().size(); ++k)
    {
      const Ball& ball = world.balls()[k];
      std::fprintf(file_.get(), "%s,%d", t.c_str(), ball.id);
      put(ball.position);
      put(ball.velocity);
      if (spin_)
        put(world.angularVelocity(k));
      std::fputc('\n', file_.get());
    }
  }

  /// Flushes and closes; the error text when anything failed to be written (disk full).
  std::string close()
  {
    if (!file_)
    {
      return "";
    }
    // fclose flushes the buffer, so a full disk may show only here.
    const bool write_failed = std::ferror(file_.get()) != 0;
    const int write_errno = errno;
    const bool close_failed = std::fclose(file_.release()) != 0;
    const int close_errno = errno;
    if (write_failed || close_failed)
    {
      return path_ + ": write failed (" + std::strerror(write_failed ? write_errno : close_errno) + ")";
    }
    return "";
  }

private:
  struct FileCloser
  {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::string path_;
  bool spin_ = false;
  // Declared before file_ so that it is destroyed after it: fclose flushes from it.
  std::vector<char> buffer_;
  std::unique_ptr<std::FILE, FileCloser> file_;
};

/// What a run reads and writes, made by prepareRun().
struct Run
{
  ball_collision_sim::yaml::SceneFile file;
  std::unique_ptr<World> world;
  std::uint64_t steps = 0;
  CsvWriter csv;
  std::unique_ptr<ball_collision_sim::bridge::RunBag> bag;
};

/// The number of steps the duration asks for, in `steps`; the error text when it is too
/// many.
std::string stepsOf(const SimulateOptions& options, double dt, std::uint64_t& steps)
{
  // The small epsilon keeps a duration that is a whole number of steps from taking an
  // extra one when the division rounds up: 0.07 / 0.01 is 7.000000000000001 in doubles.
  const double exact_steps = options.duration / dt;
  if (!(exact_steps <= kMaxSteps))
  {
    char message[160];
    std::snprintf(message, sizeof(message), "--duration: %s s at dt = %s s is more than %s steps",
                  formatNumber(options.duration).c_str(), formatNumber(dt).c_str(), formatNumber(kMaxSteps).c_str());
    return message;
  }
  steps = static_cast<std::uint64_t>(std::max(0.0, std::ceil(exact_steps - 1e-9)));
  return {};
}

/// Loads the scene, builds its world and opens the outputs: 0, or the exit status of
/// what was refused (reported).
int prepareRun(const SimulateOptions& options, Run& run)
{
  try
  {
    run.file = ball_collision_sim::yaml::loadValidSceneFile(options.scene_path);
  }
  catch (const ball_collision_sim::yaml::SceneError& e)
  {
    return reportBadInput(e.what());
  }
  // validate() has passed, so this throws only if the core finds something validate()
  // missed; that is still the scene's fault, reported the same way.
  try
  {
    ball_collision_sim::core::StepSettings settings;
    settings.threads = options.threads;
    run.world = std::make_unique<World>(run.file.scene, std::move(run.file.checked), settings);
  }
  catch (const std::invalid_argument& e)
  {
    return reportBadInput(options.scene_path + ": " + e.what());
  }
  const std::string too_long = stepsOf(options, run.world->dt(), run.steps);
  if (!too_long.empty())
    return reportBadCommandLine(too_long);
  if (!options.csv_path.empty())
  {
    const std::string error = run.csv.open(options.csv_path, run.world->friction().has_value());
    if (!error.empty())
      return reportBadInput("--csv: " + error);
  }
  if (!options.bag_path.empty())
  {
    try
    {
      run.bag = std::make_unique<ball_collision_sim::bridge::RunBag>(
          options.bag_path, *run.world, run.file.node,
          ball_collision_sim::yaml::writeScene(run.file.scene, run.file.node), options.marker_rate);
    }
    catch (const rosbag::BagException& e)
    {
      return reportBadInput("--bag: " + options.bag_path + ": cannot write the bag (" + e.what() + ")");
    }
  }
  // Only the bag reads each step's list of collisions; the summary counts them anyway.
  run.world->recordEvents(run.bag != nullptr);
  return 0;
}

/// One step and its outputs; returns how many balls left the world in it (reported once
/// and taken out, as the node does).
std::size_t stepOnce(const SimulateOptions& options, Run& run, std::uint64_t step, Progress& progress)
{
  World& world = *run.world;
  world.step();
  const std::vector<ball_collision_sim::core::LostBall> gone = world.removeLostBalls();
  for (const ball_collision_sim::core::LostBall& ball : gone)
  {
    progress.finish();
    std::fprintf(stderr, "simulate: t = %s s: ball %d %s at (%s, %s, %s) m; removed from the world\n",
                 formatNumber(world.time()).c_str(), ball.ball.id, ball.reason.c_str(),
                 formatNumber(ball.ball.position.x()).c_str(), formatNumber(ball.ball.position.y()).c_str(),
                 formatNumber(ball.ball.position.z()).c_str());
  }
  if (run.bag && !gone.empty())
    run.bag->lost(world, gone);
  if (run.bag && !world.lastPocketed().empty())
    run.bag->pocketed(world);
  if (run.csv.isOpen() && step % options.sample_every == 0)
    run.csv.writeSample(world);
  if (run.bag)
    run.bag->afterStep(world);
  return gone.size();
}

/// Closes the outputs and prints the summary: the run's exit status.
int finishRun(Run& run, double energy_start, std::uint64_t lost, double wall_seconds, const std::string& csv_error)
{
  const World& world = *run.world;
  if (run.bag)
    run.bag->close();
  if (!csv_error.empty())
  {
    std::fprintf(stderr, "simulate: error: %s\n", csv_error.c_str());
    return kExitInternalError;
  }
  std::printf(
      "summary: steps=%llu events=%llu floor_impacts=%llu wall_s=%.6f energy_start=%s energy_end=%s "
      "balls_lost=%d balls_pocketed=%llu\n",
      static_cast<unsigned long long>(world.stats().steps), static_cast<unsigned long long>(world.stats().events),
      static_cast<unsigned long long>(world.stats().floor_impacts), wall_seconds, formatNumber(energy_start).c_str(),
      formatNumber(world.energy().total()).c_str(), static_cast<int>(lost) + world.lostBalls(),
      static_cast<unsigned long long>(world.stats().pocketed_balls));
  if (std::fflush(stdout) != 0)
    return kExitInternalError;
  if (g_interrupted)
  {
    std::fprintf(stderr, "simulate: interrupted at t = %s s; outputs hold the run so far\n",
                 formatNumber(world.time()).c_str());
    return kExitInterrupted;
  }
  return 0;
}

int run(const SimulateOptions& options)
{
  Run run;
  if (const int refused = prepareRun(options, run))
    return refused;
  const double energy_start = run.world->energy().total();
  if (run.csv.isOpen())
    run.csv.writeSample(*run.world);
  // Ctrl-C ends the loop, and the outputs are closed as if the run had been that long.
  std::signal(SIGINT, onInterrupt);
  Progress progress(run.steps, run.world->dt());
  const auto wall_start = std::chrono::steady_clock::now();
  const auto wallSeconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  std::uint64_t lost = 0;
  for (std::uint64_t step = 1; step <= run.steps && !g_interrupted; ++step)
  {
    lost += stepOnce(options, run, step, progress);
    progress.update(step, wallSeconds());
  }
  progress.finish();
  const std::string csv_error = run.csv.close();
  return finishRun(run, energy_start, lost, wallSeconds(), csv_error);
}
}  // namespace

int main(int argc, char** argv)
{
  ros::Time::init();  // rosbag stamps need ros::Time, without a master
  const std::vector<std::string> args(argv + 1, argv + argc);
  const ball_collision_sim::tools::ParsedOptions parsed = ball_collision_sim::tools::parseSimulateOptions(args);
  if (!parsed.ok())
    return reportBadCommandLine(parsed.error);
  if (parsed.options.help)
  {
    std::fputs(ball_collision_sim::tools::simulateUsage().c_str(), stdout);
    return 0;
  }
  try
  {
    return run(parsed.options);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "simulate: internal error: %s\n", e.what());
    return kExitInternalError;
  }
}
