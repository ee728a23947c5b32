// The friction laws of a ball on a plane: its motion kind from its velocity and spin, the
// constant accelerations of each kind, and the exact time the phase ends.
#include "ball_collision_sim/core/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ball_collision_sim::core
{
namespace
{
constexpr double kNever = std::numeric_limits<double>::infinity();
}  // namespace

const char* motionKindName(MotionKind kind)
{
  switch (kind)
  {
    case MotionKind::kSliding:
      return "sliding";
    case MotionKind::kRolling:
      return "rolling";
    case MotionKind::kSpinning:
      return "spinning";
    case MotionKind::kStationary:
      return "stationary";
    case MotionKind::kFlying:
      return "flying";
  }
  return "?";
}

FrictionLaw::FrictionLaw(const FrictionDef& mu, const Vec3& normal, const Vec3& gravity, const Vec3& along,
                         double slip_tolerance, double still_speed)
    : mu_(mu), normal_(normal), slip_tolerance_(slip_tolerance), still_speed_(still_speed)
{
  // (no pull into the floor, no friction: a floor above its balls, or no gravity)
  g_n_ = std::max(0.0, -gravity.dot(normal));
  g_t_ = along;
}

void TurningPhase::at(double t, Vec3& velocity, Vec3& move, Vec3& spin_change) const
{
  Vec3 q, integral_q;
  drag.at(t, q, integral_q);
  velocity = v0 + t * drift + share * (q - q0);
  move = t * v0 + (0.5 * t * t) * drift + share * (integral_q - t * q0);
  spin_change = normal.cross(velocity - v0 - slip_share * (q - q0)) / radius;
}

void FrictionLaw::turn(const Vec3& q0, const Vec3& v0, double k, double r, FrictionPhase& phase) const
{
  // the slip's drag (sliding) or the velocity's (rolling)
  const bool slides = phase.kind == MotionKind::kSliding;
  const TurningDrag drag = slides ? TurningDrag(q0, g_t_, mu_.sliding * g_n_ * (1 + k) / k)
                                  : TurningDrag(q0, g_t_ / (1 + k), mu_.rolling * g_n_);
  if (!drag.turns())
    return;  // (along the fall line, or no pull or no drag: the accelerations are constant)
  TurningPhase& turning = phase.turning;
  turning.drag = drag;
  turning.q0 = q0;
  turning.v0 = v0;
  turning.normal = normal_;
  turning.radius = r;
  if (slides)
  {
    turning.drift = g_t_ / (1 + k);
    turning.share = k / (1 + k);
    turning.slip_share = 1.0;
  }
  phase.duration = drag.endTime();
  phase.ends = std::isfinite(phase.duration) ? (slides ? kSlipStops : kBallStops) : kPhaseRuns;
}

void FrictionLaw::stick(double k, double r, Vec3& v, Vec3& w) const
{
  // The impulse P at the contact point changes the slip by (1 + 1/k) P / m: P = -m u k / (1 + k).
  const Vec3 u = slip(r, v, w);
  v -= (k / (1 + k)) * u;
  w += normal_.cross(u) / ((1 + k) * r);
}

FrictionPhase FrictionLaw::sliding(double k, double r, const Vec3& u_direction, double u_norm) const
{
  FrictionPhase phase;
  phase.kind = MotionKind::kSliding;
  phase.slip_direction = u_direction;
  const double force = mu_.sliding * g_n_;  // friction's deceleration [m/s^2]
  phase.acceleration = g_t_ - force * u_direction;
  phase.angular_acceleration = (force / (k * r)) * normal_.cross(u_direction);
  // du/dt = g_t - mu_s g_n (1 + 1/k) u/|u|: |u| falls at this rate along its direction
  const double rate = force * (1 + k) / k - g_t_.dot(u_direction);
  phase.duration = kNever;
  // (the slip ends where friction takes it away; without friction (mu_s g_n = 0) gravity
  // only turns it, and a part across its first direction stays: the ball slides on)
  if (u_norm > 0 && rate > 0 && force > 0)
  {
    phase.duration = u_norm / rate;
    phase.ends = kSlipStops;
  }
  return phase;
}

FrictionPhase FrictionLaw::rolling(double k, double r, const Vec3& v, const Vec3& direction) const
{
  FrictionPhase phase;
  phase.kind = MotionKind::kRolling;
  phase.gravity_share = 1 / (1 + k);
  phase.acceleration = g_t_ / (1 + k) - (mu_.rolling * g_n_) * direction;
  phase.angular_acceleration = normal_.cross(phase.acceleration) / r;
  const double speed = v.norm();
  const double rate = mu_.rolling * g_n_ - g_t_.dot(direction) / (1 + k);
  phase.duration = kNever;
  if (speed > 0 && rate > 0)
  {
    phase.duration = speed / rate;
    phase.ends = kBallStops;
  }
  return phase;
}

void FrictionLaw::spinDecay(double k, double r, double wn, FrictionPhase& phase) const
{
  if (phase.kind == MotionKind::kStationary && wn != 0)
    phase.kind = MotionKind::kSpinning;
  const double rate = mu_.spinning * g_n_ / (k * r);  // [rad/s^2]
  if (wn == 0 || !(rate > 0))
    return;
  phase.angular_acceleration -= std::copysign(rate, wn) * normal_;
  const double t = std::abs(wn) / rate;
  if (t < phase.duration)
  {
    phase.duration = t;
    phase.ends = kSpinStops;
  }
  else if (t == phase.duration)
    phase.ends |= kSpinStops;
}

double FrictionLaw::spinAboutNormal(double r, const Vec3& v, Vec3& w) const
{
  const double wn = w.dot(normal_);
  // A spin about n of round-off (of the projection that ended it, on a tilted floor) is none.
  if (wn != 0 && (std::abs(wn) <= slip_tolerance_ * (w.norm() + v.norm() / r) || std::abs(wn) * r <= still_speed_))
  {
    w -= wn * normal_;
    return 0.0;
  }
  return wn;
}

FrictionLaw::ConstrainedSpin FrictionLaw::constrained(double k, double r, const Vec3& v, Vec3& w) const
{
  ConstrainedSpin out;
  const double wn = spinAboutNormal(r, v, w);
  const Vec3 along = w - wn * normal_;
  const Vec3 rolling = normal_.cross(v) / r;
  const Vec3 gap = along - rolling;
  const double gap_norm = gap.norm();
  const double rate = mu_.sliding * g_n_ / (k * r);  // [rad/s^2]
  if (gap_norm > 0 && rate > 0 && rolling.norm() <= along.norm())
  {
    out.along_rate = (-rate / gap_norm) * gap;
    out.along_time = gap_norm / rate;
  }
  const double spin_rate = mu_.spinning * g_n_ / (k * r);
  if (wn != 0 && spin_rate > 0)
  {
    out.normal_rate = -std::copysign(spin_rate, wn);
    out.normal_time = std::abs(wn) / spin_rate;
  }
  return out;
}

bool FrictionLaw::slipsBeyondContacts(double r, const Vec3& v, const Vec3& w) const
{
  const Vec3 gap = w - w.dot(normal_) * normal_ - normal_.cross(v) / r;
  return r * gap.norm() > std::max(slip_tolerance_ * speeds(r, v, w), still_speed_);
}

Vec3 FrictionLaw::settled(double r, const Vec3& v, const Vec3& w) const
{
  return slipsBeyondContacts(r, v, w) ? w : Vec3(normal_.cross(v) / r + w.dot(normal_) * normal_);
}

MotionKind FrictionLaw::constrainedKind(double r, const Vec3& v, const Vec3& w) const
{
  const double wn = w.dot(normal_);
  if (slipsBeyondContacts(r, v, w))
    return MotionKind::kSliding;
  if (v != Vec3::Zero())
    return MotionKind::kRolling;
  return std::abs(wn) > slip_tolerance_ * w.norm() && std::abs(wn) * r > still_speed_ ? MotionKind::kSpinning
                                                                                     : MotionKind::kStationary;
}

Vec3 FrictionLaw::rollingSpin(double r, const Vec3& v, const Vec3& w, double wn) const
{
  const Vec3 along_floor = normal_.cross(v) / r;
  const Vec3 rolling = along_floor + wn * normal_;
  // Under a normal other than the one the spin was rolling under (a curved floor's, a
  // step on), part of the spin along the floor becomes spin about n: it may not add
  // energy, so the spin about n is cut to what |w| leaves.
  if (!(rolling.squaredNorm() > w.squaredNorm()))
    return rolling;
  const double room = w.squaredNorm() - along_floor.squaredNorm();
  if (room < 0)
    return w;  // (the velocity changed since the spin was rolling's: a real slip, friction's to take)
  return along_floor + std::copysign(std::sqrt(room), wn) * normal_;
}

FrictionPhase FrictionLaw::start(double k, double r, Vec3& v, Vec3& w) const
{
  const double wn = spinAboutNormal(r, v, w);
  // (a ball all but still, slipping by round-off: still)
  const auto stillIfAllBut = [&] {
    if (v.norm() <= still_speed_ && r * (w - wn * normal_).norm() <= still_speed_)
    {
      v = Vec3::Zero();
      w = wn * normal_;
      return true;
    }
    return false;
  };
  const bool still = stillIfAllBut();
  const Vec3 u = still ? Vec3::Zero() : slip(r, v, w);
  const double u_norm = u.norm();
  const double scale = speeds(r, v, w);
  FrictionPhase phase;
  if (u_norm > slip_tolerance_ * scale)
  {
    phase = sliding(k, r, u / u_norm, u_norm);
    turn(u, along(v), k, r, phase);
    spinDecay(k, r, wn, phase);
    phase.conservative = phase.acceleration == g_t_;
    return phase;
  }
  if (u_norm > 0 && mu_.sliding * g_n_ > 0)
  {
    stick(k, r, v, w);
    stillIfAllBut();  // (the slip it took was round-off of a ball at rest)
  }
  w = normal_.cross(v) / r + wn * normal_;  // rolling's spin, exactly
  const Vec3 moving = along(v);  // (the direction of rolling is along the floor)
  const double speed = moving.norm();
  const double pull = g_t_.norm();
  // friction holds rolling while k |g_t| / (1 + k) <= mu_s g_n; beyond, slip grows along g_t
  const bool holds = k * pull / (1 + k) <= mu_.sliding * g_n_;
  const Vec3 downhill = pull > 0 ? Vec3(g_t_ / pull) : Vec3::Zero();
  if (speed > 0)
  {
    phase = holds ? rolling(k, r, moving, moving / speed) : sliding(k, r, downhill, 0.0);
    if (holds)
      turn(moving, moving, k, r, phase);
  }
  else if (pull / (1 + k) <= mu_.rolling * g_n_)
  {
    phase.kind = MotionKind::kStationary;  // (spinning, where it turns about n)
    phase.duration = kNever;
    phase.gravity_share = 0.0;
  }
  else
    phase = holds ? rolling(k, r, v, downhill) : sliding(k, r, downhill, 0.0);
  spinDecay(k, r, wn, phase);
  phase.conservative = phase.acceleration == g_t_;
  return phase;
}

MotionKind FrictionLaw::kindOf(double k, double r, const Vec3& v, const Vec3& w) const
{
  Vec3 v_copy = v, w_copy = w;
  return start(k, r, v_copy, w_copy).kind;
}

void FrictionLaw::finish(std::uint8_t ends, double k, double r, double speeds, Vec3& v, Vec3& w) const
{
  if (ends & kSlipStops)
  {
    stick(k, r, v, w);
    if (v.norm() <= slip_tolerance_ * speeds)
      ends |= kBallStops;
  }
  if (ends & kBallStops)
  {
    v = Vec3::Zero();
    w = w.dot(normal_) * normal_;
  }
  if (ends & kSpinStops)
    w -= w.dot(normal_) * normal_;
}

Vec3 tangentialImpulse(const Vec3& slip, const Vec3& t1, const Vec3& t2, const Mat2& response, double mu,
                       double normal_impulse)
{
  const Vec2 u(slip.dot(t1), slip.dot(t2));
  if (!(mu > 0) || !(normal_impulse > 0) || u == Vec2::Zero())
    return Vec3::Zero();
  const Vec2 stop = -response.llt().solve(u);
  const double size = stop.norm(), bound = mu * normal_impulse;
  const Vec2 j = size > bound ? Vec2((bound / size) * stop) : stop;
  return j.x() * t1 + j.y() * t2;
}
}  // namespace ball_collision_sim::core
