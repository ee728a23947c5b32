// Runs the benchmark scenes S1 (billiards) and S2 (bullets) in ODE, Bullet, Box2D and this
// package's core in one run and writes one CSV row per engine, scene and ball count:
//
//   engine,scene,balls,steps,median_ns_per_ball_step,kinetic_end_over_start,max_overlap_m,escaped
//
// Every engine gets the very same balls (bench/scenes.hpp) and dt = 0.01 s. The peers get
// their fairest settings (see bench/compare_peers.md): restitution 1 with no restitution
// velocity threshold, no friction, no damping, no sleeping, balls kept in the plane.
//
// Usage: compare_peers [--sizes 1000,10000,100000] [--seconds 10] [--budget 20]
//                      [--engines ball_collision_sim,ode,bullet,box2d] [--scenes S1,S2]
//                      [--out file.csv] [--bullet-spec-restitution 0|1]
//
// --seconds is the simulated time of S1 (S2 is always 1 s, as the issue says). --budget is
// the wall time [s] one engine may spend stepping one scene: an engine stops after the first
// step that ends past it, and the steps column says how many steps were run; the kinetic
// energy ratio, overlap and escaped count are those at the end of the steps actually run.
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <box2d/box2d.h>
#include <btBulletDynamicsCommon.h>
#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ball_collision_sim::core::Scene;
using ball_collision_sim::core::Vec3;
using Clock = std::chrono::steady_clock;

/// Thickness given to the scene's zero-thickness walls where an engine needs a solid
/// (ODE and Bullet boxes). The box lies outside the wall's plane, so its inner face is the
/// scene's wall exactly; "thin" as in the issue: a quarter of the S1 ball's diameter.
constexpr double kWallThickness = 0.025;

/// A ball's state in the plane, as every engine reports it at the end.
struct Disc
{
  double x, y, r;
};

/// What an engine must offer: one step, and its balls' positions and kinetic energy.
class Engine
{
public:
  virtual ~Engine() = default;
  virtual void step() = 0;
  virtual std::vector<Disc> discs() const = 0;
  virtual double kinetic() const = 0;
};

/// The side of the square box of a bench scene: the walls span [0, side]^2.
double sideOf(const Scene& scene)
{
  return scene.floor->u.norm();
}

/// Box [lo, hi] of an axis-aligned wall of the scene, thickened by kWallThickness to the
/// outside of the box (centre `c`) and at both ends so the corners are closed.
void wallBox(const ball_collision_sim::core::WallDef& w, double c, Vec3& lo, Vec3& hi)
{
  const Vec3 a = w.point, b = w.point + w.u + w.v;
  lo = a.cwiseMin(b);
  hi = a.cwiseMax(b);
  const int n = std::abs(hi.x() - lo.x()) < 1e-12 ? 0 : 1;  // the wall's normal axis
  const int t = 1 - n;                                        // its horizontal tangent axis
  if (lo[n] < c)
    lo[n] -= kWallThickness;
  else
    hi[n] += kWallThickness;
  lo[t] -= kWallThickness;
  hi[t] += kWallThickness;
}

// ---------------------------------------------------------------------------------------
// This package's core: just another engine.
class CoreEngine : public Engine
{
public:
  explicit CoreEngine(const Scene& scene) : world_(scene) {}
  void step() override { world_.step(); }
  std::vector<Disc> discs() const override
  {
    std::vector<Disc> out;
    out.reserve(world_.balls().size());
    for (const auto& b : world_.balls())
      out.push_back({b.position.x(), b.position.y(), b.radius});
    return out;
  }
  double kinetic() const override { return world_.energy().kinetic; }

private:
  ball_collision_sim::core::World world_;
};

// ---------------------------------------------------------------------------------------
// ODE: quickstep, sweep-and-prune space, bouncy frictionless contacts, z velocity zeroed.
class OdeEngine : public Engine
{
public:
  OdeEngine(const Scene& scene, bool /*ccd: ODE has none for spheres*/) : dt_(scene.dt)
  {
    world_ = dWorldCreate();
    // Gravity is normal to the floor and the balls are kept in the plane, so it would do
    // no work: the peers get neither gravity nor a floor (no N floor contacts per step).
    dWorldSetGravity(world_, 0, 0, 0);
    dWorldSetAutoDisableFlag(world_, 0);
    space_ = dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ);
    contacts_ = dJointGroupCreate(0);
    const double c = sideOf(scene) / 2;
    for (const auto& w : scene.walls)
    {
      Vec3 lo, hi;
      wallBox(w, c, lo, hi);
      const Vec3 size = hi - lo, mid = (lo + hi) / 2;
      dGeomID g = dCreateBox(space_, size.x(), size.y(), size.z());
      dGeomSetPosition(g, mid.x(), mid.y(), mid.z());
    }
    for (const auto& b : scene.balls)
    {
      dBodyID body = dBodyCreate(world_);
      dMass m;
      dMassSetSphereTotal(&m, b.mass, b.radius);
      dBodySetMass(body, &m);
      dBodySetPosition(body, b.position.x(), b.position.y(), b.radius);
      dBodySetLinearVel(body, b.velocity.x(), b.velocity.y(), 0);
      dGeomID g = dCreateSphere(space_, b.radius);
      dGeomSetBody(g, body);
      bodies_.push_back(body);
      radii_.push_back(b.radius);
      masses_.push_back(b.mass);
    }
  }
  ~OdeEngine() override
  {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys its geoms (cleanup mode on by default)
    dWorldDestroy(world_);
  }

  void step() override
  {
    dSpaceCollide(space_, this, &OdeEngine::nearCallback);
    dWorldQuickStep(world_, dt_);
    dJointGroupEmpty(contacts_);
    // keep the balls in the plane: cheaper than a plane-2D joint per ball (no extra rows
    // in the solver), and contact normals are horizontal, so this removes only round-off.
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
      const dReal* v = dBodyGetLinearVel(bodies_[i]);
      if (v[2] != 0)
        dBodySetLinearVel(bodies_[i], v[0], v[1], 0);
      const dReal* p = dBodyGetPosition(bodies_[i]);
      if (p[2] != radii_[i])
        dBodySetPosition(bodies_[i], p[0], p[1], radii_[i]);
    }
  }

  std::vector<Disc> discs() const override
  {
    std::vector<Disc> out;
    out.reserve(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
      const dReal* p = dBodyGetPosition(bodies_[i]);
      out.push_back({p[0], p[1], radii_[i]});
    }
    return out;
  }
  double kinetic() const override
  {
    double k = 0;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
      const dReal* v = dBodyGetLinearVel(bodies_[i]);
      k += 0.5 * masses_[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    return k;
  }

private:
  static void nearCallback(void* data, dGeomID o1, dGeomID o2)
  {
    auto* self = static_cast<OdeEngine*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2)
      return;  // wall against wall
    dContact contact{};
    if (dCollide(o1, o2, 1, &contact.geom, sizeof(dContact)) == 0)
      return;
    contact.surface.mode = dContactBounce;
    contact.surface.mu = 0;          // no friction
    contact.surface.bounce = 1;      // restitution 1
    contact.surface.bounce_vel = 0;  // ... at every closing speed
    dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact);
    dJointAttach(j, b1, b2);
  }

  double dt_;
  dWorldID world_;
  dSpaceID space_;
  dJointGroupID contacts_;
  std::vector<dBodyID> bodies_;
  std::vector<double> radii_, masses_;
};

// ---------------------------------------------------------------------------------------
// Bullet: DBVT broad phase, sequential impulse solver, CCD in S2.
class BulletEngine : public Engine
{
public:
  BulletEngine(const Scene& scene, bool ccd, bool spec_restitution)
    : dispatcher_(&config_), world_(&dispatcher_, &broadphase_, &solver_, &config_), dt_(scene.dt)
  {
    world_.setGravity(btVector3(0, 0, 0));  // see OdeEngine: gravity would do no work
    btContactSolverInfo& solver = world_.getSolverInfo();
    solver.m_restitutionVelocityThreshold = 0;  // bounce at every closing speed (default 0.2)
    // Penetration is always undone by split impulse (position only), never by Baumgarte
    // feedback into the velocity: by default penetrations shallower than 0.04 m are fed
    // back into the velocity and every bouncing contact gains energy (a head-on pair at
    // 2 m/s leaves at 2.4 m/s; S1 then heats up 30-fold in 2 s).
    solver.m_splitImpulse = true;
    solver.m_splitImpulsePenetrationThreshold = 1e30f;
    const double c = sideOf(scene) / 2;
    for (const auto& w : scene.walls)
    {
      Vec3 lo, hi;
      wallBox(w, c, lo, hi);
      const Vec3 half = (hi - lo) / 2, mid = (lo + hi) / 2;
      auto box = std::make_unique<btBoxShape>(btVector3(half.x(), half.y(), half.z()));
      // The default margin (0.04 m) is embedded in the box and must not exceed a half
      // extent: thin walls get a margin of a fifth of their half thickness.
      box->setMargin(std::min<btScalar>(box->getMargin(), 0.2 * std::min({half.x(), half.y(), half.z()})));
      shapes_.push_back(std::move(box));
      btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
      info.m_startWorldTransform.setOrigin(btVector3(mid.x(), mid.y(), mid.z()));
      info.m_restitution = 1;
      info.m_friction = 0;
      walls_.push_back(std::make_unique<btRigidBody>(info));
      world_.addRigidBody(walls_.back().get());
    }
    for (const auto& b : scene.balls)
    {
      if (shapes_.size() == walls_.size() || spheres_radius_ != b.radius)
      {
        shapes_.push_back(std::make_unique<btSphereShape>(b.radius));
        spheres_radius_ = b.radius;
      }
      btCollisionShape* shape = shapes_.back().get();
      btVector3 inertia(0, 0, 0);
      shape->calculateLocalInertia(b.mass, inertia);
      btRigidBody::btRigidBodyConstructionInfo info(b.mass, nullptr, shape, inertia);
      info.m_startWorldTransform.setOrigin(btVector3(b.position.x(), b.position.y(), b.radius));
      info.m_restitution = 1;
      info.m_friction = 0;
      info.m_rollingFriction = 0;
      info.m_spinningFriction = 0;
      info.m_linearDamping = 0;
      info.m_angularDamping = 0;
      auto body = std::make_unique<btRigidBody>(info);
      body->setLinearVelocity(btVector3(b.velocity.x(), b.velocity.y(), 0));
      body->setLinearFactor(btVector3(1, 1, 0));  // stay in the plane
      body->setActivationState(DISABLE_DEACTIVATION);
      if (ccd)
      {
        // off by default: then CCD's speculative contacts are inelastic and S2's balls
        // stop; on (--bullet-spec-restitution 1) they bounce but gain energy (see .md)
        world_.setApplySpeculativeContactRestitution(spec_restitution);
        body->setCcdMotionThreshold(b.radius);
        body->setCcdSweptSphereRadius(b.radius);
      }
      world_.addRigidBody(body.get());
      balls_.push_back(std::move(body));
    }
  }
  ~BulletEngine() override
  {
    for (auto& b : balls_)
      world_.removeRigidBody(b.get());
    for (auto& w : walls_)
      world_.removeRigidBody(w.get());
  }

  // maxSubSteps 0: exactly one step of dt, no interpolation or accumulation
  void step() override { world_.stepSimulation(static_cast<btScalar>(dt_), 0); }

  std::vector<Disc> discs() const override
  {
    std::vector<Disc> out;
    out.reserve(balls_.size());
    for (const auto& b : balls_)
    {
      const btVector3& p = b->getWorldTransform().getOrigin();
      out.push_back({p.x(), p.y(), static_cast<const btSphereShape*>(b->getCollisionShape())->getRadius()});
    }
    return out;
  }
  double kinetic() const override
  {
    double k = 0;
    for (const auto& b : balls_)
      k += 0.5 / b->getInvMass() * b->getLinearVelocity().length2();
    return k;
  }

private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  double dt_;
  double spheres_radius_ = -1;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> walls_, balls_;
};

// ---------------------------------------------------------------------------------------
// Box2D: 2D (the floor is implicit), no gravity in its plane, bullets in S2.
class Box2dEngine : public Engine
{
public:
  Box2dEngine(const Scene& scene, bool bullets) : world_(b2Vec2(0, 0)), dt_(scene.dt)
  {
    world_.SetAllowSleeping(false);
    world_.SetContinuousPhysics(true);  // the default: TOI against static walls
    b2BodyDef wall_def;
    b2Body* walls = world_.CreateBody(&wall_def);
    for (const auto& w : scene.walls)
    {
      b2EdgeShape edge;  // two-sided segment: the scene's zero-thickness wall exactly
      edge.SetTwoSided(b2Vec2(static_cast<float>(w.point.x()), static_cast<float>(w.point.y())),
                       b2Vec2(static_cast<float>(w.point.x() + w.u.x()), static_cast<float>(w.point.y() + w.u.y())));
      b2FixtureDef fd;
      fd.shape = &edge;
      fd.friction = 0;
      fd.restitution = 1;
      fd.restitutionThreshold = 0;  // Box2D 2.4.1: per fixture; contacts take the min
      walls->CreateFixture(&fd);
    }
    for (const auto& b : scene.balls)
    {
      b2BodyDef bd;
      bd.type = b2_dynamicBody;
      bd.position.Set(static_cast<float>(b.position.x()), static_cast<float>(b.position.y()));
      bd.linearVelocity.Set(static_cast<float>(b.velocity.x()), static_cast<float>(b.velocity.y()));
      bd.linearDamping = 0;
      bd.angularDamping = 0;
      bd.allowSleep = false;
      bd.bullet = bullets;
      b2Body* body = world_.CreateBody(&bd);
      b2CircleShape circle;
      circle.m_radius = static_cast<float>(b.radius);
      b2FixtureDef fd;
      fd.shape = &circle;
      fd.density = static_cast<float>(b.mass / (M_PI * b.radius * b.radius));
      fd.friction = 0;
      fd.restitution = 1;
      fd.restitutionThreshold = 0;
      body->CreateFixture(&fd);
      balls_.push_back(body);
      radii_.push_back(b.radius);
    }
  }

  void step() override { world_.Step(static_cast<float>(dt_), 8, 3); }

  std::vector<Disc> discs() const override
  {
    std::vector<Disc> out;
    out.reserve(balls_.size());
    for (std::size_t i = 0; i < balls_.size(); ++i)
    {
      const b2Vec2& p = balls_[i]->GetPosition();
      out.push_back({p.x, p.y, radii_[i]});
    }
    return out;
  }
  double kinetic() const override
  {
    double k = 0;
    for (const b2Body* b : balls_)
    {
      const b2Vec2& v = b->GetLinearVelocity();
      k += 0.5 * static_cast<double>(b->GetMass()) * (static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y);
    }
    return k;
  }

private:
  b2World world_;
  double dt_;
  std::vector<b2Body*> balls_;
  std::vector<double> radii_;
};

// ---------------------------------------------------------------------------------------
// Measures.

/// Largest r_i + r_j - |c_i - c_j| over all pairs (0 when none overlap), by a sort and
/// sweep on x: only pairs closer in x than r_i + r_max are looked at.
double maxOverlap(std::vector<Disc> d)
{
  std::sort(d.begin(), d.end(), [](const Disc& a, const Disc& b) { return a.x < b.x; });
  double r_max = 0;
  for (const auto& e : d)
    r_max = std::max(r_max, e.r);
  double worst = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = i + 1; j < d.size() && d[j].x - d[i].x < d[i].r + r_max; ++j)
    {
      const double dx = d[j].x - d[i].x, dy = d[j].y - d[i].y;
      const double reach = d[i].r + d[j].r;
      if (std::abs(dy) >= reach)
        continue;
      worst = std::max(worst, reach - std::sqrt(dx * dx + dy * dy));
    }
  return worst;
}

/// Balls whose centre is outside [0, side] in x or y (or not finite).
int escaped(const std::vector<Disc>& d, double side)
{
  int n = 0;
  for (const auto& e : d)
    if (!(e.x >= 0 && e.x <= side && e.y >= 0 && e.y <= side))
      ++n;
  return n;
}

struct Row
{
  std::string engine, scene;
  std::size_t balls = 0;
  long steps = 0;
  double ns_per_ball_step = 0, kinetic_ratio = 0, overlap = 0;
  int escaped = 0;
  std::string csv() const
  {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s,%s,%zu,%ld,%.6g,%.9g,%.6g,%d", engine.c_str(), scene.c_str(), balls, steps,
                  ns_per_ball_step, kinetic_ratio, overlap, escaped);
    return buf;
  }
};

Row run(Engine& engine, const std::string& name, const std::string& scene_name, const Scene& scene, long steps,
        double budget_s)
{
  Row row;
  row.engine = name;
  row.scene = scene_name;
  row.balls = scene.balls.size();
  const double k0 = engine.kinetic();
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(steps));
  double total = 0;
  for (long s = 0; s < steps && total < budget_s; ++s)
  {
    const auto t0 = Clock::now();
    engine.step();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    times.push_back(dt);
    total += dt;
  }
  row.steps = static_cast<long>(times.size());
  if (!times.empty())
  {
    const std::size_t mid = times.size() / 2;
    std::nth_element(times.begin(), times.begin() + mid, times.end());
    double median = times[mid];
    if (times.size() % 2 == 0)
      median = (median + *std::max_element(times.begin(), times.begin() + mid)) / 2;
    row.ns_per_ball_step = median * 1e9 / static_cast<double>(row.balls);
  }
  row.kinetic_ratio = engine.kinetic() / k0;
  const auto d = engine.discs();
  row.overlap = maxOverlap(d);
  row.escaped = escaped(d, sideOf(scene));
  return row;
}

std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
}

bool contains(const std::vector<std::string>& v, const std::string& s)
{
  return std::find(v.begin(), v.end(), s) != v.end();
}

[[noreturn]] void usage(const char* why)
{
  std::cerr << "compare_peers: " << why
            << "\nusage: compare_peers [--sizes 1000,10000,100000] [--seconds 10] [--budget 20]\n"
               "                     [--engines ball_collision_sim,ode,bullet,box2d] [--scenes S1,S2]\n"
               "                     [--out file.csv] [--bullet-spec-restitution 0|1]\n";
  std::exit(2);
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<int> sizes = {1000, 10000, 100000};
  double seconds = 10, budget = 20;
  std::vector<std::string> engines = {"ball_collision_sim", "ode", "bullet", "box2d"};
  std::vector<std::string> scenes = {"S1", "S2"};
  std::string out_path;
  bool bullet_spec = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (i + 1 >= argc)
      usage(("missing value for " + a).c_str());
    const std::string v = argv[++i];
    try
    {
      if (a == "--sizes")
      {
        sizes.clear();
        for (const auto& s : split(v))
          sizes.push_back(std::stoi(s));
      }
      else if (a == "--seconds")
        seconds = std::stod(v);
      else if (a == "--budget")
        budget = std::stod(v);
      else if (a == "--engines")
        engines = split(v);
      else if (a == "--scenes")
        scenes = split(v);
      else if (a == "--bullet-spec-restitution")
        bullet_spec = std::stoi(v) != 0;
      else if (a == "--out")
        out_path = v;
      else
        usage(("unknown option " + a).c_str());
    }
    catch (const std::exception&)
    {
      usage(("bad value for " + a).c_str());
    }
  }
  for (const auto& e : engines)
    if (!contains({"ball_collision_sim", "ode", "bullet", "box2d"}, e))
      usage(("unknown engine " + e).c_str());

  std::ofstream out;
  if (!out_path.empty())
  {
    out.open(out_path);
    if (!out)
      usage(("cannot write " + out_path).c_str());
  }
  const std::string header =
      "engine,scene,balls,steps,median_ns_per_ball_step,kinetic_end_over_start,max_overlap_m,escaped";
  std::cout << header << std::endl;
  if (out)
    out << header << std::endl;

  dInitODE2(0);
  auto make = [&](const std::string& name, const Scene& scene, bool ccd) -> std::unique_ptr<Engine> {
    if (name == "ode")
      return std::make_unique<OdeEngine>(scene, ccd);
    if (name == "bullet")
      return std::make_unique<BulletEngine>(scene, ccd, bullet_spec);
    if (name == "box2d")
      return std::make_unique<Box2dEngine>(scene, ccd);
    return std::make_unique<CoreEngine>(scene);
  };
  auto runScene = [&](const std::string& scene_name, const Scene& scene, long steps, bool ccd) {
    for (const auto& e : engines)
    {
      std::cerr << "running " << e << " " << scene_name << " with " << scene.balls.size() << " balls, " << steps
                << " steps..." << std::endl;
      auto engine = make(e, scene, ccd);
      const Row row = run(*engine, e, scene_name, scene, steps, budget);
      std::cout << row.csv() << std::endl;
      if (out)
        out << row.csv() << std::endl;
    }
  };

  if (contains(scenes, "S1"))
    for (int n : sizes)
    {
      const Scene scene = ball_collision_sim::bench::billiards(n);
      runScene("S1", scene, std::lround(seconds / scene.dt), false);
    }
  if (contains(scenes, "S2"))
  {
    const Scene scene = ball_collision_sim::bench::bullets();
    runScene("S2", scene, std::lround(1.0 / scene.dt), true);
  }
  dCloseODE();
  return 0;
}
