#pragma once
// What the tests of the command-line tools share: running a program in a temporary
// folder, reading what it wrote, and parsing simulate's summary line.

#include <gtest/gtest.h>

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace ball_collision_sim::test::cli
{
namespace fs = std::filesystem;

struct RunResult
{
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shellQuote(const std::string& text)
{
  std::string quoted = "'";
  for (const char c : text)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

inline std::string readFile(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> lines(const std::string& text)
{
  std::vector<std::string> result;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
  {
    result.push_back(line);
  }
  return result;
}

inline bool startsWith(const std::string& text, const std::string& prefix)
{
  return text.rfind(prefix, 0) == 0;
}

inline bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/// Runs the test in a fresh temporary folder, removed afterwards.
class SimulateCli : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("bcs_simulate_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override
  {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  /// The simulate tool with these arguments.
  RunResult run(const std::vector<std::string>& args) { return runProgram(BCS_SIMULATE_EXE, args); }

  /// A program with these arguments, its stdout and stderr caught, no stdin.
  RunResult runProgram(const std::string& program, const std::vector<std::string>& args)
  {
    const fs::path out = dir_ / "stdout.txt";
    const fs::path err = dir_ / "stderr.txt";
    std::string command = shellQuote(program);
    for (const std::string& arg : args)
    {
      command += " " + shellQuote(arg);
    }
    command += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
    const int status = std::system(command.c_str());
    RunResult result;
    result.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
    result.out = readFile(out);
    result.err = readFile(err);
    return result;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

struct Summary
{
  std::uint64_t steps = 0;
  std::uint64_t events = 0;
  std::uint64_t floor_impacts = 0;
  double wall_s = 0.0;
  double energy_start = 0.0;
  double energy_end = 0.0;
  int balls_lost = -1;
  std::uint64_t balls_pocketed = 0;
};

/// The summary line: exactly these keys, in this order, every value parsing whole.
inline Summary parseSummary(const std::string& line)
{
  static const std::regex pattern(
      R"(^summary: steps=([0-9]+) events=([0-9]+) floor_impacts=([0-9]+) wall_s=(\S+) energy_start=(\S+) )"
      R"(energy_end=(\S+) balls_lost=([0-9]+) balls_pocketed=([0-9]+)$)");
  std::smatch match;
  Summary summary;
  EXPECT_TRUE(std::regex_match(line, match, pattern)) << line;
  if (match.empty())
  {
    return summary;
  }
  auto number = [&](int i) {
    const std::string text = match[i].str();
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    EXPECT_EQ(used, text.size()) << text;
    return value;
  };
  summary.steps = std::stoull(match[1].str());
  summary.events = std::stoull(match[2].str());
  summary.floor_impacts = std::stoull(match[3].str());
  summary.wall_s = number(4);
  summary.energy_start = number(5);
  summary.energy_end = number(6);
  summary.balls_lost = std::stoi(match[7].str());
  summary.balls_pocketed = std::stoull(match[8].str());
  return summary;
}

/// The value of `key=` in a line of key=value fields.
inline double field(const std::string& line, const std::string& key)
{
  const std::size_t at = line.find(" " + key + "=");
  EXPECT_NE(at, std::string::npos) << key << " in " << line;
  return at == std::string::npos ? std::nan("") : std::stod(line.substr(at + key.size() + 2));
}
}  // namespace ball_collision_sim::test::cli
