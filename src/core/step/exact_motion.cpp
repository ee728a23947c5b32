// Motion on a plane or without a floor (StepState::ExactMotion, and PathMotion where the
// ground pulls balls along it): a free ball's path is exact (a line, or PathMotion's
// parabola under gravity's part along the plane); a ball under its contacts moves on its
// chord in the plane, whose energy is linear along it.
// Reads and writes motions_ and the start velocities of friction phases.
#include "spin_phase.hpp"

namespace ball_collision_sim::core
{
using namespace step;

const StepState::FloorMotion& StepState::FloorMotion::of(const Ground& ground)
{
  static const ExactMotion exact;
  static const PathMotion path;
  static const ChordMotion chord;
  if (ground.bends())
    return chord;
  return ground.pathAcceleration() == Vec3::Zero() ? static_cast<const FloorMotion&>(exact) : path;
}

void StepState::ExactMotion::predict(StepContext& w, std::size_t i, const Vec3& v) const
{
  // (on a plane gravity alone pulls the paths the floor's type makes: a phase that pulls
  // a ball itself makes its path itself, SpinPhase::startMotion())
  w.motions_[i].b = w.predictedEnd(i, w.startPosition(i), v, w.dt_, w.gravity_) - w.startPosition(i);
}

void StepState::ExactMotion::start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const
{
  // (no pull along the floor: the motion is the line at v0, its energy its start's)
  const double rest = 1 - x;
  w.motions_[i].b = rest > 0 ? Vec3((w.predictedEnd(i, position, v0, rest * w.dt_, w.gravity_) - position) / rest) : Vec3(w.dt_ * v0);
}

void StepState::PathMotion::predict(StepContext& w, std::size_t i, const Vec3& v) const
{
  w.motions_[i].b = w.dt_ * v;  // the parabola the ground gives a free ball, exactly
  w.motions_[i].become(MotionType::kPath);
}

void StepState::PathMotion::start(StepContext& w, std::size_t i, double, const Vec3&, const Vec3& v0) const
{
  predict(w, i, v0);
}

FrictionLaw StepState::ExactMotion::lawUnder(const StepContext& w, const Vec3&) const
{
  return *w.friction_;  // the plane's (or no floor's) own
}

bool StepState::ExactMotion::stillMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const
{
  return drivenMotion(w, i, law);  // (its phase's parabola, of no acceleration along the floor)
}

bool StepState::ExactMotion::drivenMotion(StepContext& w, std::size_t i, const FrictionLaw& law) const
{
  // (its path is a parabola on the plane: a part of v into the floor, which a contact's
  // projection out of a leaning wall can leave, is the floor's)
  Vec3& v = w.startVelocity(i);
  v = law.along(v);
  w.motions_[i].b = w.dt_ * v;
  w.motions_[i].become(MotionType::kPhase);
  return false;
}

Vec3 StepState::ExactMotion::phaseVelocity(const StepContext& w, std::size_t i, double x, const Vec3&, const Vec3&) const
{
  return SpinPhase::constantlyAccelerated(w, i, x);
}

double StepState::ExactMotion::speedSquaredAt(const StepContext& w, std::size_t i, double, const Vec3& p) const
{
  return w.pulledSpeedSquared(i, p);
}
}  // namespace ball_collision_sim::core
