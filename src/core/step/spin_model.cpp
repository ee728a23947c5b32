// The two spin types (spin_model.hpp): RollingSpin without friction, FrictionSpin with it.
// FrictionSpin runs the friction laws through the StepContext's friction helpers
// (friction.cpp) and the phases (SpinPhase).
#include "spin_model.hpp"

#include "flight.hpp"
#include "rolling.hpp"
#include "spin_phase.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/scene.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

namespace
{
using Event = StepState::Event;
using Motion = StepState::Motion;
using PairContact = StepContext::PairContact;

/// No friction: a ball's spin is rolling's on the floor, none in flight; nothing is kept.
struct RollingSpin final : StepState::SpinModel
{
  void makeSpins(StepContext&, const std::vector<Vec2>&) const override {}
  void reserveOne(StepContext&) const override {}
  void addSpin(StepContext&, const BallDef&, const Vec2&, bool) const override {}
  void setSpin(StepContext&, std::size_t, const BallDef&, const Vec2&, bool) const override {}
  std::string strike(StepContext&, std::size_t, const Vec3&, const Vec3&, const Vec3&, bool) const override
  {
    return "";  // (an offset turns no ball that cannot keep a spin)
  }
  Vec3 angularVelocity(const StepContext& c, std::size_t s) const override
  {
    const Ball& ball = c.balls_[s];
    if (ball.flying())
      return Vec3::Zero();
    const Vec3 normal = c.ground_.normalUnder(c.footOf(s));
    return normal.cross(ball.velocity) / ball.radius;
  }
  MotionKind kindOnFloor(const StepContext& c, std::size_t s) const override
  {
    return c.balls_[s].velocity == Vec3::Zero() ? MotionKind::kStationary : MotionKind::kRolling;
  }
  double inertia(const StepContext&, std::size_t) const override { return kSolidInertia; }

  void startStep(StepContext& c) const override { c.spin_motions_.clear(); }
  void predictAsleep(StepContext&, std::size_t) const override {}
  void predictFlight(StepContext&, std::size_t) const override {}
  bool predictOnFloor(StepContext& c, std::size_t i) const override
  {
    c.floor_motion_->predict(c, i, c.balls_[i].velocity);
    return true;
  }
  void startOnFloor(StepContext& c, std::size_t i, double x, const Vec3& position, bool) const override
  {
    c.floor_motion_->start(c, i, x, position, c.startVelocity(i));
  }
  void hold(StepContext&, std::size_t) const override {}
  void cap(StepContext&, std::size_t) const override {}
  void followGroup(StepContext&, std::size_t, bool) const override {}
  void stop(StepContext&, std::size_t) const override {}
  void startFlight(StepContext&, std::size_t) const override {}
  void liftOff(StepContext& c, std::size_t i, double x, bool flew) const override
  {
    // (on the floor a ball is rolling while it moves)
    if (!flew)
      recordFlightChange(c, i, x, c.startVelocity(i) == Vec3::Zero() ? MotionKind::kStationary : MotionKind::kRolling,
                         MotionKind::kFlying);
  }
  double speedSquaredAt(const StepContext& c, std::size_t i, double, const Vec3& p) const override
  {
    return c.pulledSpeedSquared(i, p);
  }
  const Vec3& pull(const StepContext& c, std::size_t) const override { return c.gravity_; }
  double chordSpeedSquared(const StepContext& c, std::size_t i, double rest, const Vec3& b) const override
  {
    return c.linearChordSpeedSquared(i, rest, b);
  }
  bool flowLaw(const StepContext&, std::size_t, FloorFlow::Law& law) const override
  {
    law = FloorFlow::Law{};  // (a frictionless ball's: gravity along the floor)
    return true;
  }
  void queueEnd(StepContext&, std::size_t) const override {}
  void endMotion(StepContext&, const Event&, const Vec3&, Vec3&) const override {}
  void takeOff(StepContext&, std::size_t, double, const Vec3&, const Vec3&) const override {}
  void wallImpact(StepContext&, std::size_t, double, const Vec3&, const Vec3&, double, const Vec3&,
                  Vec3&) const override
  {
  }
  void pairImpact(StepContext&, const PairContact&, double, double, const Vec3&, const Vec3&, Vec3&,
                  Vec3&) const override
  {
  }
  void landingImpact(StepContext&, std::size_t, double, const Vec3&, double, Vec3&) const override {}
  void landed(StepContext& c, std::size_t i, double x, const Vec3& v) const override
  {
    recordFlightChange(c, i, x, MotionKind::kFlying, v == Vec3::Zero() ? MotionKind::kStationary : MotionKind::kRolling);
  }
  void commit(StepContext&, std::size_t, const Ground::End&) const override {}
  void roll(StepContext& c, std::size_t i, const Vec3& normal, const Vec3& d) const override
  {
    Ball& ball = c.balls_[i];
    if (ball.flying())
      return;
    // rolling without slip, by the move along the floor (step::rolled())
    ball.orientation = rolled(ball.orientation, normal, d, ball.radius);
  }
  double spinEnergy(const StepContext&, std::size_t) const override { return 0.0; }
  void addSpinEnergies(const StepContext&, std::vector<double>&) const override {}
  void scaleSpin(StepContext&, std::size_t, double) const override {}
  bool rollsInGroup(const StepContext&, std::size_t, const Vec3&) const override { return false; }
  void settle(StepContext&, std::size_t, const Vec3&, const Vec3&) const override {}
};

/// Friction: each ball's own spin, and its phase in the step.
struct FrictionSpin final : StepState::SpinModel
{
  void makeSpins(StepContext& c, const std::vector<Vec2>& feet) const override
  {
    c.spins_.reserve(c.balls_.size());
    for (std::size_t k = 0; k < c.balls_.size(); ++k)
    {
      BallDef def = k < c.scene_.balls.size() ? c.scene_.balls[k] : randomBallDef(c.scene_, c.balls_[k]);
      def.position = c.balls_[k].position;
      def.velocity = c.balls_[k].velocity;
      c.spins_.push_back(c.makeSpin(def, feet[k], c.balls_[k].flying()));
    }
  }
  void reserveOne(StepContext& c) const override
  {
    if (c.spins_.size() == c.spins_.capacity())
      c.spins_.reserve(2 * c.spins_.size() + 1);
  }
  void addSpin(StepContext& c, const BallDef& placed, const Vec2& foot, bool flying) const override
  {
    c.spins_.push_back(c.makeSpin(placed, foot, flying));
  }
  void setSpin(StepContext& c, std::size_t s, const BallDef& def, const Vec2& foot, bool flying) const override
  {
    c.spins_[s] = c.makeSpin(def, foot, flying);
  }
  std::string strike(StepContext& c, std::size_t s, const Vec3& impulse, const Vec3& offset, const Vec3& velocity,
                     bool flying) const override
  {
    const Ball& ball = c.balls_[s];
    BallSpin& spin = c.spins_[s];
    const Vec3 w = spin.angular_velocity + offset.cross(impulse) / (spin.inertia * ball.mass * ball.radius * ball.radius);
    if (!(w.stableNorm() <= kMaxSpin))
      return "impulse: would give ball " + std::to_string(ball.id) + " a spin of " + formatNumber(w.stableNorm()) +
             " rad/s, past the limit of " + formatNumber(kMaxSpin) + " rad/s";
    spin.angular_velocity = w;
    spin.kind = flying ? MotionKind::kFlying
                       : c.frictionUnder(c.ground_.normalUnder(c.footOf(s))).kindOf(spin.inertia, ball.radius, velocity, w);
    return "";
  }
  Vec3 angularVelocity(const StepContext& c, std::size_t s) const override { return c.spins_[s].angular_velocity; }
  MotionKind kindOnFloor(const StepContext& c, std::size_t s) const override { return c.spins_[s].kind; }
  double inertia(const StepContext& c, std::size_t s) const override { return c.spins_[s].inertia; }

  void startStep(StepContext& c) const override { c.spin_motions_.resize(c.balls_.size()); }
  static void load(StepContext& c, std::size_t i)
  {
    SpinMotion& sm = c.spin_motions_[i];
    sm.w0 = c.spins_[i].angular_velocity;
    sm.kind = sm.reported = c.spins_[i].kind;
  }
  void predictAsleep(StepContext& c, std::size_t i) const override
  {
    load(c, i);
    c.keepSpin(i);
  }
  void predictFlight(StepContext& c, std::size_t i) const override
  {
    load(c, i);  // (its kind is recorded where it leaves the floor, or left it just now)
  }
  bool predictOnFloor(StepContext& c, std::size_t i) const override
  {
    load(c, i);
    c.spin_motions_[i].normal = c.floorNormalAt(i, c.balls_[i].position);  // (where its last step put it)
    // (a change of kind was recorded where the last phase ended)
    if (!c.startFriction(i, 0.0, false, false))
      return false;
    c.floor_motion_->predict(c, i, c.balls_[i].velocity);
    phaseChord(c, i);
    return true;
  }
  void startOnFloor(StepContext& c, std::size_t i, double x, const Vec3& position, bool impact) const override
  {
    if (!c.startFriction(i, x, true, impact))  // the phase its velocity and spin give it
      return;                                  // (else the chord below, under the phase's pull)
    c.floor_motion_->start(c, i, x, position, c.startVelocity(i));
    phaseChord(c, i);
  }
  /// A phase that gives its velocity itself, moved on the floor's chord: the chord is its.
  static void phaseChord(StepContext& c, std::size_t i)
  {
    Motion& m = c.motions_[i];
    if (m.type == MotionType::kLine && c.spin_motions_[i].phase->givesVelocity())
      m.type = MotionType::kPhaseChord;
  }
  void hold(StepContext& c, std::size_t i) const override { c.keepSpin(i); }
  void cap(StepContext& c, std::size_t i) const override
  {
    c.keepSpin(i);
    c.spin_motions_[i].w0 = Vec3::Zero();  // (no motion at all, and no energy made)
  }
  void followGroup(StepContext& c, std::size_t i, bool rolls) const override
  {
    if (rolls)
      c.rollSpin(i);
    else
      c.constrainSpin(i);
  }
  void stop(StepContext& c, std::size_t i) const override
  {
    // (a ball whose phase does not make its motion keeps what spin it has)
    if (c.spin_motions_[i].phase->ownsMotion())
      c.constrainSpin(i);
  }
  void startFlight(StepContext& c, std::size_t i) const override
  {
    c.keepSpin(i);
    c.spin_motions_[i].kind = MotionKind::kFlying;
  }
  void liftOff(StepContext& c, std::size_t i, double x, bool) const override
  {
    c.spin_motions_[i].kind = MotionKind::kFlying;
    c.recordKind(i, x);
    c.spins_[i].kind = MotionKind::kFlying;
  }
  double speedSquaredAt(const StepContext& c, std::size_t i, double x, const Vec3& p) const override
  {
    return c.spin_motions_[i].phase->speedSquaredAt(c, i, x, p);
  }
  const Vec3& pull(const StepContext& c, std::size_t i) const override
  {
    return c.spin_motions_[i].phase->pull(c, c.spin_motions_[i]);
  }
  double chordSpeedSquared(const StepContext& c, std::size_t i, double rest, const Vec3& b) const override
  {
    return c.spin_motions_[i].phase->chordSpeedSquared(c, i, rest, b);
  }
  bool flowLaw(const StepContext& c, std::size_t i, FloorFlow::Law& law) const override
  {
    return c.spin_motions_[i].phase->flowLaw(c, i, law);
  }
  void queueEnd(StepContext& c, std::size_t i) const override { c.queueTransition(i); }
  void endMotion(StepContext& c, const Event& event, const Vec3& normal, Vec3& v) const override
  {
    const std::size_t i = event.i;
    SpinMotion& sm = c.spin_motions_[i];
    Vec3 w = c.spinAtEvent(i, event.x, normal, v);
    if (event.end == MotionEnd::kPhase)
    {
      // (under the normal where it is now: its velocity there lies along that floor)
      const FrictionLaw law = c.frictionUnder(normal);
      const double speeds = law.speeds(c.balls_[i].radius, c.startVelocity(i), sm.w0);
      law.finish(sm.ends, c.spins_[i].inertia, c.balls_[i].radius, speeds, v, w);
      if (sm.ends & kSlipStops)
        sm.kind = MotionKind::kRolling;  // (its slip is gone: it rolls, or finds it cannot)
    }
    sm.w0 = w;
    sm.normal = normal;  // (the spin there is under the normal there: rollOn())
  }
  void takeOff(StepContext& c, std::size_t i, double x, const Vec3& normal, const Vec3& v) const override
  {
    c.spin_motions_[i].w0 = c.spinAtEvent(i, x, normal, v);
  }

  void wallImpact(StepContext& c, std::size_t i, double x, const Vec3& n, const Vec3& floor_normal, double impulse,
                  const Vec3& before, Vec3& v) const override
  {
    c.spin_motions_[i].w0 = c.spinAtEvent(i, x, floor_normal, before);
    c.ballWallFriction(i, n, floor_normal, impulse, v);
  }
  void pairImpact(StepContext& c, const PairContact& pair, double x, double impulse, const Vec3& va_before,
                  const Vec3& vb_before, Vec3& va, Vec3& vb) const override
  {
    // (the spins there before the impact: the new motions' w0)
    c.spin_motions_[pair.i].w0 = c.spinAtEvent(pair.i, x, pair.na, va_before);
    c.spin_motions_[pair.j].w0 = c.spinAtEvent(pair.j, x, pair.nb, vb_before);
    c.ballBallFriction(pair, impulse, va, vb);
  }
  void landingImpact(StepContext& c, std::size_t i, double x, const Vec3& n, double normal_impulse,
                     Vec3& v) const override
  {
    // Friction's impulse at the contact point against its slip u = v + r n x w, at most
    // mu_s times the normal impulse: it stops the slip where that is enough (an impulse J
    // along the floor changes u by J (1 + 1/k) / m).
    const Ball& ball = c.balls_[i];
    const double r = ball.radius;
    Vec3 w = c.spinAt(i, x);
    const double k = c.spins_[i].inertia;
    Vec3 u = v + r * n.cross(w);
    u -= u.dot(n) * n;
    const double slip = u.norm();
    if (slip > 0)
    {
      const double stop = slip * ball.mass * k / (1 + k);
      const Vec3 j = -(std::min(c.scene_.friction->sliding * normal_impulse, stop) / slip) * u;
      v += j / ball.mass;
      w -= n.cross(j) / (k * ball.mass * r);
    }
    c.spin_motions_[i].w0 = w;
  }
  void landed(StepContext&, std::size_t, double, const Vec3&) const override
  {
    // (the phase it lands in reports its kind: startMotion())
  }

  void commit(StepContext& c, std::size_t i, const Ground::End& end) const override
  {
    // its own spin at the end, and its turn over the step by the mean of its spins
    const Ball& ball = c.balls_[i];
    SpinMotion& sm = c.spin_motions_[i];
    BallSpin& spin = c.spins_[i];
    // (a rolling ball rolls under the normal where it ends)
    const Vec3 w = ball.flying()
                       ? c.spinAt(i, 1.0)
                       : c.floor_motion_->spinThere(
                             c, i, 1.0, end.normal, ball.velocity,
                             sm.phase->spinWith(c, i, 1.0, end.normal, ball.velocity),
                             sm.phase->rollsAtCommit(sm));
    sm.turn = (0.5 * c.dt_) * (spin.angular_velocity + w);
    spin.angular_velocity = w;
    sm.kind = ball.flying() ? MotionKind::kFlying : sm.phase->kindAtEnd(c, i, sm, end.normal, ball.velocity, w);
    c.recordKind(i, sm.phase->kindFrom(c, i, sm));  // (a kind the step's events did not report)
    spin.kind = sm.kind;
  }
  void roll(StepContext& c, std::size_t i, const Vec3&, const Vec3&) const override
  {
    c.turn(i, c.spin_motions_[i].turn);  // by its own spin
  }
  double spinEnergy(const StepContext& c, std::size_t i) const override
  {
    if (!c.friction_->grips())
      return 0.0;  // (a spin that never meets the floor's grip is not the ball's to give)
    const Ball& ball = c.balls_[i];
    return 0.5 * c.spins_[i].inertia * ball.mass * ball.radius * ball.radius *
           c.spins_[i].angular_velocity.squaredNorm();
  }
  void addSpinEnergies(const StepContext& c, std::vector<double>& energies) const override
  {
    for (std::size_t i = 0; i < energies.size(); ++i)
      energies[i] += spinEnergy(c, i);
  }
  void scaleSpin(StepContext& c, std::size_t i, double scale) const override
  {
    if (c.friction_->grips())
      c.spins_[i].angular_velocity *= scale;
  }
  bool rollsInGroup(const StepContext& c, std::size_t i, const Vec3& n) const override
  {
    // (a ball that slips goes on slipping: its contacts move it as a mass, and its
    // spin follows friction, FrictionLaw::constrained(), until its slip ends)
    return c.spin_motions_[i].kind != MotionKind::kSliding && c.frictionUnder(n).holdsRolling(c.spins_[i].inertia);
  }
  void settle(StepContext& c, std::size_t i, const Vec3& change, const Vec3& normal) const override
  {
    if (rollsInGroup(c, i, normal))
      c.spins_[i].angular_velocity += normal.cross(change) / c.balls_[i].radius;
  }
};

const RollingSpin kRollingSpin;
const FrictionSpin kFrictionSpin;
}  // namespace

double StepContext::spinEnergy(std::size_t i) const
{
  return spin_->spinEnergy(*this, i);
}

const StepState::SpinModel& StepState::SpinModel::of(bool friction)
{
  if (friction)
    return kFrictionSpin;
  return kRollingSpin;
}
}  // namespace ball_collision_sim::core
