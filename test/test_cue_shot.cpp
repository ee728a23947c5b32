// The cue in rviz as arithmetic (src/ros/cue_shot.cpp, no ROS): a cue's pose gives the
// strike's impulse and offset, checked against numbers worked by hand.
#include "ball_collision_sim/ros/cue_shot.hpp"

#include <gtest/gtest.h>

#include <cmath>

using ball_collision_sim::bridge::CuePose;
using ball_collision_sim::bridge::CueShot;
using ball_collision_sim::bridge::cueShot;
using ball_collision_sim::bridge::kCueMaxSpeed;
using ball_collision_sim::bridge::kCueSpeedPerPull;
using ball_collision_sim::bridge::seatedCue;
using ball_collision_sim::core::Vec3;

namespace
{
// A pool ball [m, kg].
constexpr double kR = 0.028575;
constexpr double kM = 0.170097;
const Vec3 kCentre(0.5, -0.25, kR);

void expectNear(const Vec3& got, const Vec3& want, double tolerance)
{
  EXPECT_NEAR((got - want).norm(), 0.0, tolerance) << "got " << got.transpose() << ", want " << want.transpose();
}

Eigen::Quaterniond about(const Vec3& axis, double angle)
{
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}
}  // namespace

TEST(CueShot, PulledBackAlongXStrikesAlongXWithTheSpeedItsPullGives)
{
  // along +x, 0.2 m behind the centre, its line 1 cm to the side (+y) and 5 mm above
  const CuePose cue{kCentre + Vec3(-0.2, 0.01, 0.005), Eigen::Quaterniond::Identity()};
  const CueShot shot = cueShot(cue, kCentre, kR, kM);
  EXPECT_EQ(shot.error, "");
  EXPECT_NEAR(shot.pull, 0.2, 1e-15);
  expectNear(shot.direction, Vec3::UnitX(), 0.0);
  expectNear(shot.offset, Vec3(0, 0.01, 0.005), 1e-15);
  // 10 m/s per metre: 2 m/s, J = 0.340194 N s
  expectNear(shot.impulse, Vec3(2.0 * kM, 0, 0), 1e-15);
  EXPECT_NEAR(shot.impulse.x(), 0.340194, 1e-15);
}

TEST(CueShot, TheDirectionIsTheCuesXAxisTurnedByItsOrientation)
{
  // turned 90 degrees about z: along +y; pulled back 0.1 m along -y, no offset
  const CuePose cue{kCentre + Vec3(0, -0.1, 0), about(Vec3::UnitZ(), M_PI / 2)};
  const CueShot shot = cueShot(cue, kCentre, kR, kM);
  EXPECT_EQ(shot.error, "");
  expectNear(shot.direction, Vec3::UnitY(), 1e-15);
  EXPECT_NEAR(shot.pull, 0.1, 1e-15);
  expectNear(shot.offset, Vec3::Zero(), 1e-15);
  expectNear(shot.impulse, Vec3(0, 1.0 * kM, 0), 1e-15);

  // tilted 30 degrees about its y axis: the butt up, the cue pointing down into the ball
  // (a jump shot): d = (cos 30, 0, -sin 30)
  const Vec3 d(std::cos(M_PI / 6), 0, -std::sin(M_PI / 6));
  const CuePose tilted{kCentre - 0.3 * d, about(Vec3::UnitY(), M_PI / 6)};
  const CueShot jump = cueShot(tilted, kCentre, kR, kM);
  EXPECT_EQ(jump.error, "");
  expectNear(jump.direction, d, 1e-15);
  EXPECT_NEAR(jump.pull, 0.3, 1e-15);
  expectNear(jump.impulse, 3.0 * kM * d, 1e-15);
  expectNear(jump.offset, Vec3::Zero(), 1e-15);
}

TEST(CueShot, TheOffsetIsSquareToTheCueWhereverItsOriginSitsOnItsLine)
{
  // The origin anywhere along the same line gives the same offset: the line's point
  // nearest the centre. Line: through c + (0, 0.02, -0.01), along (1, 1, 0) / sqrt 2.
  const Eigen::Quaterniond q = about(Vec3::UnitZ(), M_PI / 4);
  const Vec3 d = Vec3(1, 1, 0).normalized();
  const Vec3 o = Vec3(0, 0.02, -0.01) - Vec3(0, 0.02, -0.01).dot(d) * d;  // (-0.01, 0.01, -0.01)
  expectNear(o, Vec3(-0.01, 0.01, -0.01), 1e-15);
  for (const double s : {0.0, 0.05, 0.5, -0.05, 0.999e-3, 1e-3})
  {
    const CueShot shot = cueShot(CuePose{kCentre + o - s * d, q}, kCentre, kR, kM);
    EXPECT_EQ(shot.error, "");
    EXPECT_NEAR(shot.pull, s, 1e-15);
    expectNear(shot.offset, o, 1e-15);
    EXPECT_NEAR(shot.offset.dot(shot.direction), 0.0, 1e-15);
    // pushed forward, or pulled back less than 1 mm: no strike
    if (s < 1e-3)
      expectNear(shot.impulse, Vec3::Zero(), 0.0);
    else
      expectNear(shot.impulse, kM * std::min(kCueSpeedPerPull * s, kCueMaxSpeed) * d, 1e-15);
  }
  // The offset's torque is that of J where the line meets the surface, c + o - t d.
  const CueShot shot = cueShot(CuePose{kCentre + o - 0.2 * d, q}, kCentre, kR, kM);
  const Vec3 contact = o - std::sqrt(kR * kR - o.squaredNorm()) * d;
  expectNear(contact.cross(shot.impulse), o.cross(shot.impulse), 1e-16);
}

TEST(CueShot, TheSpeedIsCappedAtAMetreOfPull)
{
  for (const double s : {1.0, 1.5, 40.0})
  {
    const CueShot shot = cueShot(CuePose{kCentre - Vec3(s, 0, 0), Eigen::Quaterniond::Identity()}, kCentre, kR, kM);
    EXPECT_EQ(shot.error, "");
    expectNear(shot.impulse, Vec3(kCueMaxSpeed * kM, 0, 0), 1e-14);
  }
}

TEST(CueShot, AnUnnormalisedOrientationCountsAsItsRotation)
{
  const Eigen::Quaterniond q = about(Vec3(0.3, -0.2, 1.0), 0.7);
  const Eigen::Quaterniond doubled(2 * q.w(), 2 * q.x(), 2 * q.y(), 2 * q.z());
  const CuePose a{kCentre - 0.1 * (q * Vec3::UnitX()) + Vec3(0, 0, 0.004), q};
  const CuePose b{a.position, doubled};
  const CueShot one = cueShot(a, kCentre, kR, kM);
  const CueShot two = cueShot(b, kCentre, kR, kM);
  EXPECT_EQ(two.error, "");
  expectNear(two.impulse, one.impulse, 1e-15);
  expectNear(two.offset, one.offset, 1e-15);
}

TEST(CueShot, ALineThatMissesTheBallOrABrokenPoseIsRefusedWithTheReason)
{
  const CueShot miss = cueShot(CuePose{kCentre + Vec3(-0.2, 0.03, 0), Eigen::Quaterniond::Identity()}, kCentre, kR, kM);
  EXPECT_EQ(miss.error, "offset: the cue's line passes 0.03 m from the ball's centre, outside its radius 0.028575 m");
  expectNear(miss.impulse, Vec3::Zero(), 0.0);
  // a line that grazes the surface still strikes
  const CueShot graze = cueShot(CuePose{kCentre + Vec3(-0.2, 0, kR), Eigen::Quaterniond::Identity()}, kCentre, kR, kM);
  EXPECT_EQ(graze.error, "");
  EXPECT_GT(graze.impulse.norm(), 0.0);

  const CueShot zero = cueShot(CuePose{kCentre, Eigen::Quaterniond(0, 0, 0, 0)}, kCentre, kR, kM);
  EXPECT_EQ(zero.error, "orientation: the cue's pose is not a finite rotation and position");
  const CueShot nan = cueShot(CuePose{Vec3(std::nan(""), 0, 0), Eigen::Quaterniond::Identity()}, kCentre, kR, kM);
  EXPECT_EQ(nan.error, "orientation: the cue's pose is not a finite rotation and position");
}

TEST(CueShot, ASeatedCueHasNoPullItsOffsetAndALevelYAxis)
{
  const Vec3 d = Vec3(2, -1, 0).normalized();
  const Vec3 o = Vec3(0, 0, 0.01) + 0.005 * Vec3(1, 2, 0).normalized();  // square to d
  const CuePose seated = seatedCue(kCentre, d, o, Vec3::UnitZ());
  expectNear(seated.position, kCentre + o, 1e-15);
  EXPECT_NEAR(seated.orientation.norm(), 1.0, 1e-15);
  expectNear(seated.orientation * Vec3::UnitX(), d, 1e-15);
  EXPECT_NEAR((seated.orientation * Vec3::UnitY()).z(), 0.0, 1e-15);  // level: aim turns about z
  EXPECT_GT((seated.orientation * Vec3::UnitZ()).z(), 0.0);           // z up
  const CueShot shot = cueShot(seated, kCentre, kR, kM);
  EXPECT_NEAR(shot.pull, 0.0, 1e-15);
  expectNear(shot.offset, o, 1e-15);
  expectNear(shot.impulse, Vec3::Zero(), 0.0);

  // straight down the normal: some y square to it, still a rotation
  const CuePose down = seatedCue(kCentre, -Vec3::UnitZ(), Vec3::Zero(), Vec3::UnitZ());
  expectNear(down.orientation * Vec3::UnitX(), -Vec3::UnitZ(), 1e-15);
  EXPECT_NEAR(down.orientation.norm(), 1.0, 1e-15);
}
