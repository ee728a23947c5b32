// Motion on a curved floor (StepState::ChordMotion): every motion is a chord between points
// of the floor, cut where it is longer than the floor allows, put back on the floor after
// every correction and kept within the ball's energy; friction laws are taken under the
// normal where the ball is, and a moving phase is a chord under its pull.
// Reads and writes motions_, spin_motions_ and the start velocities; reads the start positions.
#include "floor_motion.hpp"

#include "../bracketed_root.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

void StepState::ChordMotion::predict(StepContext& w, std::size_t i, const Vec3& v) const
{
  // a chord across the path, no longer than the floor allows, kept within the energy
  Motion& m = w.motions_[i];
  const Vec3& p0 = w.startPosition(i);
  const Vec2 foot = w.guessOf(i);  // (the kept foot point, under p0)
  m.b = w.chordOver(i, p0, v, 0.0, 1.0, true);
  w.cutChord(i, p0, v, &foot);
  keepEnergy(w, i);
}

void StepState::ChordMotion::start(StepContext& w, std::size_t i, double x, const Vec3& position, const Vec3& v0) const
{
  Motion& m = w.motions_[i];
  m.b = w.chordOver(i, position, v0, x, 1.0, false);
  w.cutChord(i, position, v0, nullptr);
  keepEnergy(w, i);
}

void StepState::ChordMotion::keepEnergy(StepContext& w, std::size_t i)
{
  const double rest = w.chordEnd(i) - w.motions_[i].x0;
  // (a chord that ends where the ball's laws take it keeps its energy as they do)
  if (w.motions_[i].frozen() || !(rest > 0) || !(w.flow_ends_[i].x < 0))
    return;
  const StepContext::EnergyCheck energy{&w, i, rest};
  // (the chord's own end is what counts: one cut short of where its energy runs out
  // ends off the floor)
  const double full = energy.chordSpeedSquared(w.motions_[i].b);
  if (full >= 0)
    return;
  shorten(w, i, energy, energy.speedSquared(0.0), full);
}

void StepState::ChordMotion::shorten(StepContext& w, std::size_t i, const StepContext::EnergyCheck& energy, double start, double full)
{
  // The chord ends higher than the ball's energy reaches (a turning point, or a ball in
  // a pile whose constraints turned its motion uphill): it stops where the energy runs
  // out instead, so that no energy is made.
  Motion& m = w.motions_[i];
  const double rest = energy.rest;
  w.flow_ends_[i].x = -1.0;  // (the chord is no longer where the ball's laws took it)
  double lo = 0.0;
  if (start > 0)
    lo = energyRunsOut(w, energy, start, full);
  // (round-off may leave the end a hair too high; the speed is clamped to zero then)
  m.b *= lo;
  if (lo > 0)
  {
    const Vec3& p0 = w.startPosition(i);
    const Vec3 b = (w.onFloor(i, p0 + rest * m.b) - p0) / rest;
    if (energy.chordSpeedSquared(b) >= 0)
      m.b = b;
    else
      w.stop(i);
    return;
  }
  slideDownhill(w, energy, start);
}

double StepState::ChordMotion::energyRunsOut(const StepContext& w, const StepContext::EnergyCheck& energy, double start, double full)
{
  // the root of the speed on [0, 1], where it is still >= 0
  return bracketedRoot([&](double s) { return energy.speedSquared(s); }, [](double v) { return v >= 0 ? 1 : -1; },
                       0.0, 1.0, start, full, w.settings_.energy_root_iterations, w.settings_.energy_root_width);
}

void StepState::ChordMotion::slideDownhill(StepContext& w, const StepContext::EnergyCheck& energy, double start)
{
  const std::size_t i = energy.i;
  const double rest = energy.rest;
  Motion& m = w.motions_[i];
  // A motion that starts at an impact inside the step starts on the chord, below or
  // above the floor; where the floor above it is higher than the energy reaches, the
  // ball slides downhill from there instead, as far as it takes to be low enough.
  // Where it finds no way, its energy has run out where it is: it stops (StepContext::stop()).
  const Vec3& p0 = w.startPosition(i);
  const Vec3 foot = w.onFloor(i, p0);
  const Vec3 downhill = tangentPart(w.gravity_, w.floorNormalAt(i, foot));
  const double slope = downhill.norm();
  if (!(slope > 0))
    return w.stop(i);
  // (a short way only: the chord's sag is small next to the ball; else it stays put)
  // The reaches tried are first * 2^k below half the radius. Where the energy left grows
  // with the reach (the lower the end, the more), halving the range of k after the
  // longest has shown that one does finds the shortest that does; elsewhere it finds one
  // that does, or, where the longest does not, stops the ball (which makes no energy).
  const StepSettings& settings = w.settings_;
  const double first = std::max(-start / slope, settings.slide_first_reach * w.balls_[i].radius);
  int count = 0;
  const double longest = settings.slide_longest_reach * w.balls_[i].radius;
  while (count < settings.slide_doublings && std::ldexp(first, count) < longest)
    ++count;
  const auto motionTo = [&](int k) -> Vec3 {
    return (w.onFloor(i, foot + (std::ldexp(first, k) / slope) * downhill) - p0) / rest;
  };
  const auto keeps = [&](const Vec3& b) { return energy.speedSquaredWith(b) >= 0 && energy.chordSpeedSquared(b) >= 0; };
  if (count == 0)
    return w.stop(i);
  Vec3 found = motionTo(count - 1);
  if (!keeps(found))
    return w.stop(i);
  int fails = -1, works = count - 1;  // the largest k known to fail, the smallest known to work
  while (works - fails > 1)
  {
    const int k = fails + (works - fails) / 2;
    const Vec3 b = motionTo(k);
    if (keeps(b))
    {
      works = k;
      found = b;
    }
    else
      fails = k;
  }
  m.b = found;
}

FrictionLaw StepState::ChordMotion::lawUnder(const StepContext& w, const Vec3& n) const
{
  return FrictionLaw(*w.scene_.friction, n, w.gravity_, tangentPart(w.gravity_, n), w.settings_.slip_tolerance,
                     w.settings_.resting_speed_floor);
}

void StepState::ChordMotion::rollOn(StepContext& w, std::size_t i, const FrictionLaw& law) const
{
  // (the normal turned under it since its phase began: the discrete path's turn, not a
  // slip; its spin about the normal is carried over, so |w| and the energy stay)
  SpinMotion& sm = w.spin_motions_[i];
  sm.w0 = law.rollingSpin(w.balls_[i].radius, w.startVelocity(i), sm.w0, sm.w0.dot(sm.normal));
}

bool StepState::ChordMotion::drivenMotion(StepContext&, std::size_t, const FrictionLaw&) const
{
  return true;  // a chord under its pull
}

bool StepState::ChordMotion::stillMotion(StepContext& w, std::size_t i, const FrictionLaw&) const
{
  // It stays where it is, with no speed (a chord's point below the floor, where a
  // phase ended mid-step, is not lifted onto it for nothing).
  w.startVelocity(i) = w.motions_[i].b = Vec3::Zero();
  w.motions_[i].become(MotionType::kPhaseChord);
  return false;
}

Vec3 StepState::ChordMotion::phaseVelocity(const StepContext& w, std::size_t i, double x, const Vec3& position,
                                       const Vec3& normal) const
{
  Vec3 v;
  if (w.flowVelocity(i, x, position, normal, v))
    return v;  // (where its chord ends, as its laws take it)
  const SpinMotion& sm = w.spin_motions_[i];
  const double t = (x - w.motions_[i].x0) * w.dt_;
  return w.ground_.withSpeedSquared(w.ground_.along(w.startVelocity(i) + t * sm.pull, normal),
                                    w.speedSquaredAt(i, x, position));
}

double StepState::ChordMotion::speedSquaredAt(const StepContext& w, std::size_t i, double x, const Vec3& p) const
{
  const Motion& m = w.motions_[i];
  const Vec3& v0 = w.startVelocity(i);
  const Vec3 moved = p - w.startPosition(i);
  const SpinMotion& sm = w.spin_motions_[i];
  const double k = w.spins_[i].inertia;
  if (sm.kind == MotionKind::kRolling)
  {
    // d(v^2 / 2) = <g, dp> / (1 + k) - mu_r g_n ds: the chord's length for the path's (no
    // longer than it), so rolling resistance never gives energy, also where the ball
    // turns within the chord
    return v0.squaredNorm() + 2 * (w.gravity_.dot(moved) / (1 + k) - sm.roll_resistance * moved.norm());
  }
  // sliding: what gravity's work along the chord leaves after the spin's change and the
  // slip's loss, mu_s g_n (|u0| t - rate t^2 / 2)
  const double t = std::min((x - m.x0) * w.dt_, std::max(sm.x_end - m.x0, 0.0) * w.dt_);
  const Vec3 spin = sm.w0 + t * sm.alpha;
  const double spin_change = k * w.balls_[i].radius * w.balls_[i].radius * (spin.squaredNorm() - sm.w0.squaredNorm());
  const double loss = sm.slip_force * (sm.slip0 * t - 0.5 * sm.slip_rate * t * t);
  return v0.squaredNorm() + 2 * w.gravity_.dot(moved) - spin_change - 2 * loss;
}

Vec3 StepState::ChordMotion::spinThere(const StepContext& w, std::size_t i, double x, const Vec3& normal, const Vec3& v,
                                       const Vec3& spin, bool rolling) const
{
  // Where its chord ends as its laws took it: a sliding ball's spin is the flow's, a
  // rolling one's rolling's for the velocity there with the flow's spin about the normal
  // (the law's (1 + k) counted its energy).
  if (w.flowEndsAt(i, x))
    return rolling ? Vec3(normal.cross(v) / w.balls_[i].radius + w.flow_ends_[i].spin_n * normal)
                   : w.flow_ends_[i].spin;
  if (!rolling)
    return spin;
  const double wn = spin.dot(w.spin_motions_[i].normal);
  // (elsewhere a rolling ball rolls with the velocity its energy gives it there, under
  // the normal there)
  return lawUnder(w, normal).rollingSpin(w.balls_[i].radius, v, spin, wn);
}
}  // namespace ball_collision_sim::core
