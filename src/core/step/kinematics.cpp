// A ball's motion on the floor within the step: where it is, the floor's normal under
// it, its velocity there, the resting speed, starting a new motion at an event, and a
// curved floor's chords cut to the longest it allows (an event at the cut).
// Reads motions_, the floor; writes motions_, chord_ends_, the start position and
// velocity (step_starts_ keeping where the step started a ball), and, at a cut, the queue.
#include "spin_model.hpp"
#include "spin_phase.hpp"
#include "flight.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
using namespace step;

Vec3 StepContext::rateAt(std::size_t i, double x) const
{
  const Motion& m = motions_[i];
  return motions_[i].accelerates() ? Vec3(m.b + (2 * (x - m.x0)) * pathTerm(i)) : m.b;
}

Vec3 StepContext::parabolaOf(std::size_t i) const
{
  return motions_[i].accelerates() ? pathTerm(i) : Vec3::Zero();
}

Vec3 StepContext::floorNormalAt(std::size_t i, const Vec3& position) const
{
  return ground_.normalAt(position, guessOf(i));
}

Vec3 StepContext::motionVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const
{
  switch (motions_[i].type)
  {
    case MotionType::kFlight:
      return flightVelocity(*this, i, x);  // (off the floor)
    case MotionType::kGrouped:
      return ground_.along(groupVelocityAt(i, x), normal);  // (its group's time step)
    case MotionType::kCapped:
    case MotionType::kAsleep:
    case MotionType::kPocketed:
      return Vec3::Zero();
    case MotionType::kPhase:
    case MotionType::kPhaseChord:
      return spin_motions_[i].phase->velocity(*this, i, x, position, normal);  // (its friction phase's)
    default:  // (a free line or path on the floor: the ground's)
      return ground_.velocityAt(startVelocity(i), (x - motions_[i].x0) * dt_, startPosition(i), position, normal);
  }
}

double StepContext::stillSpeed(const Vec3& floor_normal) const
{
  return settings_.resting_steps * dt_ * ground_.gravityAlong(floor_normal) + settings_.resting_speed_floor;
}

Vec3 StepContext::wallPush(const Vec3& n, const Vec3& floor_normal) const
{
  const Vec3 along = ground_.along(n, floor_normal);
  return along.squaredNorm() < settings_.wall_along_floor_squared ? n : Vec3(along.normalized());
}

double StepContext::restingSpeed(const Vec3& floor_normal, double restitution, const Vec3& position, double radius) const
{
  // Closing speeds of round-off: the floor's, and what a ball pulled along the floor at
  // a reaches falling through a gap of the positions' round-off, sqrt(2 a gap) (two
  // balls at rest in a pile have such gaps; a parabola closes them at that speed).
  const double a = ground_.gravityAlong(floor_normal);
  const double roundoff = settings_.resting_speed_floor + std::sqrt(2 * a * roundoffAt(position, radius, settings_));
  // After an impact at closing speed v, gravity along the floor brings the ball back for
  // bounces e times as fast each, which last 2 e v / (a (1 - e)) in all. Where that is
  // within resting_steps steps, their sum, rest against what was hit, is taken at once:
  // a resting contact. At e = 1 they never end (nor lose energy): no resting contact
  // but at round-off speeds.
  if (!(restitution < 1))
    return roundoff;
  if (!(restitution > 0))
    return std::numeric_limits<double>::infinity();  // no bounce at all
  return settings_.resting_steps * dt_ * a * (1 - restitution) / (2 * restitution) + roundoff;
}

double StepContext::pairRestingSpeed(const Vec3& na, const Vec3& pa, double ra, const Vec3& nb, const Vec3& pb,
                               double rb) const
{
  return std::max(restingSpeed(na, scene_.restitution, pa, ra), restingSpeed(nb, scene_.restitution, pb, rb));
}

void StepContext::beginMotion(std::size_t i, double x, const Vec3& position, const Vec3& v0)
{
  Motion& m = motions_[i];
  m.become(MotionType::kLine);
  m.x0 = x;
  if (step_start_of_[i] == kNoStepStart)
  {
    // (its first new motion in the step: where the step started it is kept for the commit)
    step_start_of_[i] = static_cast<std::uint32_t>(step_starts_.size());
    step_starts_.push_back(balls_[i].position);
  }
  startPosition(i) = position;
  startVelocity(i) = v0;
  if (!chord_ends_.empty())
  {
    chord_ends_[i] = 1.0;
    flow_ends_[i].x = -1.0;
  }
}

void StepContext::startMotion(std::size_t i, double x, const Vec3& position, const Vec3& velocity, bool impact)
{
  Motion& m = motions_[i];
  beginMotion(i, x, position, motions_[i].frozen() ? Vec3::Zero() : velocity);
  if (motions_[i].frozen())
  {
    m.b = Vec3::Zero();
    spin_->hold(*this, i);
    return;
  }
  if (!balls_[i].flying() && leavesFloor(*this, i, position, startVelocity(i)) && !grouped(i))
  {
    // The floor cannot hold it on its bend: it flies from the floor (a chord's point can
    // lie off it), its speed what its energy gives there.
    liftOff(*this, i, x);
    const Vec3 q = onFloor(i, position);
    const double speed2 = std::max(0.0, startVelocity(i).squaredNorm() + 2 * gravity_.dot(q - position));
    startVelocity(i) = ground_.withSpeedSquared(startVelocity(i), speed2);
    startPosition(i) = q;
  }
  if (balls_[i].flying())
  {
    startFlight(*this, i);
    return;
  }
  spin_->startOnFloor(*this, i, x, position, impact);
}

void StepContext::cutChord(std::size_t i, const Vec3& position, const Vec3& v0, const Vec2* start_foot)
{
  if (chord_ends_.empty())
    return;  // (paths that do not bend are not chords)
  Motion& m = motions_[i];
  // (the path's length, or the chord's where that is longer: the chord's end is the
  // path's put back on the floor, which can lie far from it)
  const double rest = 1 - m.x0;
  const double length = rest * std::max(m.b.norm(), dt_ * v0.norm());
  const double longest = ground_.longestChord(balls_[i].radius);
  if (!(length > longest))
    return;
  // (the path beyond the cut is not the chord's: the cut's event makes the chord after it)
  const double span = rest * (longest / length);
  chord_ends_[i] = m.x0 + span;
  if (start_foot)
    guessOf(i) = *start_foot;  // (the uncut chord's end moved the kept foot point)
  m.b = chordOver(i, position, v0, m.x0, chord_ends_[i], start_foot != nullptr);
}

Vec3 StepContext::chordOver(std::size_t i, const Vec3& p, const Vec3& v, double x0, double x1, bool on_kept_foot)
{
  FloorFlow::Law law;
  FlowEnd& end = flow_ends_[i];
  end.x = -1.0;
  end.ends = kPhaseRuns;
  const double span = x1 - x0;
  if (!spin_->flowLaw(*this, i, law) || !(span > 0))
    return span > 0 ? Vec3((predictedEnd(i, p, v, span * dt_) - p) / span) : Vec3(dt_ * v);
  // from the foot point under p (a start part way along a chord lies off the floor by
  // its sag; at the step's start the ball is over its kept foot point), at v (whose
  // part along the floor there is what counts), with its spin
  const double r = balls_[i].radius;
  Vec2& foot = guessOf(i);
  if (!on_kept_foot)
    ground_.landKeepingFoot(p, r, foot);
  FloorFlow::State state{foot, v};
  if (!spin_motions_.empty())
  {
    // (a free ball's spin stays as it is; a rolling or sliding one's in its parts about
    // the normal and along the floor)
    const SpinMotion& sm = spin_motions_[i];
    state.spin = sm.w0;
    if (law.kind != FloorFlow::Kind::kFree)
    {
      state.spin_n = sm.w0.dot(sm.normal);
      state.spin -= state.spin_n * sm.normal;
      // (a spin about the normal that the phase's start took for round-off is none:
      // FrictionLaw::start() left it at that)
      if (!(std::abs(state.spin_n) * r > settings_.resting_speed_floor))
        state.spin_n = 0.0;
    }
  }
  const Floor& floor = *ground_.floor();
  const double k = floor.maxCurvature();
  const double bend = r * k < 1 ? k / (1 - r * k) : k;  // (the centres' surface bends more in a hollow)
  const FloorFlow flow(floor, gravity_, r);
  const int substeps = FloorFlow::substepsFor(span * dt_, v.norm(), bend, gravity_.norm(), settings_.flow_turn);
  const FloorFlow::End reached =
      flow.advance(state, span * dt_, substeps, law, settings_.slip_turn, settings_.flow_step_cap);
  foot = state.foot;
  end.velocity = state.velocity;
  end.normal = reached.normal;
  end.spin = law.kind == FloorFlow::Kind::kSliding ? Vec3(state.spin + state.spin_n * reached.normal) : state.spin;
  end.spin_n = state.spin_n;
  // (where its phase ends on the way, its chord ends there: the phase's end, an event;
  // where it leaves the floor, its take-off, an event: searchTakeOff())
  end.x = reached.ends == kPhaseRuns ? x1 : x0 + reached.time / dt_;
  end.ends = reached.ends;
  if (law.kind != FloorFlow::Kind::kFree)
  {
    SpinMotion& sm = spin_motions_[i];
    const bool phase_ends = reached.ends != kPhaseRuns && reached.ends != kTakesOff;
    sm.x_end = phase_ends ? end.x : 2.0;
    sm.ends = phase_ends ? reached.ends : static_cast<std::uint8_t>(kPhaseRuns);
  }
  return end.x > x0 ? Vec3((reached.centre - p) / (end.x - x0)) : Vec3(dt_ * v);
}

bool StepContext::flowVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal, Vec3& v) const
{
  if (!flowEndsAt(i, x))
    return false;
  const FlowEnd& end = flow_ends_[i];
  // (without drag its speed is its energy's, as a chord's is: no energy made or lost to
  // the integration's round-off)
  FloorFlow::Law law;
  spin_->flowLaw(*this, i, law);  // (the law the flow followed: the motion's, unchanged since)
  v = law.keepsEnergy() ? ground_.withSpeedSquared(ground_.along(end.velocity, normal), speedSquaredAt(i, x, position))
                       : ground_.along(end.velocity, normal);
  return true;
}

void StepContext::queueCut(std::size_t i)
{
  const double x = chord_ends_[i];
  if (!(x < 1))
    return;
  queueMotionEnd(i, x, MotionEnd::kCut);
}

void StepContext::queueMotionEnd(std::size_t i, double x, MotionEnd end)
{
  const auto k = static_cast<std::uint32_t>(i);
  const std::uint16_t epoch = motions_[i].epoch;
  pushEvent(Event{x, k, k, epoch, epoch, EventKind::kMotionEnd, WallFeature::kFace, end, Vec3::Zero()});
}

void StepContext::queueMotionEnds(std::size_t i)
{
  switch (motions_[i].type)
  {
    case MotionType::kFlight:
      queueLanding(*this, i);
      return;
    case MotionType::kCapped:
    case MotionType::kAsleep:
    case MotionType::kPocketed:
      return;
    default:  // on the floor: a line, a path, a phase, a group's chord
      spin_->queueEnd(*this, i);
      if (!chord_ends_.empty())
      {
        queueCut(i);
        queueTakeOff(*this, i);
      }
  }
}

void StepContext::resolveMotionEnd(const Event& event)
{
  // The ball goes on from where it is, on the floor, with the velocity and spin there;
  // at its friction phase's end (not a chord's cut) the phase's end is made exact first.
  const std::size_t i = event.i;
  const Vec3 p = positionAt(i, event.x);
  const Vec3 normal = floorNormalAt(i, p);
  Vec3 v = onFloorVelocity(i, event.x, p, normal);
  spin_->endMotion(*this, event, normal, v);
  if (motions_[i].followsGroup())
  {
    // (a member of a group: the group goes on from here, solved again, the spin it has
    // now kept as it is until then)
    spin_->hold(*this, i);
    solveGroup(i, event.x);
    return;
  }
  startMotion(i, event.x, p, v, false);
  countEvent(i);
  detect(i);
}

Vec3 StepContext::onFloor(std::size_t i, const Vec3& q) const
{
  return ground_.land(q, balls_[i].radius, guessOf(i));
}
}  // namespace ball_collision_sim::core
