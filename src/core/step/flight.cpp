// Flight: a ball off the floor moves on the parabola of gravity, its spin kept, until it
// meets the floor (an event at the exact time: a quadratic's root over a plane, a
// bracketed root of its height over a curved floor), a wall or a ball. At the floor it
// bounces at the floor's restitution, friction's impulse against the slip of its contact
// point turning its spin; a bounce too low to fly puts it on the floor. (Where a ball
// leaves the floor: take_off.cpp.)
// Reads and writes motions_, spin_motions_, the start positions and velocities, the
// balls' flying flags; writes the queue, events_, transitions_ and stats_.
#include "floor_motion.hpp"

#include "../bracketed_root.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ball_collision_sim::core
{
using namespace step;

double StepContext::floorRestitution() const
{
  return scene_.floor && scene_.floor->restitution ? *scene_.floor->restitution : scene_.restitution;
}

void StepContext::recordFlightChange(std::size_t i, double x, MotionKind from, MotionKind to)
{
  ++stats_.transitions;
  transitions_.push_back({(static_cast<double>(stats_.steps) + x) * dt_, balls_[i].id, from, to});
}

void StepContext::startFlight(std::size_t i)
{
  Motion& m = motions_[i];
  m.b = dt_ * startVelocity(i);
  m.become(MotionType::kFlight);  // (pathTerm(): flight_c_)
  ++flights_;
  if (!chord_ends_.empty())
    chord_ends_[i] = 1.0;
  if (friction_)
  {
    keepSpin(i);
    spin_motions_[i].kind = MotionKind::kFlying;
  }
}

Vec3 StepContext::flightVelocity(std::size_t i, double x) const
{
  return startVelocity(i) + ((x - motions_[i].x0) * dt_) * gravity_;
}

std::optional<double> StepContext::landingIn(std::size_t i, double rest) const
{
  return ground_.bends() ? landingOverCurve(i, rest) : landingOverPlane(i, rest);
}

std::optional<double> StepContext::landingOverPlane(std::size_t i, double rest) const
{
  // The height is the quadratic h(s) = h0 + B s + A s^2 in s = x - x0: its root where it
  // falls.
  const Ball& ball = balls_[i];
  const Vec3& p0 = startPosition(i);
  const double tolerance = roundoffAt(p0, ball.radius, settings_);
  const Vec3& n = ground_.floor()->planeNormal();
  const double h0 = n.dot(p0) - ground_.floor()->planeOffset() - ball.radius;
  const double B = n.dot(motions_[i].b), A = n.dot(flight_c_);
  if (h0 < -tolerance)
    return std::nullopt;  // (under the floor: fallen past its edge, it meets it no more)
  if (!(h0 > tolerance) && B <= 0)
    return 0.0;  // (on the floor, to round-off, and not leaving it)
  double s;
  if (A < 0)
  {
    const double disc = B * B - 4 * A * h0;
    if (!(disc >= 0))
      return 0.0;  // (below the floor all the way: at once)
    // the larger root, where h falls (stable form)
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    s = std::max(q / A, q != 0 ? h0 / q : 0.0);
  }
  else if (B < 0)
    s = -h0 / B;  // (no pull into the floor: a line)
  else
    return std::nullopt;
  if (!(s <= rest))
    return std::nullopt;
  return std::max(s, 0.0);
}

std::optional<double> StepContext::landingOverCurve(std::size_t i, double rest) const
{
  // The height sampled along the flight: the first sample more than round-off below the
  // floor closes a bracket, whose root is then found to neighbouring doubles. (A flight
  // that dips below and out again between two samples, a graze on a bump narrower than
  // the step's flight over StepSettings::landing_samples, is not seen.)
  const Ball& ball = balls_[i];
  const Vec3& p0 = startPosition(i);
  const double tolerance = roundoffAt(p0, ball.radius, settings_);
  Vec2 guess = guessOf(i);
  const auto height = [&](double s) {
    const Vec3 p = p0 + s * motions_[i].b + (s * s) * flight_c_;
    return ground_.heightAbove(p, ball.radius, guess);
  };
  const double h0 = height(0.0);
  if (h0 < -tolerance)
    return std::nullopt;  // (under the floor: fallen past its edge, it meets it no more)
  const int samples = settings_.landing_samples;
  double lo = 0.0, h_lo = std::max(h0, 0.0);
  for (int k = 1; k <= samples; ++k)
  {
    const double s = rest * k / samples;
    const double h = height(s);
    if (h < -tolerance)
      return bracketedRoot(height, [](double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }, lo, s, h_lo, h);
    if (h > 0)
    {
      lo = s;
      h_lo = h;
    }
  }
  return std::nullopt;
}

void StepContext::queueLanding(std::size_t i)
{
  if (!ground_.floor())
    return;
  const Motion& m = motions_[i];
  const std::optional<double> s = landingIn(i, 1 - m.x0);
  if (!s)
    return;
  // (where it lands off the floor's patch, it does not: it falls past the edge; the
  // patch's margin of Floor::inside() less its tolerance, so that a ball that has just
  // passed the edge, where it took off, is never taken for one landing there)
  if (!(edgeMargin(i, m.x0 + *s) >= Floor::kInsideTolerance))
    return;
  queueMotionEnd(i, std::min(m.x0 + *s, 1.0), MotionEnd::kLanding);
}

void StepContext::resolveLanding(const Event& event)
{
  const std::size_t i = event.i;
  const double x = event.x;
  Ball& ball = balls_[i];
  const double r = ball.radius;
  // where it meets the floor, put on it, and the normal there
  const Ground::End at = ground_.airEnd(positionAt(i, x), guessOf(i));
  guessOf(i) = at.foot;
  const Vec3 n = at.normal;
  const Vec3 p = ground_.land(at.centre, r, at.foot);
  Vec3 v = flightVelocity(i, x);
  const double closing = std::max(0.0, -v.dot(n));
  const double e = floorRestitution();
  const double normal_impulse = (1 + e) * ball.mass * closing;
  v += ((1 + e) * closing) * n;  // v_n -> -e v_n
  if (friction_)
  {
    // Friction's impulse at the contact point against its slip u = v + r n x w, at most
    // mu_s times the normal impulse: it stops the slip where that is enough (an impulse J
    // along the floor changes u by J (1 + 1/k) / m).
    SpinMotion& sm = spin_motions_[i];
    Vec3 w = spinAt(i, x);
    const double k = spins_[i].inertia;
    Vec3 u = v + r * n.cross(w);
    u -= u.dot(n) * n;
    const double slip = u.norm();
    if (slip > 0)
    {
      const double stop = slip * ball.mass * k / (1 + k);
      const Vec3 j = -(std::min(scene_.friction->sliding * normal_impulse, stop) / slip) * u;
      v += j / ball.mass;
      w -= n.cross(j) / (k * ball.mass * r);
    }
    sm.w0 = w;
  }
  const double away = v.dot(n);
  const double g_n = -gravity_.dot(n);
  const bool lands = !(away > 0) || 2 * away < settings_.min_flight_time * g_n;
  if (lands)
  {
    v -= away * n;  // (on the floor: what is left along its normal is the floor's)
    ball.flying = false;
    // (with friction the phase it lands in reports its kind: startMotion())
    if (!friction_)
      recordFlightChange(i, x, MotionKind::kFlying, v == Vec3::Zero() ? MotionKind::kStationary : MotionKind::kRolling);
  }
  ++stats_.floor_impacts;
  recordEvent(CollisionEvent::Kind::kBallFloor, ball.id, 0, p - r * n, -n, normal_impulse, closing, lands, event);
  startMotion(i, x, p, v, true);
  countEvent(i);
  detect(i);
}
}  // namespace ball_collision_sim::core
