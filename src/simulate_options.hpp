#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ball_collision_sim::tools
{
/// The command line of `simulate` (design.md section 6).
struct SimulateOptions
{
  std::string scene_path;
  double duration = 0.0;           ///< simulated time to run [s], finite and >= 0
  std::string bag_path;            ///< empty: no rosbag
  std::string csv_path;            ///< empty: no CSV
  std::uint64_t sample_every = 1;  ///< a CSV sample after every N-th step, N >= 1
  double marker_rate = 30.0;       ///< markers per simulated second in the bag [Hz]; 0 = the first only
  unsigned threads = 1;            ///< threads the step runs on (StepSettings::threads); 0 = every core
  bool help = false;               ///< -h/--help: print the usage and nothing else
};

/// The options, or why the command line is wrong.
struct ParsedOptions
{
  SimulateOptions options;
  std::string error;  ///< one line, e.g. "--duration: expected a number of seconds, got 'abc'"
  bool ok() const { return error.empty(); }
};

/// Parses the arguments after the program name. Pure: no I/O, no exit, so it is testable.
/// Both "--flag value" and "--flag=value" are accepted; "--" ends the options. -h/--help
/// anywhere wins over any other problem.
ParsedOptions parseSimulateOptions(const std::vector<std::string>& args);

/// The usage text printed by --help (several lines, ends with a newline).
std::string simulateUsage();
}  // namespace ball_collision_sim::tools
