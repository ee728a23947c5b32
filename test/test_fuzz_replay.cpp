// Every input kept under test/fuzz/ (seeds, and what the fuzz targets once found) through
// the fuzz targets' own checks, built with the package's compiler: a finding fixed stays
// fixed without clang or libFuzzer.
#include "fuzz_checks.hpp"

#include <gtest/gtest.h>

#include <string>

namespace
{
using ball_collision_sim::fuzz::filesIn;
using ball_collision_sim::fuzz::readBytes;

const std::string kFuzzDir = BCS_FUZZ_DIR;

TEST(FuzzReplay, SceneReaderInputs)
{
  const auto files = filesIn(kFuzzDir + "/scene_reader");
  ASSERT_GE(files.size(), 5u);
  for (const std::string& path : files)
  {
    const auto bytes = readBytes(path);
    EXPECT_EQ(ball_collision_sim::fuzz::checkSceneReader(bytes.data(), bytes.size()), "") << path;
  }
}

TEST(FuzzReplay, SteppingInputs)
{
  const auto files = filesIn(kFuzzDir + "/step");
  ASSERT_GE(files.size(), 5u);
  int stepped = 0;
  for (const std::string& path : files)
  {
    const auto bytes = readBytes(path);
    EXPECT_EQ(ball_collision_sim::fuzz::checkStepping(bytes.data(), bytes.size()), "") << path;
    stepped += ball_collision_sim::core::validate(ball_collision_sim::fuzz::decodeStepCase(bytes.data(), bytes.size()).scene).empty();
  }
  // the inputs kept are worth keeping: most decode to scenes that run
  EXPECT_GE(2 * stepped, static_cast<int>(files.size()));
}

// Short or empty input reads as zeros: still a scene that runs (an open tilted floor).
TEST(FuzzReplay, DecoderMakesAValidSceneFromZeros)
{
  const std::vector<std::uint8_t> zeros(200, 0);
  const auto c = ball_collision_sim::fuzz::decodeStepCase(zeros.data(), zeros.size());
  EXPECT_EQ(c.box_walls, 0u);  // the first flag bytes are zero: open floor
  EXPECT_TRUE(ball_collision_sim::core::validate(c.scene).empty());
  EXPECT_EQ(ball_collision_sim::fuzz::checkStepping(zeros.data(), zeros.size()), "");
}
}  // namespace
