// libFuzzer target: random small scenes stepped with their invariants checked after every
// step (see fuzz_checks.hpp).
#include "fuzz_checks.hpp"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string problem = ball_collision_sim::fuzz::checkStepping(data, size);
  if (!problem.empty())
  {
    std::fprintf(stderr, "fuzz_step: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
