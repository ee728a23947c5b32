// libFuzzer target: the YAML scene reader on arbitrary bytes (see fuzz_checks.hpp).
#include "fuzz_checks.hpp"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string problem = ball_collision_sim::fuzz::checkSceneReader(data, size);
  if (!problem.empty())
  {
    std::fprintf(stderr, "fuzz_scene_reader: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
