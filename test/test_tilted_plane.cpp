// Friction across a tilted plane's fall line, where the slip's (sliding) or the
// velocity's (rolling) direction turns toward the fall line: TurningDrag's closed form
// against an integration of dq/dt = a - c q/|q| and against the puck's known terminal
// speed; and balls on planes tilted every way, sliding, rolling and stopping, against an
// integration of the friction laws as docs/physics.md states them (RK4 in long double,
// steps of 1e-4 s, shorter near a slip's or a speed's end), position and velocity to
// 1e-9 at every step's end and the time a phase ends to 1e-9 s.
#include "fixtures.hpp"

#include "ball_collision_sim/core/friction.hpp"
#include "ball_collision_sim/core/turning_drag.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;
using VL = Eigen::Matrix<long double, 3, 1>;

VL wide(const Vec3& x)
{
  return x.cast<long double>();
}
Vec3 narrow(const VL& x)
{
  return x.cast<double>();
}

/// dq/dt = a - c q/|q| by RK4 in long double, with steps of at most h and at most a
/// tenth of |q| / (|a| + c), until time t or until |q| falls below 1e-12 (then the rest of
/// the way to 0 at the rate along q, and q = 0). Returns q; `integral` its integral,
/// `end` where it reached 0 (infinite where it did not).
VL integrateDrag(const VL& q0, const VL& a, long double c, long double t, VL& integral, long double& end)
{
  const auto f = [&](const VL& q) -> VL { return a - c * q / q.norm(); };
  VL q = q0;
  integral = VL::Zero();
  end = INFINITY;
  long double now = 0;
  while (now < t)
  {
    const long double s = q.norm();
    if (s < 1e-12L)
    {
      const long double rate = c - a.dot(q) / s;
      end = now + s / rate;
      integral += (0.5L * (end - now)) * q;
      q = VL::Zero();
      return q;
    }
    const long double h = std::min({1e-4L, t - now, s / (100 * (a.norm() + c))});
    const VL k1 = f(q), k2 = f(q + 0.5L * h * k1), k3 = f(q + 0.5L * h * k2), k4 = f(q + h * k3);
    // the integral by the same stages (q's RK4 weights applied to q itself)
    integral += (h / 6) * (q + 2 * (q + 0.5L * h * k1) + 2 * (q + 0.5L * h * k2) + (q + h * k3));
    q += (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
    now += h;
  }
  return q;
}

// Random drags in a random plane, lambda = c / |a| from 0.3 to 3: q and its integral at
// times up to 2 s (or the end) and the time q reaches 0.
TEST(TurningDrag, MatchesAnIntegrationOfItsLaw)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), lam(0.3, 3);
  for (int trial = 0; trial < 40; ++trial)
  {
    const Vec3 n = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    const Vec3 a = 3 * unit(rng) * e1 + 3 * unit(rng) * e2;
    const Vec3 q0 = 2 * unit(rng) * e1 + 2 * unit(rng) * e2;
    const double c = lam(rng) * a.norm();
    const TurningDrag drag(q0, a, c);
    ASSERT_TRUE(drag.turns());
    for (double t : {0.01, 0.1, 0.37, 1.0, 2.0})
    {
      VL integral;
      long double end;
      const VL q = integrateDrag(wide(q0), wide(a), c, t, integral, end);
      Vec3 got_q, got_integral;
      drag.at(t, got_q, got_integral);
      EXPECT_LT((got_q - narrow(q)).norm(), 1e-12 * (1 + q0.norm())) << trial << " t " << t;
      EXPECT_LT((got_integral - narrow(integral)).norm(), 1e-12 * (1 + q0.norm())) << trial << " t " << t;
      if (std::isfinite(static_cast<double>(end)))
      {
        EXPECT_NEAR(drag.endTime(), static_cast<double>(end), 1e-11) << trial << " lambda " << c / a.norm();
      }
      else if (c > a.norm())
      {
        EXPECT_GT(drag.endTime(), t);
      }
    }
    if (c <= a.norm())
    {
      EXPECT_TRUE(std::isinf(drag.endTime()));
    }
  }
}

// A slow start that gravity soon outruns (lambda < 1): t(y) grows as an exponential, and
// the time is still turned into y to round-off (a first guess past the largest double).
TEST(TurningDrag, SlowStartOutrunByGravity)
{
  const Vec3 a(4.7260112641172736, 0, 0), q0(3.05e-5, 8.0334006476821135e-05, 0);
  const TurningDrag drag(q0, a, 0.48476699075773633 * a.norm());
  for (double t : {1e-4, 0.048685249592153666, 1.0})
  {
    VL integral;
    long double end;
    const VL q = integrateDrag(wide(q0), wide(a), 0.48476699075773633L * a.norm(), t, integral, end);
    Vec3 got_q, got_integral;
    drag.at(t, got_q, got_integral);
    EXPECT_LT((got_q - narrow(q)).norm(), 1e-12 * (1 + q.norm())) << t;
    EXPECT_LT((got_integral - narrow(integral)).norm(), 1e-12 * (1 + integral.norm())) << t;
  }
}

// A puck whose friction just balances the pull (lambda = 1) reaches the terminal speed
// s0 (1 + cos phi0) / 2, phi0 its start's angle from the fall line (the classic result);
// along the fall line the drag is constant acceleration, and nothing turns.
TEST(TurningDrag, TerminalSpeedAndTheFallLine)
{
  const Vec3 a(0, -2.0, 0);
  for (double phi0 : {0.3, 1.2, 2.5})
  {
    const Vec3 q0 = 1.5 * Vec3(std::sin(phi0), -std::cos(phi0), 0);
    const TurningDrag drag(q0, a, 2.0);
    Vec3 q, integral;
    drag.at(200.0, q, integral);
    EXPECT_NEAR(q.norm(), 1.5 * (1 + std::cos(phi0)) / 2, 1e-6) << phi0;
    EXPECT_TRUE(std::isinf(drag.endTime()));
  }
  // uphill along the line, lambda = 2: s = s0 - (|a| + c) t until s0 / (|a| + c)
  const TurningDrag up(Vec3(0, 1.2, 0), a, 4.0);
  EXPECT_FALSE(up.turns());
  EXPECT_NEAR(up.endTime(), 1.2 / 6.0, 1e-15);
  Vec3 q, integral;
  up.at(0.1, q, integral);
  EXPECT_NEAR(q.y(), 1.2 - 0.6, 1e-15);
  EXPECT_NEAR(integral.y(), 1.2 * 0.1 - 3.0 * 0.01, 1e-15);
}

/// A plane through the origin tilted by `tilt` degrees, falling toward azimuth `azimuth`
/// degrees, 20 m square; its downhill and across directions and normal.
struct Tilted
{
  Vec3 down, across, normal;
  Scene scene;
  Tilted(double tilt, double azimuth, const FrictionDef& f)
  {
    const double a = tilt * M_PI / 180, b = azimuth * M_PI / 180;
    const Vec3 d(std::cos(b), std::sin(b), 0);
    down = std::cos(a) * d - std::sin(a) * Vec3::UnitZ();
    across = Vec3::UnitZ().cross(d);
    normal = std::sin(a) * d + std::cos(a) * Vec3::UnitZ();
    FloorDef floor;
    floor.point = -10 * down - 10 * across;
    floor.u = 20 * down;
    floor.v = 20 * across;
    scene.floor = floor;
    scene.friction = f;
  }
};

/// The friction laws of docs/physics.md for one ball on a plane, integrated by RK4 in
/// long double: sliding while the slip lasts (its end found as integrateDrag() does),
/// then rolling (its stop found the same way) or held.
struct Reference
{
  VL n, g_t;
  long double g_n, mu_s, mu_r, k, r;
  VL p, v, w;  ///< w along the plane; about its normal, normalSpin()
  long double wn0, spin_rate;
  long double now = 0;
  bool sliding = true, still = false;
  long double slip_end = INFINITY, stop = INFINITY;

  Reference(const Tilted& plane, const FrictionDef& f, const BallDef& b, const Vec3& p0)
      : n(wide(plane.normal)), g_n(kG * plane.normal.z()), mu_s(f.sliding), mu_r(f.rolling), k(b.inertia),
        r(b.radius), p(wide(p0)), v(wide(b.velocity)), w(wide(*b.angular_velocity))
  {
    const VL g(0, 0, -kG);
    g_t = g - g.dot(n) * n;
    wn0 = w.dot(n);
    w -= wn0 * n;
    spin_rate = f.spinning * g_n / (k * r);
  }
  /// The spin about the normal, which falls at mu_sp g_n / (k r) to 0 in every state.
  long double normalSpin() const
  {
    const long double left = std::max(0.0L, std::abs(wn0) - spin_rate * now);
    return std::copysign(left, wn0);
  }
  VL spin() const { return still ? VL(normalSpin() * n) : VL(w + normalSpin() * n); }
  VL slip() const { return v + r * n.cross(w); }
  /// d(p, v, w)/dt
  void rates(const VL& vv, const VL& ww, VL& dv, VL& dw) const
  {
    if (sliding)
    {
      const VL u = vv + r * n.cross(ww);
      const VL uh = u / u.norm();
      dv = g_t - mu_s * g_n * uh;
      dw = (mu_s * g_n / (k * r)) * n.cross(uh);
      return;
    }
    dv = g_t / (1 + k) - mu_r * g_n * vv / vv.norm();
    dw = n.cross(dv) / r;
  }
  void advance(long double t)
  {
    while (now < t && !still)
    {
      const VL q = sliding ? slip() : v;
      const long double s = q.norm();
      const long double drag = sliding ? mu_s * g_n * (1 + k) / k : mu_r * g_n;
      const VL pull = sliding ? g_t : VL(g_t / (1 + k));
      if (s < 1e-12L)
      {
        // the rest of the way to 0 at the rate along q, then the next phase
        const long double rest = s / (drag - pull.dot(q) / s);
        VL dv, dw;
        rates(v, w, dv, dw);
        p += rest * v;
        v += rest * dv;
        w += rest * dw;
        now += rest;
        if (sliding)
        {
          slip_end = now;
          sliding = false;
          v -= v.dot(n) * n;
          w = n.cross(v) / r;  // (its slip is gone: rolling's spin)
        }
        else
        {
          stop = now;
          still = true;
          v = w = VL::Zero();
        }
        continue;
      }
      const long double h = std::min({1e-4L, t - now, s / (10 * (pull.norm() + drag))});
      VL a1, b1, a2, b2, a3, b3, a4, b4;
      rates(v, w, a1, b1);
      rates(v + 0.5L * h * a1, w + 0.5L * h * b1, a2, b2);
      rates(v + 0.5L * h * a2, w + 0.5L * h * b2, a3, b3);
      rates(v + h * a3, w + h * b3, a4, b4);
      p += (h / 6) * (v + 2 * (v + 0.5L * h * a1) + 2 * (v + 0.5L * h * a2) + (v + h * a3));
      v += (h / 6) * (a1 + 2 * a2 + 2 * a3 + a4);
      w += (h / 6) * (b1 + 2 * b2 + 2 * b3 + b4);
      now += h;
    }
  }
};

struct Case
{
  double tilt, azimuth, mu_s, mu_r, speed_across, speed_down;
  MotionKind last;  ///< the kind it ends in
  double mu_sp = 0, spin_about_normal = 0;
};

class AcrossTheFallLine : public ::testing::TestWithParam<Case>
{
};

// A ball thrown across the fall line without spin slides, its slip turning toward the fall
// line, until the slip is gone; then it rolls, turning downhill, and rolls on or stops as
// rolling resistance says: every step's end to 1e-9 m and m/s, each phase's end to 1e-9 s.
TEST_P(AcrossTheFallLine, SlidesRollsAndStopsAsTheLawsSay)
{
  const Case c = GetParam();
  const FrictionDef f = friction(c.mu_s, c.mu_r, c.mu_sp);
  Tilted plane(c.tilt, c.azimuth, f);
  BallDef b;
  b.radius = 0.1;
  b.mass = 1;
  b.inertia = kSolidInertia;
  b.position = b.radius * plane.normal;
  b.velocity = c.speed_across * plane.across + c.speed_down * plane.down;
  b.angular_velocity = c.spin_about_normal * plane.normal;
  plane.scene.balls = {b};
  World world(plane.scene);
  Reference ref(plane, f, b, world.balls()[0].position);
  std::vector<MotionTransition> transitions;
  double worst_p = 0, worst_v = 0, worst_w = 0;
  while (world.time() < 3.0 - 1e-9)
  {
    world.step();
    transitions.insert(transitions.end(), world.lastTransitions().begin(), world.lastTransitions().end());
    ref.advance(world.time());
    worst_p = std::max(worst_p, (world.balls()[0].position - narrow(ref.p)).norm());
    worst_v = std::max(worst_v, (world.balls()[0].velocity - narrow(ref.v)).norm());
    worst_w = std::max(worst_w, (world.angularVelocity(0) - narrow(ref.spin())).norm() * b.radius);
  }
  EXPECT_LT(worst_w, 1e-9);
  EXPECT_LT(worst_p, 1e-9);
  EXPECT_LT(worst_v, 1e-9);
  EXPECT_LT((world.angularVelocity(0) - narrow(ref.spin())).norm() * b.radius, 1e-9);
  ASSERT_TRUE(std::isfinite(static_cast<double>(ref.slip_end)));
  ASSERT_GE(transitions.size(), 1u);
  EXPECT_EQ(transitions[0].to, MotionKind::kRolling);
  EXPECT_NEAR(transitions[0].time, static_cast<double>(ref.slip_end), 1e-9);
  EXPECT_EQ(world.motionKind(0), c.last);
  if (c.last == MotionKind::kStationary)
  {
    ASSERT_EQ(transitions.size(), 2u);
    EXPECT_NEAR(transitions[1].time, static_cast<double>(ref.stop), 1e-9);
  }
  else
    EXPECT_EQ(transitions.size(), 1u);
}

// tilt, azimuth, mu_s, mu_r, speed across, speed downhill (negative: uphill), last kind.
// lambda for the slip, mu_s g_n (1 + 1/k) / g_t: 3.97, 6.68, 6.2; for rolling, mu_r g_n
// (1 + k) / g_t: 0.08 (rolls on), 2.67 and 1.49 (stops).
INSTANTIATE_TEST_SUITE_P(
    Planes, AcrossTheFallLine,
    ::testing::Values(Case{10, 0, 0.2, 0.01, 1.5, 0.0, MotionKind::kRolling},
                      Case{3, 37, 0.1, 0.1, 1.0, -0.4, MotionKind::kStationary},
                      Case{8, 210, 0.25, 0.15, -2.0, 0.5, MotionKind::kStationary},
                      // spinning about the normal too, which dies while it slides
                      Case{10, 120, 0.2, 0.01, 1.2, -0.3, MotionKind::kRolling, 0.044, 15.0}));
}  // namespace
