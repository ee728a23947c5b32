// Flight: a ball off the floor moves on the parabola of gravity, its spin kept, until it
// meets the floor (an event at the exact time: a quadratic's root over a plane, a
// bracketed root of its height over a curved floor), a wall or a ball. At the floor it
// bounces at the floor's restitution, friction's impulse against the slip of its contact
// point turning its spin; a bounce too low to fly puts it on the floor. (Where a ball
// leaves the floor: take_off.cpp.)
// Reads and writes motions_, spin_motions_, the start positions and velocities, the
// balls' flying flags; writes the queue, events_, transitions_ and stats_.
#include "spin_model.hpp"
#include "flight.hpp"

#include "floor_motion.hpp"

#include "../bracketed_root.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ball_collision_sim::core::step
{

double floorRestitution(const StepContext& c)
{
  return c.scene_.floor && c.scene_.floor->restitution ? *c.scene_.floor->restitution : c.scene_.restitution;
}

void recordFlightChange(StepContext& c, std::size_t i, double x, MotionKind from, MotionKind to)
{
  c.noteTransition(i, x, from, to);
}

void startFlight(StepContext& c, std::size_t i)
{
  Motion& m = c.motions_[i];
  m.b = c.dt_ * c.startVelocity(i);
  m.become(MotionType::kFlight);  // (pathTerm(): flight_c_)
  c.noteFlight();
  if (!c.chord_ends_.empty())
  {
    c.chord_ends_[i] = 1.0;
    c.flow_ends_[i].x = -1.0;
  }
  c.spin_->startFlight(c, i);
}

Vec3 flightVelocity(const StepContext& c, std::size_t i, double x)
{
  return c.startVelocity(i) + ((x - c.motions_[i].x0) * c.dt_) * c.gravity_;
}

std::optional<double> landingIn(const StepContext& c, std::size_t i, double rest)
{
  return c.ground_.bends() ? landingOverCurve(c, i, rest) : landingOverPlane(c, i, rest);
}

std::optional<double> landingOverPlane(const StepContext& c, std::size_t i, double rest)
{
  // The height is the quadratic h(s) = h0 + B s + A s^2 in s = x - x0: its root where it
  // falls.
  const Ball& ball = c.balls_[i];
  const Vec3& p0 = c.startPosition(i);
  const double tolerance = roundoffAt(p0, ball.radius, c.settings_);
  const Vec3& n = c.ground_.floor()->planeNormal();
  const double h0 = n.dot(p0) - c.ground_.floor()->planeOffset() - ball.radius;
  const double B = n.dot(c.motions_[i].b), A = n.dot(c.flight_c_);
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

std::optional<double> landingOverCurve(const StepContext& c, std::size_t i, double rest)
{
  // The height sampled along the flight: the first sample more than round-off below the
  // floor closes a bracket, whose root is then found to neighbouring doubles. (A flight
  // that dips below and out again between two samples, a graze on a bump narrower than
  // the step's flight over StepSettings::landing_samples, is not seen.)
  const Ball& ball = c.balls_[i];
  const Vec3& p0 = c.startPosition(i);
  const double tolerance = roundoffAt(p0, ball.radius, c.settings_);
  Vec2 guess = c.guessOf(i);
  const auto height = [&](double s) {
    const Vec3 p = p0 + s * c.motions_[i].b + (s * s) * c.flight_c_;
    return c.ground_.heightAbove(p, ball.radius, guess);
  };
  const double h0 = height(0.0);
  if (h0 < -tolerance)
    return std::nullopt;  // (under the floor: fallen past its edge, it meets it no more)
  const int samples = c.settings_.landing_samples;
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

void queueLanding(StepContext& c, std::size_t i)
{
  if (!c.ground_.floor())
    return;
  const Motion& m = c.motions_[i];
  const std::optional<double> s = landingIn(c, i, 1 - m.x0);
  if (!s)
    return;
  // (where it lands off the floor's patch, it does not: it falls past the edge; the
  // patch's margin of Floor::inside() less its tolerance, so that a ball that has just
  // passed the edge, where it took off, is never taken for one landing there)
  if (!(edgeMargin(c, i, m.x0 + *s) >= Floor::kInsideTolerance))
    return;
  c.queueMotionEnd(i, std::min(m.x0 + *s, 1.0), MotionEnd::kLanding);
}

void resolveLanding(StepContext& c, const Event& event)
{
  const std::size_t i = event.i;
  const double x = event.x;
  Ball& ball = c.balls_[i];
  const double r = ball.radius;
  // where it meets the floor, put on it, and the normal there
  const Ground::End at = c.ground_.airEnd(c.positionAt(i, x), c.guessOf(i));
  c.guessOf(i) = at.foot;
  const Vec3 n = at.normal;
  const Vec3 p = c.ground_.land(at.centre, r, at.foot);
  Vec3 v = flightVelocity(c, i, x);
  const double closing = std::max(0.0, -v.dot(n));
  const double e = floorRestitution(c);
  const double normal_impulse = (1 + e) * ball.mass * closing;
  v += ((1 + e) * closing) * n;  // v_n -> -e v_n
  c.spin_->landingImpact(c, i, x, n, normal_impulse, v);
  const double away = v.dot(n);
  const double g_n = -c.gravity_.dot(n);
  const bool lands = !(away > 0) || 2 * away < c.settings_.min_flight_time * g_n;
  if (lands)
  {
    v -= away * n;  // (on the floor: what is left along its normal is the floor's)
    ball.support = Ball::Support::kFloor;
    c.spin_->landed(c, i, x, v);
  }
  ++c.stats_.floor_impacts;
  c.recordEvent(CollisionEvent::Kind::kBallFloor, ball.id, 0, p - r * n, -n, normal_impulse, closing, lands, event);
  c.startMotion(i, x, p, v, true);
  c.countEvent(i);
  c.detect(i);
}
}  // namespace ball_collision_sim::core::step
