#include "simulate_options.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

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
         "                [--sample-every N]\n"
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
         "  -h, --help          print this help\n"
         "\n"
         "On a terminal, a progress bar with ETA goes to stderr.\n"
         "Exit status: 0 done, 2 bad command line or bad scene, 1 internal error,\n"
         "130 stopped by Ctrl-C (the outputs hold the run so far).\n";
}

ParsedOptions parseSimulateOptions(const std::vector<std::string>& args)
{
  ParsedOptions parsed;
  SimulateOptions& options = parsed.options;

  // --help wins, so that "simulate --durtion 3 --help" still shows the usage.
  for (const std::string& arg : args)
  {
    if (arg == "--")
    {
      break;
    }
    if (isHelp(arg))
    {
      options.help = true;
      return parsed;
    }
  }

  bool have_duration = false;
  bool have_sample_every = false;
  bool have_marker_rate = false;
  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (options_ended || arg.size() < 2 || arg[0] != '-' || (arg[1] != '-' && !std::isalpha(static_cast<unsigned char>(arg[1]))))
    {
      // A positional argument: the scene ("-" alone or "-1" would be one too).
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

    std::string flag = arg;
    std::optional<std::string> value;
    const std::size_t equals = arg.find('=');
    if (arg.rfind("--", 0) == 0 && equals != std::string::npos)
    {
      flag = arg.substr(0, equals);
      value = arg.substr(equals + 1);
    }
    if (flag != "--duration" && flag != "--bag" && flag != "--csv" && flag != "--sample-every" &&
        flag != "--marker-rate")
    {
      parsed.error = "unknown option " + quoted(flag);
      return parsed;
    }
    if (!value)
    {
      // "--duration -1" must reach the number check, so only a long option or the end
      // of the line counts as a missing value.
      if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
      {
        parsed.error = flag + ": missing value";
        return parsed;
      }
      value = args[++i];
    }

    if (flag == "--duration")
    {
      if (have_duration)
      {
        parsed.error = "--duration: given twice";
        return parsed;
      }
      have_duration = true;
      const std::optional<double> seconds = parseNumber(*value);
      if (!seconds || !std::isfinite(*seconds))
      {
        parsed.error = "--duration: expected a number of seconds, got " + quoted(*value);
        return parsed;
      }
      if (*seconds < 0.0)
      {
        parsed.error = "--duration: must be >= 0, got " + *value;
        return parsed;
      }
      options.duration = *seconds;
    }
    else if (flag == "--marker-rate")
    {
      if (have_marker_rate)
      {
        parsed.error = "--marker-rate: given twice";
        return parsed;
      }
      have_marker_rate = true;
      const std::optional<double> rate = parseNumber(*value);
      if (!rate || !std::isfinite(*rate) || *rate < 0.0)
      {
        parsed.error = "--marker-rate: expected a rate >= 0 in Hz, got " + quoted(*value);
        return parsed;
      }
      options.marker_rate = *rate;
    }
    else if (flag == "--sample-every")
    {
      if (have_sample_every)
      {
        parsed.error = "--sample-every: given twice";
        return parsed;
      }
      have_sample_every = true;
      const std::optional<std::uint64_t> n = parseCount(*value);
      if (!n || *n == 0)
      {
        parsed.error = "--sample-every: expected an integer >= 1, got " + quoted(*value);
        return parsed;
      }
      options.sample_every = *n;
    }
    else
    {
      std::string& path = flag == "--bag" ? options.bag_path : options.csv_path;
      if (!path.empty())
      {
        parsed.error = flag + ": given twice";
        return parsed;
      }
      if (value->empty())
      {
        parsed.error = flag + ": missing file name";
        return parsed;
      }
      path = *value;
    }
  }

  if (options.scene_path.empty())
  {
    parsed.error = "missing the scene file (SCENE.yaml)";
  }
  else if (!have_duration)
  {
    parsed.error = "missing --duration SECONDS";
  }
  return parsed;
}
}  // namespace ball_collision_sim::tools
