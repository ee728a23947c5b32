#include "simulate_options.hpp"

#include "ball_collision_sim/core/step_settings.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

namespace ball_collision_sim::tools
{
namespace
{
std::string quoted(const std::string& text)
{
  return "'" + text + "'";
}

// A whole-string decimal number; from_chars ignores the locale and takes no "0x".
std::optional<double> parseNumber(const std::string& text)
{
  const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  double value = 0.0;
  const std::from_chars_result result = std::from_chars(first, last, value);
  if (first == last || result.ec != std::errc() || result.ptr != last)
  {
    return std::nullopt;
  }
  return value;
}

std::optional<std::uint64_t> parseCount(const std::string& text)
{
  const char* first = text.data();
  const char* last = text.data() + text.size();
  std::uint64_t value = 0;
  const std::from_chars_result result = std::from_chars(first, last, value);
  if (first == last || result.ec != std::errc() || result.ptr != last)
  {
    return std::nullopt;
  }
  return value;
}

bool isHelp(const std::string& arg)
{
  return arg == "-h" || arg == "--help";
}
}  // namespace

std::string simulateUsage()
{
  return "usage: simulate SCENE.yaml --duration SECONDS [--bag OUT.bag] [--marker-rate HZ] [--csv OUT.csv]\n"
         "                [--sample-every N] [--threads N]\n"
         "\n"
         "Runs a scene as fast as the machine allows and prints a one-line summary on stdout:\n"
         "  summary: steps=S events=E floor_impacts=F wall_s=W energy_start=A energy_end=B balls_lost=L\n"
         "\n"
         "  SCENE.yaml          the scene (see config/*.yaml)\n"
         "  --duration SECONDS  simulated time to run; ceil(SECONDS / dt) steps\n"
         "  --csv OUT.csv       write t,id,x,y,z,vx,vy,vz for every ball at t = 0 and per sample\n"
         "  --sample-every N    a CSV sample after every N-th step (default 1)\n"
         "  --bag OUT.bag       write the node's topics (/clock, /tf, /ball_sim/...) stamped with\n"
         "                      simulated time; Ctrl-C closes a valid bag of the run so far\n"
         "  --marker-rate HZ    markers per simulated second in the bag (default 30; 0: the first only)\n"
         "  --threads N         threads the step runs on (default 1; 0: every core); the same bits\n"
         "                      for every N\n"
         "  -h, --help          print this help\n"
         "\n"
         "On a terminal, a progress bar with ETA goes to stderr.\n"
         "Exit status: 0 done, 2 bad command line or bad scene, 1 internal error,\n"
         "130 stopped by Ctrl-C (the outputs hold the run so far).\n";
}

namespace
{
/// Which options have been given, so that one given twice is refused.
struct Given
{
  bool duration = false;
  bool sample_every = false;
  bool marker_rate = false;
  bool threads = false;
};

// A positional argument: the scene ("-" alone or "-1" would be one too).
bool isPositional(const std::string& arg, bool options_ended)
{
  return options_ended || arg.size() < 2 || arg[0] != '-' ||
         (arg[1] != '-' && !std::isalpha(static_cast<unsigned char>(arg[1])));
}

bool isKnownFlag(const std::string& flag)
{
  return flag == "--duration" || flag == "--bag" || flag == "--csv" || flag == "--sample-every" ||
         flag == "--marker-rate" || flag == "--threads";
}

// Each option's value into `options`: the error, or empty.
std::string takeDuration(const std::string& value, SimulateOptions& options, Given& given)
{
  if (std::exchange(given.duration, true))
    return "--duration: given twice";
  const std::optional<double> seconds = parseNumber(value);
  if (!seconds || !std::isfinite(*seconds))
    return "--duration: expected a number of seconds, got " + quoted(value);
  if (*seconds < 0.0)
    return "--duration: must be >= 0, got " + value;
  options.duration = *seconds;
  return {};
}

std::string takeMarkerRate(const std::string& value, SimulateOptions& options, Given& given)
{
  if (std::exchange(given.marker_rate, true))
    return "--marker-rate: given twice";
  const std::optional<double> rate = parseNumber(value);
  if (!rate || !std::isfinite(*rate) || *rate < 0.0)
    return "--marker-rate: expected a rate >= 0 in Hz, got " + quoted(value);
  options.marker_rate = *rate;
  return {};
}

std::string takeSampleEvery(const std::string& value, SimulateOptions& options, Given& given)
{
  if (std::exchange(given.sample_every, true))
    return "--sample-every: given twice";
  const std::optional<std::uint64_t> n = parseCount(value);
  if (!n || *n == 0)
    return "--sample-every: expected an integer >= 1, got " + quoted(value);
  options.sample_every = *n;
  return {};
}

std::string takeThreads(const std::string& value, SimulateOptions& options, Given& given)
{
  if (std::exchange(given.threads, true))
    return "--threads: given twice";
  const std::optional<std::uint64_t> n = parseCount(value);
  if (!n || *n > ball_collision_sim::core::kMaxThreads)
    return "--threads: expected an integer from 0 (every core) to " +
           std::to_string(ball_collision_sim::core::kMaxThreads) + ", got " +
           quoted(value);
  options.threads = static_cast<unsigned>(*n);
  return {};
}

std::string takePath(const std::string& flag, const std::string& value, SimulateOptions& options)
{
  std::string& path = flag == "--bag" ? options.bag_path : options.csv_path;
  if (!path.empty())
    return flag + ": given twice";
  if (value.empty())
    return flag + ": missing file name";
  path = value;
  return {};
}

std::string takeOption(const std::string& flag, const std::string& value, SimulateOptions& options, Given& given)
{
  if (flag == "--duration")
    return takeDuration(value, options, given);
  if (flag == "--marker-rate")
    return takeMarkerRate(value, options, given);
  if (flag == "--sample-every")
    return takeSampleEvery(value, options, given);
  if (flag == "--threads")
    return takeThreads(value, options, given);
  return takePath(flag, value, options);
}

// --help wins, so that "simulate --durtion 3 --help" still shows the usage.
bool asksForHelp(const std::vector<std::string>& args)
{
  for (const std::string& arg : args)
  {
    if (arg == "--")
      return false;
    if (isHelp(arg))
      return true;
  }
  return false;
}
}  // namespace

ParsedOptions parseSimulateOptions(const std::vector<std::string>& args)
{
  ParsedOptions parsed;
  SimulateOptions& options = parsed.options;
  if (asksForHelp(args))
  {
    options.help = true;
    return parsed;
  }
  Given given;
  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (isPositional(arg, options_ended))
    {
      if (!options.scene_path.empty())
      {
        parsed.error = "unexpected argument " + quoted(arg) + " (only one scene file is taken)";
        return parsed;
      }
      options.scene_path = arg;
      continue;
    }
    if (arg == "--")
    {
      options_ended = true;
      continue;
    }
    // "--flag=value", or "--flag value"
    const std::size_t equals = arg.rfind("--", 0) == 0 ? arg.find('=') : std::string::npos;
    const std::string flag = arg.substr(0, equals);
    if (!isKnownFlag(flag))
    {
      parsed.error = "unknown option " + quoted(flag);
      return parsed;
    }
    std::string value;
    if (equals != std::string::npos)
      value = arg.substr(equals + 1);
    else if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
    {
      // ("--duration -1" must reach the number check, so only a long option or the end
      // of the line counts as a missing value)
      parsed.error = flag + ": missing value";
      return parsed;
    }
    else
      value = args[++i];
    parsed.error = takeOption(flag, value, options, given);
    if (!parsed.error.empty())
      return parsed;
  }
  if (options.scene_path.empty())
    parsed.error = "missing the scene file (SCENE.yaml)";
  else if (!given.duration)
    parsed.error = "missing --duration SECONDS";
  return parsed;
}
}  // namespace ball_collision_sim::tools
