// A ball's motion on a curved floor as FloorFlow integrates it: against an integration of
// the same laws in long double at steps 64 times shorter (a paraboloid bowl, a saddle and
// a dome's crest), its order of convergence (4), the energy and the angular momentum
// about the bowl's axis kept, and the small-oscillation periods in the bowl,
// 2 pi sqrt((R - r) / g) frictionless and 2 pi sqrt((1 + k)(R - r) / g) rolling.
#include "fixtures.hpp"

#include "ball_collision_sim/core/floor_flow.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ball_collision_sim::core;
using namespace ball_collision_sim::test;

namespace
{
constexpr double kG = 9.81;
const Vec3 kGravity(0, 0, -kG);

/// The flow's own law once more, in long double, from the floor's derivatives: a
/// reference integrated by classical Runge-Kutta at many more, shorter steps.
struct Reference
{
  using V3 = Eigen::Matrix<long double, 3, 1>;
  using V2 = Eigen::Matrix<long double, 2, 1>;
  using M2 = Eigen::Matrix<long double, 2, 2>;
  const Floor& floor;
  long double r, share, drag;

  void rates(const V2& uv, const V3& v, V2& foot_rate, V3& acc) const
  {
    Vec3 s, su_d, sv_d, suu_d, suv_d, svv_d;
    floor.derivatives(uv.cast<double>(), s, su_d, sv_d, suu_d, suv_d, svv_d);
    // (a biquadratic's derivatives are exact in double at these parameters' round-off;
    // the rest is done wide)
    const V3 su = su_d.cast<long double>(), sv = sv_d.cast<long double>();
    V3 n = su.cross(sv).normalized();
    if (n.z() < 0)
      n = -n;
    M2 first, second;
    first << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    second << suu_d.cast<long double>().dot(n), suv_d.cast<long double>().dot(n), suv_d.cast<long double>().dot(n),
        svv_d.cast<long double>().dot(n);
    const V2 b(su.dot(v), sv.dot(v));
    foot_rate = (first - r * second).inverse() * b;
    const long double push = (first.inverse() * b).dot(second * foot_rate);
    const V3 g(0, 0, -kG);
    const long double g_n = -g.dot(n);
    const V3 g_t = g + g_n * n;
    acc = share * g_t + push * n;
    const V3 along = v - v.dot(n) * n;
    if (drag > 0 && along.norm() > 0)
      acc -= (drag * g_n / along.norm()) * along;
  }
  void advance(V2& uv, V3& v, long double duration, int steps) const
  {
    const long double h = duration / steps;
    for (int k = 0; k < steps; ++k)
    {
      V2 f1, f2, f3, f4;
      V3 a1, a2, a3, a4;
      rates(uv, v, f1, a1);
      rates(uv + h / 2 * f1, v + h / 2 * a1, f2, a2);
      rates(uv + h / 2 * f2, v + h / 2 * a2, f3, a3);
      rates(uv + h * f3, v + h * a3, f4, a4);
      uv += h / 6 * (f1 + 2 * f2 + 2 * f3 + f4);
      v += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    }
  }
};

/// The flow's law of gravity's share (1: free, 1 / (1 + k): rolling) and rolling drag.
FloorFlow::Law lawOf(double share, double drag)
{
  FloorFlow::Law law;
  if (share < 1)
  {
    law.kind = FloorFlow::Kind::kRolling;
    law.inertia = 1 / share - 1;
    law.rolling = drag;
  }
  return law;
}

/// `s` advanced by `duration` as the step does: where a phase ends on the way (a rolling
/// ball's speed reaching 0), the end made exact (FrictionLaw::finish()) and on.
void advanceThrough(const FloorFlow& flow, FloorFlow::State& s, double duration, int substeps,
                    const FloorFlow::Law& law)
{
  double left = duration;
  for (int ends = 0; left > 0 && ends < 100; ++ends)
  {
    const FloorFlow::End e = flow.advance(s, left, std::max(1, static_cast<int>(std::ceil(substeps * left / duration))), law, 0.05, 256);
    left -= e.time;
    if (e.ends & kBallStops)
      s.velocity = Vec3::Zero();
    if (e.ends & kSpinStops)
      s.spin_n = 0;
  }
}

/// A ball of radius r where `flow` puts its centre over `start`'s foot point, at its
/// velocity; the floor's normal there in `normal`.
BallDef ballAt(const FloorFlow& flow, const FloorFlow::State& start, double r, Vec3* normal = nullptr)
{
  BallDef b;
  b.radius = r;
  b.position = flow.centre(start.foot, normal);
  b.velocity = start.velocity;
  return b;
}

/// A start on the floor at foot (u, v) with velocity w along it.
FloorFlow::State startAt(const Floor& floor, const Vec2& foot, const Vec3& w)
{
  const Vec3 n = floor.normal(foot);
  return {foot, w - w.dot(n) * n};
}

struct FlowCase
{
  const char* name;
  FloorDef floor;
  Vec2 foot;
  Vec3 velocity;
  double share, drag;
};

class FlowAgainstReference : public ::testing::TestWithParam<FlowCase>
{
};

// After 1 s, 100 steps of dt = 0.01 s each in the substeps FloorFlow::substepsFor() gives
// for a turn of 0.05 rad, within 1e-8 m and m/s of the reference (about 1e-9 here); and in
// one substep a step, halving it divides the error by about 16 (fourth order).
TEST_P(FlowAgainstReference, WithinANanometreAfterOneSecond)
{
  const FlowCase c = GetParam();
  const Floor floor(c.floor, kGravity);
  const double r = 0.1;
  const FloorFlow flow(floor, kGravity, r);
  const FloorFlow::Law law = lawOf(c.share, c.drag);
  const FloorFlow::State start = startAt(floor, c.foot, c.velocity);
  const auto run = [&](double dt, int substeps_cap) {
    FloorFlow::State s = start;
    for (int k = 0; k < static_cast<int>(std::lround(1.0 / dt)); ++k)
    {
      const int n = substeps_cap > 0 ? substeps_cap
                                     : FloorFlow::substepsFor(dt, s.velocity.norm(), floor.maxCurvature() / (1 - r * floor.maxCurvature()), kG, 0.05);
      advanceThrough(flow, s, dt, n, law);
    }
    return s;
  };
  Reference ref{floor, r, c.share, c.drag};
  Reference::V2 uv = start.foot.cast<long double>();
  Reference::V3 v = start.velocity.cast<long double>();
  ref.advance(uv, v, 1.0L, 6400);
  const Vec3 ref_p = flow.centre(uv.cast<double>());
  const Vec3 ref_v = v.cast<double>();

  const FloorFlow::State got = run(0.01, 0);
  EXPECT_LT((flow.centre(got.foot) - ref_p).norm(), 1e-8) << c.name;
  EXPECT_LT((got.velocity - ref_v).norm(), 1e-8) << c.name;

  const double e1 = (flow.centre(run(0.01, 1).foot) - ref_p).norm();
  const double e2 = (flow.centre(run(0.005, 1).foot) - ref_p).norm();
  const double order = std::log2(e1 / e2);
  EXPECT_GT(order, 3.7) << c.name << " errors " << e1 << " " << e2;
  EXPECT_LT(order, 4.3) << c.name << " errors " << e1 << " " << e2;
  std::printf("%s: error after 1 s %.3g m (flow), one substep a step %.3g, at dt / 2 %.3g: order %.2f\n", c.name,
              (flow.centre(got.foot) - ref_p).norm(), e1, e2, order);
}

INSTANTIATE_TEST_SUITE_P(
    Floors, FlowAgainstReference,
    ::testing::Values(FlowCase{"bowl_free", bowl(3, 0.3), Vec2(0.8, 0.4), Vec3(-1.0, 1.5, 0), 1.0, 0.0},
                      FlowCase{"bowl_rolling", bowl(3, 0.3), Vec2(0.8, 0.4), Vec3(-1.0, 1.5, 0), 1 / 1.4, 0.0},
                      FlowCase{"bowl_resisted", bowl(3, 0.3), Vec2(0.8, 0.4), Vec3(-1.0, 1.5, 0), 1 / 1.4, 0.01},
                      FlowCase{"saddle_free", saddle(0.3), Vec2(0.45, 0.5), Vec3(1.5, 0.8, 0), 1.0, 0.0},
                      FlowCase{"saddle_rolling", saddle(0.3), Vec2(0.45, 0.5), Vec3(1.5, 0.8, 0), 1 / 1.4, 0.01},
                      FlowCase{"crest_free", dome(), Vec2(0.5, 0.52), Vec3(0.4, 0.3, 0), 1.0, 0.0},
                      FlowCase{"crest_rolling", dome(), Vec2(0.5, 0.52), Vec3(0.4, 0.3, 0), 1 / 1.4, 0.01}),
    [](const auto& info) { return std::string(info.param.name); });

// In the paraboloid bowl z = a (x^2 + y^2) a frictionless ball keeps its energy and its
// angular momentum about the axis (a surface of revolution): over 10 s to 2e-9 (fourth
// order drifts: the step takes a free ball's speed from its energy).
TEST(FloorFlow, BowlKeepsEnergyAndAngularMomentum)
{
  const Floor floor(bowl(3, 0.3), kGravity);
  const double r = 0.1;
  const FloorFlow flow(floor, kGravity, r);
  FloorFlow::State s = startAt(floor, Vec2(0.75, 0.5), Vec3(0, 1.2, 0));
  const auto energy = [&](const FloorFlow::State& st) { return 0.5 * st.velocity.squaredNorm() + kG * flow.centre(st.foot).z(); };
  const auto spin = [&](const FloorFlow::State& st) {
    const Vec3 p = flow.centre(st.foot);
    return p.x() * st.velocity.y() - p.y() * st.velocity.x();
  };
  const double e0 = energy(s), l0 = spin(s);
  for (int k = 0; k < 1000; ++k)
    flow.advance(s, 0.01, FloorFlow::substepsFor(0.01, s.velocity.norm(), 0.3, kG, 0.05), FloorFlow::Law{}, 0.05, 256);
  EXPECT_NEAR(energy(s), e0, 2e-9);
  EXPECT_NEAR(spin(s), l0, 2e-9);
  EXPECT_GT(flow.centre(s.foot).norm(), 0.2);  // (it went round, off the bottom)
}

// Small oscillations in the bowl (radius of curvature R = 1 / (2 a) at its bottom, the
// centre's path R - r): the period of x's swing, from its zero crossings over three
// periods, frictionless and rolling (the share 1 / (1 + k)).
TEST(FloorFlow, SmallOscillationPeriodsInTheBowl)
{
  const double L = 3, h = 0.3, a = 4 * h / (L * L), R = 1 / (2 * a), r = 0.1, k = 0.4;
  const Floor floor(bowl(L, h), kGravity);
  const FloorFlow flow(floor, kGravity, r);
  for (double share : {1.0, 1 / (1 + k)})
  {
    const double expected = 2 * M_PI * std::sqrt((R - r) / (share * kG));
    FloorFlow::State s = startAt(floor, Vec2(0.5 + 0.003, 0.5), Vec3::Zero());  // 9 mm off the bottom
    double t = 0, previous = flow.centre(s.foot).x();
    std::vector<double> crossings;
    const double dt = 1e-3;
    while (crossings.size() < 7)
    {
      advanceThrough(flow, s, dt, 1, lawOf(share, 0.0));
      t += dt;
      const double x = flow.centre(s.foot).x();
      if ((previous > 0) != (x > 0))
        crossings.push_back(t - dt * x / (x - previous));  // (the crossing, by the chord)
      previous = x;
    }
    const double period = (crossings[6] - crossings[0]) / 3;
    EXPECT_NEAR(period, expected, 1e-5 * expected) << share;
  }
}
}  // namespace

namespace
{
struct WorldCase
{
  const char* name;
  FloorDef floor;
  Vec2 foot;
  Vec3 velocity;
  bool friction;  ///< a friction block that holds rolling (mu_s 0.5), mu_r 0.01
};

class WorldOnCurvedFloors : public ::testing::TestWithParam<WorldCase>
{
};

// Through World at dt = 0.01 s: a frictionless ball (no friction block) and a rolling one
// (a friction block that holds rolling, rolling resistance 0.01) after 1 s within 1e-6 m
// and m/s of the reference (1e-8 here), on the bowl, the saddle and the crest.
TEST_P(WorldOnCurvedFloors, WithinAMicrometreAfterOneSecond)
{
  const WorldCase c = GetParam();
  const double r = 0.1, k = kSolidInertia;
  Scene scene;
  scene.floor = c.floor;
  const Floor floor(c.floor, kGravity);
  const FloorFlow flow(floor, kGravity, r);
  const FloorFlow::State start = startAt(floor, c.foot, c.velocity);
  BallDef b = ballAt(flow, start, r);
  if (c.friction)
  {
    scene.friction = friction(0.5, 0.01);
    b.inertia = k;  // (its spin: rolling's, n x v / r)
  }
  scene.balls = {b};
  World world(scene);
  for (int s = 0; s < 100; ++s)
    world.step();
  Reference ref{floor, r, c.friction ? 1 / (1 + k) : 1.0, c.friction ? 0.01 : 0.0};
  Reference::V2 uv = start.foot.cast<long double>();
  Reference::V3 v = start.velocity.cast<long double>();
  ref.advance(uv, v, 1.0L, 6400);
  const double dp = (world.balls()[0].position - flow.centre(uv.cast<double>())).norm();
  const double dv = (world.balls()[0].velocity - v.cast<double>()).norm();
  EXPECT_LT(dp, 1e-8) << c.name;
  EXPECT_LT(dv, 1e-8) << c.name;
  if (c.friction)
  {
    EXPECT_EQ(world.motionKind(0), MotionKind::kRolling);
  }
  std::printf("%s through World: %.3g m, %.3g m/s after 1 s\n", c.name, dp, dv);
}

// The small-oscillation periods through World at dt = 0.01 s: a ball let go at rest 9 mm
// off the bowl's bottom, frictionless (no friction block) and rolling (a friction block
// that holds rolling, no rolling resistance), swings with the period 2 pi sqrt((R - r) /
// g), and 2 pi sqrt((1 + k)(R - r) / g) rolling, to 1e-5 over five periods; x's zero
// crossings found between step ends by the cubic that meets x and its rate at both.
TEST(WorldOnCurvedFloor, SmallOscillationPeriodsInTheBowl)
{
  const double L = 3, h = 0.3, a = 4 * h / (L * L), R = 1 / (2 * a), r = 0.1;
  const Floor floor(bowl(L, h), kGravity);
  const FloorFlow flow(floor, kGravity, r);
  for (const double k : {0.0, kSolidInertia, kHollowInertia})
  {
    Scene scene;
    scene.floor = bowl(L, h);
    BallDef b = ballAt(flow, startAt(floor, Vec2(0.5 + 0.003, 0.5), Vec3::Zero()), r);
    if (k > 0)
    {
      scene.friction = friction(0.5, 0.0);
      b.inertia = k;
    }
    scene.balls = {b};
    World world(scene);
    const double expected = 2 * M_PI * std::sqrt((1 + k) * (R - r) / kG);
    std::vector<double> crossings;
    double x0 = world.balls()[0].position.x(), v0 = world.balls()[0].velocity.x();
    while (crossings.size() < 11)
    {
      const double t0 = world.time();
      world.step();
      const double dt = world.time() - t0;
      const double x1 = world.balls()[0].position.x(), v1 = world.balls()[0].velocity.x();
      if ((x0 > 0) != (x1 > 0))
      {
        // (Hermite's cubic on [0, 1] through x0, x1 with slopes v0 dt, v1 dt; Newton from
        // the chord's crossing)
        double s = x0 / (x0 - x1);
        for (int it = 0; it < 20; ++it)
        {
          const double s2 = s * s, s3 = s2 * s;
          const double p = (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * v0 * dt + (-2 * s3 + 3 * s2) * x1 +
                           (s3 - s2) * v1 * dt;
          const double dp = (6 * s2 - 6 * s) * x0 + (3 * s2 - 4 * s + 1) * v0 * dt + (-6 * s2 + 6 * s) * x1 +
                            (3 * s2 - 2 * s) * v1 * dt;
          s -= p / dp;
        }
        crossings.push_back(t0 + s * dt);
      }
      x0 = x1;
      v0 = v1;
    }
    const double period = (crossings[10] - crossings[0]) / 5;
    EXPECT_NEAR(period, expected, 1e-5 * expected) << "k " << k;
    std::printf("k %.3f: period %.9f s, expected %.9f s (%.2g)\n", k, period, expected, period / expected - 1);
  }
}

INSTANTIATE_TEST_SUITE_P(Floors, WorldOnCurvedFloors,
                         ::testing::Values(WorldCase{"bowl_free", bowl(3, 0.3), Vec2(0.8, 0.4), Vec3(-1.0, 1.5, 0), false},
                                           WorldCase{"bowl_rolling", bowl(3, 0.3), Vec2(0.8, 0.4), Vec3(-1.0, 1.5, 0), true},
                                           WorldCase{"saddle_free", saddle(0.3), Vec2(0.45, 0.5), Vec3(1.5, 0.8, 0), false},
                                           WorldCase{"saddle_rolling", saddle(0.3), Vec2(0.45, 0.5), Vec3(1.5, 0.8, 0), true},
                                           WorldCase{"crest_free", dome(), Vec2(0.5, 0.52), Vec3(0.4, 0.3, 0), false},
                                           WorldCase{"crest_rolling", dome(), Vec2(0.5, 0.52), Vec3(0.4, 0.3, 0), true}),
                         [](const auto& info) { return std::string(info.param.name); });
}  // namespace

namespace
{
/// The friction laws on a curved floor once more, in long double: a ball sliding (its spin
/// along the floor turned by friction and carried along the floor as the normal turns)
/// until its slip is gone, then rolling under rolling resistance, the spin about the
/// normal falling at mu_sp g_n / (k r) in both; RK4 at steps of at most 1e-5 s and a
/// hundredth of the time the slip's rates give it near its end, the end where the slip
/// is below 1e-13 m/s (the rest of the way at its rate); the spin about the normal stops
/// at 0 within a step.
struct FrictionReference
{
  using V3 = Eigen::Matrix<long double, 3, 1>;
  using V2 = Eigen::Matrix<long double, 2, 1>;
  using M2 = Eigen::Matrix<long double, 2, 2>;
  const Floor& floor;
  long double r, k, mu_s, mu_r, mu_sp;
  V2 foot;
  V3 v, w;              ///< w along the floor
  long double w_n = 0;  ///< about the normal
  long double now = 0, slip_end = INFINITY;
  bool sliding = true;

  struct Geometry
  {
    V3 n, su, sv;
    M2 first, second;
  };
  Geometry at(const V2& uv) const
  {
    Vec3 s, su, sv, suu, suv, svv;
    floor.derivatives(uv.cast<double>(), s, su, sv, suu, suv, svv);
    Geometry g;
    g.su = su.cast<long double>();
    g.sv = sv.cast<long double>();
    g.n = g.su.cross(g.sv).normalized();
    if (g.n.z() < 0)
      g.n = -g.n;
    g.first << g.su.dot(g.su), g.su.dot(g.sv), g.su.dot(g.sv), g.sv.dot(g.sv);
    g.second << suu.cast<long double>().dot(g.n), suv.cast<long double>().dot(g.n), suv.cast<long double>().dot(g.n),
        svv.cast<long double>().dot(g.n);
    return g;
  }
  /// d(foot, v, w, w_n)/dt
  void rates(const V2& uv, const V3& vv, const V3& ww, long double wn, V2& df, V3& dv, V3& dw, long double& dwn) const
  {
    const Geometry g = at(uv);
    const V3 vt = vv - vv.dot(g.n) * g.n;
    const V2 b(g.su.dot(vt), g.sv.dot(vt));
    df = (g.first - r * g.second).inverse() * b;
    const long double push = (g.first.inverse() * b).dot(g.second * df);
    const V3 grav(0, 0, -kG);
    const long double g_n = -grav.dot(g.n);
    const V3 g_t = grav + g_n * g.n;
    const V2 bend = g.first.inverse() * (g.second * df);
    const V3 n_rate = -(bend.x() * g.su + bend.y() * g.sv);
    dwn = wn > 0 ? -mu_sp * g_n / (k * r) : (wn < 0 ? mu_sp * g_n / (k * r) : 0);
    if (sliding)
    {
      const V3 u = vt + r * g.n.cross(ww);
      const V3 uh = u / u.norm();
      dv = g_t - mu_s * g_n * uh + push * g.n;
      dw = (mu_s * g_n / (k * r)) * g.n.cross(uh) - ww.dot(n_rate) * g.n;
    }
    else
    {
      dv = g_t / (1 + k) - mu_r * g_n * vt / vt.norm() + push * g.n;
      dw = V3::Zero();  // (rolling's spin along the floor follows from v)
    }
  }
  void step(long double h)
  {
    V2 f1, f2, f3, f4;
    V3 a1, a2, a3, a4, b1, b2, b3, b4;
    long double c1, c2, c3, c4;
    rates(foot, v, w, w_n, f1, a1, b1, c1);
    rates(foot + h / 2 * f1, v + h / 2 * a1, w + h / 2 * b1, w_n + h / 2 * c1, f2, a2, b2, c2);
    rates(foot + h / 2 * f2, v + h / 2 * a2, w + h / 2 * b2, w_n + h / 2 * c2, f3, a3, b3, c3);
    rates(foot + h * f3, v + h * a3, w + h * b3, w_n + h * c3, f4, a4, b4, c4);
    foot += h / 6 * (f1 + 2 * f2 + 2 * f3 + f4);
    v += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    w += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
    const long double wn = w_n + h / 6 * (c1 + 2 * c2 + 2 * c3 + c4);
    w_n = (wn > 0) == (w_n > 0) ? wn : 0;  // (it stops at 0, and stays)
    now += h;
  }
  void advance(long double t)
  {
    while (now < t)
    {
      long double h = std::min(1e-5L, t - now);
      if (sliding)
      {
        const Geometry g = at(foot);
        const V3 u = v - v.dot(g.n) * g.n + r * g.n.cross(w);
        V2 df;
        V3 dv, dw;
        long double dwn;
        rates(foot, v, w, w_n, df, dv, dw, dwn);
        const V3 du = dv + r * g.n.cross(dw);
        const long double shrink = -u.dot(du) / u.norm();
        if (u.norm() < 1e-13L)
        {
          // the slip's end: the rest of the way at its rate, then rolling
          const long double rest = shrink > 0 ? u.norm() / shrink : 0;
          step(rest);
          slip_end = now;
          sliding = false;
          const Geometry e = at(foot);
          v -= v.dot(e.n) * e.n;
          continue;
        }
        if (shrink > 0)
          h = std::min(h, u.norm() / shrink / 100);
      }
      step(h);
    }
  }
  Vec3 spin() const
  {
    const Geometry g = at(foot);
    return sliding ? Vec3((w + w_n * g.n).cast<double>()) : Vec3((g.n.cross(v) / r + w_n * g.n).cast<double>());
  }
};

struct SlideCase
{
  const char* name;
  FloorDef floor;
  Vec2 foot;
  Vec3 velocity;
  double spin_about_normal;
};

class SlidingOnCurvedFloors : public ::testing::TestWithParam<SlideCase>
{
};

// Struck without spin along the floor (sliding 0.2, rolling 0.01, spinning 0.044): through
// World at dt = 0.01 s the ball slides until its slip is gone, at the reference's time to
// 1e-9 s, and rolls on; after 1 s within 1e-8 m and m/s, its spin within 1e-8 m/s (times
// r), of the reference, on the bowl, the saddle and the crest.
TEST_P(SlidingOnCurvedFloors, SlipsEndAndRollAsTheReference)
{
  const SlideCase c = GetParam();
  const double r = 0.05, k = kSolidInertia;
  Scene scene;
  scene.floor = c.floor;
  const FrictionDef f = pileFriction();
  scene.friction = f;
  const Floor floor(c.floor, kGravity);
  const FloorFlow flow(floor, kGravity, r);
  const FloorFlow::State start = startAt(floor, c.foot, c.velocity);
  Vec3 n;
  BallDef b = ballAt(flow, start, r, &n);
  b.inertia = k;
  b.angular_velocity = c.spin_about_normal * n;
  scene.balls = {b};
  World world(scene);
  std::vector<MotionTransition> transitions;
  for (int s = 0; s < 100; ++s)
  {
    world.step();
    transitions.insert(transitions.end(), world.lastTransitions().begin(), world.lastTransitions().end());
  }
  FrictionReference ref{floor, r, k, f.sliding, f.rolling, f.spinning, start.foot.cast<long double>(),
                        start.velocity.cast<long double>(), FrictionReference::V3::Zero(), c.spin_about_normal};
  ref.advance(1.0L);
  ASSERT_FALSE(ref.sliding) << c.name;
  ASSERT_EQ(transitions.size(), 1u) << c.name;
  EXPECT_EQ(transitions[0].to, MotionKind::kRolling);
  EXPECT_NEAR(transitions[0].time, static_cast<double>(ref.slip_end), 1e-9) << c.name;
  const double dp = (world.balls()[0].position - flow.centre(ref.foot.cast<double>())).norm();
  const double dv = (world.balls()[0].velocity - ref.v.cast<double>()).norm();
  const double dw = (world.angularVelocity(0) - ref.spin()).norm() * r;
  EXPECT_LT(dp, 1e-8) << c.name;
  EXPECT_LT(dv, 1e-8) << c.name;
  EXPECT_LT(dw, 1e-8) << c.name;
  std::printf("%s: slip's end %.3g s off, after 1 s %.3g m, %.3g m/s, spin %.3g m/s\n", c.name,
              transitions[0].time - static_cast<double>(ref.slip_end), dp, dv, dw);
}

INSTANTIATE_TEST_SUITE_P(
    Floors, SlidingOnCurvedFloors,
    ::testing::Values(SlideCase{"bowl", bowl(3, 0.3), Vec2(0.7667, 0.5667), Vec3(1.5, 0.5, 0), 0.0},
                      SlideCase{"bowl_spinning", bowl(3, 0.3), Vec2(0.7667, 0.5667), Vec3(1.5, 0.5, 0), 30.0},
                      SlideCase{"bowl_from_rest_across", bowl(3, 0.3), Vec2(0.7667, 0.5667), Vec3(0, 0.5, 0), 0.0},
                      SlideCase{"saddle", saddle(0.3), Vec2(0.45, 0.5), Vec3(1.5, 0.8, 0), 10.0},
                      SlideCase{"crest", dome(), Vec2(0.5, 0.52), Vec3(0.6, 0.3, 0), 0.0}),
    [](const auto& info) { return std::string(info.param.name); });
}  // namespace
