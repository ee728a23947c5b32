// Friction in the step (worlds with a friction block, on any floor): each free ball's
// motion is a phase of constant accelerations from the friction laws (FrictionLaw); the
// end of a phase (slip, speed or spin about the normal reaching zero) is an event at its
// exact time, and impacts add tangential impulses. Reads and writes motions_,
// spin_motions_, the start velocities and the queue; writes transitions_ and stats_.
#include "spin_model.hpp"
#include "spin_phase.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <algorithm>
#include <cmath>

namespace ball_collision_sim::core
{
using namespace step;

const Vec3& StepContext::pathTerm(std::size_t i) const
{
  switch (motions_[i].type)
  {
    case MotionType::kFlight:
      return flight_c_;
    case MotionType::kPhase:
      return spin_motions_[i].c;
    case MotionType::kPath:
      return path_c_;
    default:
      return zero_c_;
  }
}

Vec3 StepContext::spinOf(const BallDef& def, const Vec3& n)
{
  return def.angular_velocity ? *def.angular_velocity : Vec3(n.cross(def.velocity) / def.radius);
}

void StepContext::recordKind(std::size_t i, double x)
{
  SpinMotion& sm = spin_motions_[i];
  if (sm.kind == sm.reported)
    return;
  noteTransition(i, x, sm.reported, sm.kind);
  sm.reported = sm.kind;
}

FrictionLaw StepContext::frictionUnder(const Vec3& n) const
{
  return floor_motion_->lawUnder(*this, n);
}

double StepContext::speedSquaredAt(std::size_t i, double x, const Vec3& p) const
{
  return spin_->speedSquaredAt(*this, i, x, p);
}

double StepContext::pulledSpeedSquared(std::size_t i, const Vec3& p) const
{
  return startVelocity(i).squaredNorm() + 2 * pullOf(i).dot(p - startPosition(i));
}

const Vec3& StepContext::pullOf(std::size_t i) const
{
  return spin_->pull(*this, i);
}

bool StepContext::startFriction(std::size_t i, double x, bool record, bool impact)
{
  SpinMotion& sm = spin_motions_[i];
  const BallSpin& spin = spins_[i];
  Vec3& v = startVelocity(i);
  const FrictionLaw law = frictionUnder(floorNormalAt(i, startPosition(i)));
  if (!impact && sm.kind == MotionKind::kRolling)
    floor_motion_->rollOn(*this, i, law);  // (under the normal where it is now)
  const FrictionPhase phase = law.start(spin.inertia, balls_[i].radius, v, sm.w0);
  sm.normal = law.normal();

  // (a curved floor's chord: its share of gravity itself, and the friction force; so the
  // speed its energy gives counts gravity's work along the chord, not along the tangent)
  // A still ball has no share: the pull into the floor keeps it on it, and a start below
  // the floor (a chord's point at a mid-step end of its phase) may not rise for nothing.
  sm.pull = phase.gravity_share > 0
                ? Vec3(phase.gravity_share * gravity_ + (phase.acceleration - phase.gravity_share * law.gravityAlong()))
                : Vec3(gravity_ - law.gravityAlong());
  sm.a = phase.acceleration;
  sm.alpha = phase.angular_acceleration;
  sm.c = (0.5 * dt_ * dt_) * phase.acceleration;
  sm.kind = phase.kind;
  sm.ends = phase.ends;
  sm.x_end = x + phase.duration / dt_;
  // (what a sliding phase's slip takes on a curved floor: speedSquaredAt())
  sm.slip0 = law.slip(balls_[i].radius, v, sm.w0).norm();
  sm.slip_force = scene_.friction->sliding * std::max(0.0, -gravity_.dot(law.normal()));
  sm.roll_resistance = scene_.friction->rolling * std::max(0.0, -gravity_.dot(law.normal()));
  sm.slip_rate = sm.slip_force * (1 + spin.inertia) / spin.inertia - law.gravityAlong().dot(phase.slip_direction);
  sm.turning = phase.turning;
  sm.phase = &SpinPhase::of(phase, *floor_motion_);
  if (record)
    recordKind(i, x);
  return sm.phase->startMotion(*this, i, law);
}

void StepContext::keepSpin(std::size_t i)
{
  SpinMotion& sm = spin_motions_[i];
  sm.alpha = sm.a = sm.c = Vec3::Zero();
  sm.x_end = 2.0;
  sm.ends = kPhaseRuns;
  sm.phase = &SpinPhase::kept();
}

void StepContext::constrainSpin(std::size_t i)
{
  keepSpin(i);
  SpinMotion& sm = spin_motions_[i];
  const FrictionLaw law = frictionUnder(floorNormalAt(i, startPosition(i)));
  sm.normal = law.normal();
  const FrictionLaw::ConstrainedSpin spin =
      law.constrained(spins_[i].inertia, balls_[i].radius, startVelocity(i), sm.w0);
  sm.alpha = spin.along_rate;
  sm.along_time = spin.along_time;
  sm.normal_rate = spin.normal_rate;
  sm.normal_time = spin.normal_time;
  sm.phase = &SpinPhase::constrained();
}

void StepContext::rollSpin(std::size_t i)
{
  constrainSpin(i);  // (for its spin about the normal)
  spin_motions_[i].phase = &SpinPhase::rolled();
}

Vec3 StepContext::spinAtEvent(std::size_t i, double x, const Vec3& normal, const Vec3& v) const
{
  const SpinMotion& sm = spin_motions_[i];
  const Vec3 spin = sm.phase->spinWith(*this, i, x, normal, v);
  return floor_motion_->spinThere(*this, i, x, normal, v, spin, sm.phase->rollsAtEvent(sm));
}

Vec3 StepContext::spinAt(std::size_t i, double x) const
{
  const SpinMotion& sm = spin_motions_[i];
  const double t = (x - motions_[i].x0) * dt_;
  return sm.phase->spinAt(sm, t);
}

void StepContext::queueTransition(std::size_t i)
{
  const SpinMotion& sm = spin_motions_[i];
  if (!sm.phase->ownsMotion() || !(sm.x_end <= 1))
    return;
  queueMotionEnd(i, sm.x_end, MotionEnd::kPhase);
}

Mat2 StepContext::slipResponse(const Vec3& t1, const Vec3& t2, const Vec3& floor_normal, double inv, double k) const
{
  // (an impulse J moves the ball by inv J along what the floor lets it, and turns its
  // touching point by inv J / k)
  const Vec3 a1 = ground_.along(t1, floor_normal), a2 = ground_.along(t2, floor_normal);
  Mat2 response;
  response << t1.dot(a1) + 1 / k, t1.dot(a2), t2.dot(a1), t2.dot(a2) + 1 / k;
  return inv * response;
}

void StepContext::ballBallFriction(const PairContact& c, double normal_impulse, Vec3& va, Vec3& vb)
{
  Vec3& wa = spin_motions_[c.i].w0;
  Vec3& wb = spin_motions_[c.j].w0;
  const double mu = scene_.friction->ball_ball;
  if (!(mu > 0))
    return;
  // Friction acts across the contact's tangent plane: along the floor, and across it,
  // where it turns the spins (the floor takes the part of a push into it).
  const Vec3 t1 = c.n.unitOrthogonal(), t2 = c.n.cross(t1);
  const double ra = balls_[c.i].radius, rb = balls_[c.j].radius;
  const double ka = spins_[c.i].inertia, kb = spins_[c.j].inertia;
  // the touching points' velocities: a's at ra n from its centre, b's at -rb n from its
  // (a ball without motion, asleep or stopped by the cap, is still: its surface too,
  // else it would drive the other like a belt)
  const Vec3 spin_a = motions_[c.i].frozen() ? Vec3::Zero() : wa, spin_b = motions_[c.j].frozen() ? Vec3::Zero() : wb;
  Vec3 slip = (va + spin_a.cross(ra * c.n)) - (vb - spin_b.cross(rb * c.n));
  slip -= slip.dot(c.n) * c.n;
  const Mat2 response = slipResponse(t1, t2, c.na, c.inv_a, ka) + slipResponse(t1, t2, c.nb, c.inv_b, kb);
  const Vec3 impulse = tangentialImpulse(slip, t1, t2, response, mu, normal_impulse);  // on a; -impulse on b
  if (impulse == Vec3::Zero())
    return;
  va += c.inv_a * ground_.along(impulse, c.na);
  vb -= c.inv_b * ground_.along(impulse, c.nb);
  wa += (c.inv_a / (ka * ra)) * c.n.cross(impulse);
  wb += (c.inv_b / (kb * rb)) * c.n.cross(impulse);
}

void StepContext::ballWallFriction(std::size_t i, const Vec3& n, const Vec3& floor_normal, double normal_impulse, Vec3& v)
{
  Vec3& w = spin_motions_[i].w0;
  const double mu = scene_.friction->wall;
  if (!(mu > 0) || motions_[i].frozen())
    return;
  // (across the contact's tangent plane, as between balls)
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const double r = balls_[i].radius;
  const double k = spins_[i].inertia;
  const double inv = 1.0 / balls_[i].mass;
  Vec3 slip = v + w.cross(r * n);  // the touching point's, n toward the wall
  slip -= slip.dot(n) * n;
  const Vec3 impulse = tangentialImpulse(slip, t1, t2, slipResponse(t1, t2, floor_normal, inv, k), mu, normal_impulse);
  if (impulse == Vec3::Zero())
    return;
  v += inv * ground_.along(impulse, floor_normal);
  w += (inv / (k * r)) * n.cross(impulse);
}

void StepContext::turn(std::size_t i, const Vec3& angle)
{
  const double a = angle.norm();
  if (!(a > 0))
    return;
  Ball& ball = balls_[i];
  const Quat q = Quat(Eigen::AngleAxisd(a, angle / a)) * ball.orientation;
  ball.orientation = q.normalized();
}
}  // namespace ball_collision_sim::core
