// Runs the benchmark scenes S1 (billiards), S2 (bullets) and S1F (S1 with pooltool's cloth
// friction) in ODE, Bullet, Box2D and this package's core in one run and writes one CSV row
// per engine, scene and ball count:
//
//   engine,scene,balls,steps,median_ns_per_ball_step,kinetic_end_over_start,max_overlap_m,escaped
//
// Every engine gets the very same balls (bench/scenes.hpp) and dt = 0.01 s. The peers get
// their fairest settings (see bench/compare_peers.md): in S1 and S2 restitution 1 with no
// restitution velocity threshold, no friction, no damping, no sleeping, balls kept in the
// plane; in S1F real spheres on a floor under gravity (ODE, Bullet) or a top-down friction
// joint (Box2D), with friction coefficients matched to the scene's laws.
//
// With --closed-forms FILE it also runs two single-ball cases with closed-form answers in
// every engine (a ball struck without spin; a stop shot) and writes
//
//   engine,case,quantity,measured,closed_form,abs_error,note
//
// Usage: compare_peers [--sizes 1000,10000,100000] [--friction-sizes 1000,10000]
//                      [--seconds 10] [--budget 20]
//                      [--engines ball_collision_sim,ode,bullet,box2d] [--scenes S1,S2,S1F|none]
//                      [--out file.csv] [--closed-forms file.csv] [--bullet-spec-restitution 0|1]
//
// --seconds is the simulated time of S1 and S1F (S2 is always 1 s, as the issue says).
// --budget is the wall time [s] one engine may spend stepping one scene: an engine stops
// after the first step that ends past it, and the steps column says how many steps were
// run; the kinetic energy ratio, overlap and escaped count are those at the end of the
// steps actually run.
#include "scenes.hpp"

#include "ball_collision_sim/core/world.hpp"

#include <box2d/box2d.h>
#include <btBulletDynamicsCommon.h>
#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ball_collision_sim::core::BallDef;
using ball_collision_sim::core::FrictionDef;
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

/// A ball's full state, as the closed-form cases read it.
struct BallState
{
  Vec3 position, velocity, angular_velocity;
};

/// What an engine must offer: one step, and its balls' positions and kinetic energy.
class Engine
{
public:
  virtual ~Engine() = default;
  virtual void step() = 0;
  virtual std::vector<Disc> discs() const = 0;
  /// Translational kinetic energy, sum of m |v|^2 / 2 [J].
  virtual double kinetic() const = 0;
  virtual BallState ballState(std::size_t i) const = 0;
  /// Whether a ball can spin about an axis along the floor (false for 2D engines, whose
  /// discs turn about the floor's normal only: no slip distinct from the velocity).
  virtual bool spinsAlongFloor() const { return true; }
};

/// A ball's initial spin: its own, or else that of rolling without slip on a level floor
/// (z up), n x v / r, as the core gives a ball without one.
Vec3 initialSpin(const BallDef& b)
{
  return b.angular_velocity ? *b.angular_velocity : Vec3(Vec3::UnitZ().cross(b.velocity) / b.radius);
}

/// Peers' rolling and spinning friction are torques limited to rho N (rho a length, N the
/// normal force). A ball of inertia k m r^2 rolling under a pure torque rho m g against its
/// spin, held to rolling by floor friction F: m a = -F, k m r^2 a / r = F r - rho m g, so
/// a = -rho g / ((1 + k) r); the scene's rolling deceleration mu_r g needs
/// rho = (1 + k) mu_r r. A spin about the normal decays at rho_N m g / (k m r^2), the
/// scene's mu_sp g / (k r) needs rho_N = mu_sp r.
double rollingTorqueArm(const FrictionDef& f, double k, double r)
{
  return (1 + k) * f.rolling * r;
}
double spinningTorqueArm(const FrictionDef& f, double r)
{
  return f.spinning * r;
}

/// Gravity's pull into a level floor (z up) [m/s^2].
double gravityIntoFloor(const Scene& scene)
{
  return -scene.gravity.z();
}

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
  BallState ballState(std::size_t i) const override
  {
    const auto& b = world_.balls()[i];
    return {b.position, b.velocity, world_.angularVelocity(i)};
  }
  const ball_collision_sim::core::World& world() const { return world_; }

private:
  ball_collision_sim::core::World world_;
};

// ---------------------------------------------------------------------------------------
// ODE: quickstep, sweep-and-prune space, bouncy frictionless contacts between balls and
// with walls. Without friction: no gravity and no floor, z velocity zeroed. With friction:
// a floor plane under gravity with Coulomb, rolling and spinning friction.
class OdeEngine : public Engine
{
public:
  OdeEngine(const Scene& scene, bool /*ccd: ODE has none for spheres*/)
    : dt_(scene.dt), restitution_(scene.restitution), friction_(scene.friction)
  {
    world_ = dWorldCreate();
    if (friction_)
    {
      // Friction needs the floor's normal force: real spheres resting on a plane (z = 0)
      // under gravity, free in z (a plane-2D joint would also lock the spin along the
      // floor that rolling needs).
      dWorldSetGravity(world_, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
    }
    else
    {
      // Gravity is normal to the floor and the balls are kept in the plane, so it would do
      // no work: the peers get neither gravity nor a floor (no N floor contacts per step).
      dWorldSetGravity(world_, 0, 0, 0);
    }
    dWorldSetAutoDisableFlag(world_, 0);
    space_ = dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ);
    contacts_ = dJointGroupCreate(0);
    if (friction_)
      floor_ = dCreatePlane(space_, 0, 0, 1, 0);
    const double c = scene.walls.empty() ? 0 : sideOf(scene) / 2;
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
      if (friction_)
      {
        const double inertia = b.inertia * b.mass * b.radius * b.radius;  // k m r^2
        dMassSetParameters(&m, b.mass, 0, 0, 0, inertia, inertia, inertia, 0, 0, 0);
      }
      dBodySetMass(body, &m);
      dBodySetPosition(body, b.position.x(), b.position.y(), b.radius);
      dBodySetLinearVel(body, b.velocity.x(), b.velocity.y(), 0);
      if (friction_)
      {
        const Vec3 w = initialSpin(b);
        dBodySetAngularVel(body, w.x(), w.y(), w.z());
      }
      dBodySetData(body, reinterpret_cast<void*>(static_cast<std::uintptr_t>(bodies_.size())));
      dGeomID g = dCreateSphere(space_, b.radius);
      dGeomSetBody(g, body);
      bodies_.push_back(body);
      radii_.push_back(b.radius);
      masses_.push_back(b.mass);
      inertias_.push_back(b.inertia);
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
    if (friction_)
      return;  // the floor holds the balls
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
  BallState ballState(std::size_t i) const override
  {
    const dReal* p = dBodyGetPosition(bodies_[i]);
    const dReal* v = dBodyGetLinearVel(bodies_[i]);
    const dReal* w = dBodyGetAngularVel(bodies_[i]);
    return {Vec3(p[0], p[1], p[2]), Vec3(v[0], v[1], v[2]), Vec3(w[0], w[1], w[2])};
  }

private:
  /// Stands in for a zero rolling or spinning coefficient: ODE's dContactAxisDep counts
  /// a row for each coefficient >= 0 but fills only those > 0.
  static constexpr double kNoTorque = 1e-12;  // [m]

  static void nearCallback(void* data, dGeomID o1, dGeomID o2)
  {
    auto* self = static_cast<OdeEngine*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2)
      return;  // wall against wall or floor
    dContact contact{};
    if (dCollide(o1, o2, 1, &contact.geom, sizeof(dContact)) == 0)
      return;
    if (self->friction_ && (o1 == self->floor_ || o2 == self->floor_))
      self->floorContact(contact, b1 ? b1 : b2);
    else
    {
      contact.surface.mode = dContactBounce;
      contact.surface.mu = 0;                       // no friction
      contact.surface.bounce = self->restitution_;  // the scene's restitution
      contact.surface.bounce_vel = 0;               // ... at every closing speed
    }
    dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact);
    dJointAttach(j, b1, b2);
  }

  /// A ball on the floor: Coulomb friction mu_s in proportion to the normal force
  /// (dContactApprox1; without it mu would be a force), rolling friction rho = rho2 =
  /// (1 + k) mu_r r and spinning friction rhoN = mu_sp r as torque limits in proportion
  /// to the normal force, no bounce. The first friction direction is set along the
  /// contact point's slip while the ball slides and along its velocity while it rolls, so
  /// that ODE's box of friction limits (one per tangent axis) is not wider along a
  /// diagonal.
  void floorContact(dContact& contact, dBodyID ball) const
  {
    const std::size_t i = static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(dBodyGetData(ball)));
    const FrictionDef& f = *friction_;
    contact.surface.mode = dContactApprox1 | dContactAxisDep | dContactRolling;
    contact.surface.mu = f.sliding;
    contact.surface.mu2 = f.sliding;
    contact.surface.rho = std::max(rollingTorqueArm(f, inertias_[i], radii_[i]), kNoTorque);
    contact.surface.rho2 = contact.surface.rho;
    contact.surface.rhoN = std::max(spinningTorqueArm(f, radii_[i]), kNoTorque);
    const dReal* pv = dBodyGetLinearVel(ball);
    const dReal* pw = dBodyGetAngularVel(ball);
    const dReal* pp = dBodyGetPosition(ball);
    const Vec3 n(contact.geom.normal[0], contact.geom.normal[1], contact.geom.normal[2]);
    const Vec3 v(pv[0], pv[1], pv[2]), w(pw[0], pw[1], pw[2]);
    const Vec3 arm = Vec3(contact.geom.pos[0], contact.geom.pos[1], contact.geom.pos[2]) - Vec3(pp[0], pp[1], pp[2]);
    Vec3 slip = v + w.cross(arm);
    slip -= n.dot(slip) * n;
    Vec3 along = v - n.dot(v) * n;
    const Vec3 dir = slip.norm() > 1e-3 * along.norm() + 1e-9 ? slip : along;
    if (dir.norm() > 1e-12)
    {
      const Vec3 d = dir.normalized();
      contact.surface.mode |= dContactFDir1;
      contact.fdir1[0] = d.x();
      contact.fdir1[1] = d.y();
      contact.fdir1[2] = d.z();
    }
  }

  double dt_;
  double restitution_;
  std::optional<FrictionDef> friction_;
  dWorldID world_;
  dSpaceID space_;
  dGeomID floor_ = nullptr;
  dJointGroupID contacts_;
  std::vector<dBodyID> bodies_;
  std::vector<double> radii_, masses_, inertias_;
};

// ---------------------------------------------------------------------------------------
// Bullet: DBVT broad phase, sequential impulse solver, CCD in S2; with friction a static
// floor plane under gravity.
class BulletEngine : public Engine
{
public:
  BulletEngine(const Scene& scene, bool ccd, bool spec_restitution)
    : dispatcher_(&config_), world_(&dispatcher_, &broadphase_, &solver_, &config_), dt_(scene.dt),
      friction_(scene.friction.has_value())
  {
    if (friction_)
      world_.setGravity(btVector3(scene.gravity.x(), scene.gravity.y(), scene.gravity.z()));
    else
      world_.setGravity(btVector3(0, 0, 0));  // see OdeEngine: gravity would do no work
    btContactSolverInfo& solver = world_.getSolverInfo();
    solver.m_restitutionVelocityThreshold = 0;  // bounce at every closing speed (default 0.2)
    // Penetration is always undone by split impulse (position only), never by Baumgarte
    // feedback into the velocity: by default penetrations shallower than 0.04 m are fed
    // back into the velocity and every bouncing contact gains energy (a head-on pair at
    // 2 m/s leaves at 2.4 m/s; S1 then heats up 30-fold in 2 s).
    solver.m_splitImpulse = true;
    solver.m_splitImpulsePenetrationThreshold = 1e30f;
    const FrictionDef f = scene.friction.value_or(FrictionDef());
    if (friction_)
    {
      // By default a contact gets a second friction direction only while it slips; a
      // rolling ball (slip below 3.4e-4 m/s) would then have friction along one fixed
      // axis only.
      solver.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
      // Bullet multiplies the two bodies' coefficients (rolling: rolling_a friction_b +
      // friction_a rolling_b), which cannot give friction at the floor and none between
      // balls: each contact takes its coefficients from the body that decides it.
      gCalculateCombinedFrictionCallback = &combinedFriction;
      gCalculateCombinedRestitutionCallback = &combinedRestitution;
      gCalculateCombinedRollingFrictionCallback = &combinedRollingFriction;
      gCalculateCombinedSpinningFrictionCallback = &combinedSpinningFriction;
      shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0));
      btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
      info.m_friction = f.sliding;
      info.m_restitution = 0;
      walls_.push_back(std::make_unique<btRigidBody>(info));
      walls_.back()->setUserIndex(kFloorBody);
      world_.addRigidBody(walls_.back().get());
    }
    const double c = scene.walls.empty() ? 0 : sideOf(scene) / 2;
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
      info.m_restitution = w.restitution.value_or(scene.restitution);
      info.m_friction = f.wall;
      walls_.push_back(std::make_unique<btRigidBody>(info));
      walls_.back()->setUserIndex(kWallBody);
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
      if (friction_)
      {
        const btScalar i = b.inertia * b.mass * b.radius * b.radius;  // k m r^2
        inertia.setValue(i, i, i);
      }
      btRigidBody::btRigidBodyConstructionInfo info(b.mass, nullptr, shape, inertia);
      info.m_startWorldTransform.setOrigin(btVector3(b.position.x(), b.position.y(), b.radius));
      info.m_restitution = scene.restitution;
      info.m_friction = f.ball_ball;
      // torque limits per unit normal impulse (see rollingTorqueArm)
      info.m_rollingFriction = rollingTorqueArm(f, b.inertia, b.radius);
      info.m_spinningFriction = spinningTorqueArm(f, b.radius);
      info.m_linearDamping = 0;
      info.m_angularDamping = 0;
      auto body = std::make_unique<btRigidBody>(info);
      body->setUserIndex(kBallBody);
      body->setLinearVelocity(btVector3(b.velocity.x(), b.velocity.y(), 0));
      if (friction_)
      {
        const Vec3 w = initialSpin(b);
        body->setAngularVelocity(btVector3(w.x(), w.y(), w.z()));
      }
      else
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
    gCalculateCombinedFrictionCallback = &btManifoldResult::calculateCombinedFriction;
    gCalculateCombinedRestitutionCallback = &btManifoldResult::calculateCombinedRestitution;
    gCalculateCombinedRollingFrictionCallback = &btManifoldResult::calculateCombinedRollingFriction;
    gCalculateCombinedSpinningFrictionCallback = &btManifoldResult::calculateCombinedSpinningFriction;
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
  BallState ballState(std::size_t i) const override
  {
    const btVector3& p = balls_[i]->getWorldTransform().getOrigin();
    const btVector3& v = balls_[i]->getLinearVelocity();
    const btVector3& w = balls_[i]->getAngularVelocity();
    return {Vec3(p.x(), p.y(), p.z()), Vec3(v.x(), v.y(), v.z()), Vec3(w.x(), w.y(), w.z())};
  }

private:
  enum BodyKind
  {
    kBallBody = 0,
    kWallBody = 1,
    kFloorBody = 2,
  };
  /// The body whose coefficients a contact takes: the floor, else a wall, else (two
  /// balls) either ball, as every ball has the scene's ball-ball coefficients.
  static const btCollisionObject* decides(const btCollisionObject* a, const btCollisionObject* b)
  {
    if (a->getUserIndex() == kFloorBody || (a->getUserIndex() == kWallBody && b->getUserIndex() != kFloorBody))
      return a;
    if (b->getUserIndex() != kBallBody)
      return b;
    return a;
  }
  static bool onFloor(const btCollisionObject* a, const btCollisionObject* b)
  {
    return a->getUserIndex() == kFloorBody || b->getUserIndex() == kFloorBody;
  }
  static const btCollisionObject* ballOf(const btCollisionObject* a, const btCollisionObject* b)
  {
    return a->getUserIndex() == kBallBody ? a : b;
  }
  static btScalar combinedFriction(const btCollisionObject* a, const btCollisionObject* b)
  {
    return decides(a, b)->getFriction();
  }
  static btScalar combinedRestitution(const btCollisionObject* a, const btCollisionObject* b)
  {
    return decides(a, b)->getRestitution();
  }
  /// Rolling and spinning friction at the floor only, the ball's own (they depend on its
  /// radius and inertia).
  static btScalar combinedRollingFriction(const btCollisionObject* a, const btCollisionObject* b)
  {
    return onFloor(a, b) ? ballOf(a, b)->getRollingFriction() : 0;
  }
  static btScalar combinedSpinningFriction(const btCollisionObject* a, const btCollisionObject* b)
  {
    return onFloor(a, b) ? ballOf(a, b)->getSpinningFriction() : 0;
  }

  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  double dt_;
  bool friction_;
  double spheres_radius_ = -1;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> walls_, balls_;
};

// ---------------------------------------------------------------------------------------
// Box2D: 2D (the floor is implicit), no gravity in its plane, bullets in S2. With friction
// (top-down: Box2D has no floor contact) each ball is held to a static body without
// fixtures by a friction joint, a force of at most mu_r m g against its velocity and a
// torque of at most mu_sp m g r against its spin: rolling resistance and spinning friction,
// but no sliding phase (its discs have no spin along the floor to slip against).
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
      fd.restitution = static_cast<float>(w.restitution.value_or(scene.restitution));
      fd.restitutionThreshold = 0;  // Box2D 2.4.1: per fixture; contacts take the min
      walls->CreateFixture(&fd);
    }
    // The friction joints' anchor: a body of its own, as a joint turns off collisions
    // between the bodies it connects (the walls' body would let the balls through).
    b2Body* ground = nullptr;
    if (scene.friction)
    {
      b2BodyDef ground_def;
      ground = world_.CreateBody(&ground_def);
    }
    for (const auto& b : scene.balls)
    {
      b2BodyDef bd;
      bd.type = b2_dynamicBody;
      bd.position.Set(static_cast<float>(b.position.x()), static_cast<float>(b.position.y()));
      bd.linearVelocity.Set(static_cast<float>(b.velocity.x()), static_cast<float>(b.velocity.y()));
      if (scene.friction)
        bd.angularVelocity = static_cast<float>(initialSpin(b).z());
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
      fd.restitution = static_cast<float>(scene.restitution);
      fd.restitutionThreshold = 0;
      body->CreateFixture(&fd);
      if (scene.friction)
      {
        // a sphere's inertia about the normal, k m r^2 (a disc's would be m r^2 / 2)
        b2MassData mass;
        mass.mass = static_cast<float>(b.mass);
        mass.center.SetZero();
        mass.I = static_cast<float>(b.inertia * b.mass * b.radius * b.radius);
        body->SetMassData(&mass);
        const double g = gravityIntoFloor(scene);
        b2FrictionJointDef jd;
        jd.Initialize(ground, body, body->GetPosition());
        jd.maxForce = static_cast<float>(scene.friction->rolling * b.mass * g);
        jd.maxTorque = static_cast<float>(spinningTorqueArm(*scene.friction, b.radius) * b.mass * g);
        world_.CreateJoint(&jd);
      }
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
  BallState ballState(std::size_t i) const override
  {
    const b2Vec2& p = balls_[i]->GetPosition();
    const b2Vec2& v = balls_[i]->GetLinearVelocity();
    return {Vec3(p.x, p.y, radii_[i]), Vec3(v.x, v.y, 0), Vec3(0, 0, balls_[i]->GetAngularVelocity())};
  }
  bool spinsAlongFloor() const override { return false; }

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

// ---------------------------------------------------------------------------------------
// Closed-form cases: one pool ball on a level floor with pooltool's cloth.

constexpr double kCfRadius = 0.028575;  // [m]
constexpr double kCfMass = 0.170097;    // [kg]
constexpr double kCfSpeed = 2.0;        // v0 [m/s]
constexpr double kCfSliding = 0.2, kCfRolling = 0.01, kCfSpinning = 0.044;
constexpr double kCfGravity = 9.81;    // [m/s^2]
constexpr double kCfSeconds = 40;      // longest run [s]
constexpr double kCfRollSlip = 1e-3;   // roll onset: slip below this part of v0
constexpr double kCfStopSpeed = 1e-6;  // stopped: speed below this [m/s]

/// The ball struck at v0 along +x from the origin with spin w0, on a floor 30 m by 2 m.
Scene closedFormScene(const Vec3& w0)
{
  Scene s;
  ball_collision_sim::core::FloorDef f;
  f.point = Vec3(-1, -1, 0);
  f.u = Vec3(31, 0, 0);
  f.v = Vec3(0, 2, 0);
  s.floor = f;
  s.dt = 0.01;
  s.gravity = Vec3(0, 0, -kCfGravity);
  FrictionDef mu;
  mu.sliding = kCfSliding;
  mu.rolling = kCfRolling;
  mu.spinning = kCfSpinning;
  s.friction = mu;
  BallDef b;
  b.radius = kCfRadius;
  b.mass = kCfMass;
  b.inertia = ball_collision_sim::core::kSolidInertia;
  b.position = Vec3(0, 0, kCfRadius);
  b.velocity = Vec3(kCfSpeed, 0, 0);
  b.angular_velocity = w0;
  s.balls.push_back(b);
  return s;
}

/// (a) struck through its centre: no spin. (b) stop shot: backspin v0 / (k r) about -y.
Scene strikeScene()
{
  return closedFormScene(Vec3::Zero());
}
Scene stopShotScene()
{
  return closedFormScene(Vec3(0, -kCfSpeed / (ball_collision_sim::core::kSolidInertia * kCfRadius), 0));
}

struct CfRow
{
  std::string engine, which, quantity;
  double measured = 0, closed = 0;
  std::string note;
  std::string csv() const
  {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%.9g,%.9g,%.3g,%s", engine.c_str(), which.c_str(), quantity.c_str(),
                  measured, closed, std::abs(measured - closed), note.c_str());
    return buf;
  }
};

/// What a run of one case gives: NaN where the engine never got there.
struct CfMeasures
{
  double slide_time = NAN, slide_distance = NAN, roll_speed = NAN;
  double stop_time = NAN, stop_distance = NAN;
};

double horizontal(const Vec3& a)
{
  return std::hypot(a.x(), a.y());
}

/// Our core: transition times from World::lastTransitions() (exact), positions from
/// balls(). The state at the end of sliding, inside a step, is that of a world started
/// from the ball's state at the step's start and stepped once by the time left to the
/// transition.
CfMeasures measureCore(const Scene& scene)
{
  using ball_collision_sim::core::MotionKind;
  using ball_collision_sim::core::World;
  CfMeasures m;
  World world(scene);
  const Vec3 p0 = world.balls()[0].position;
  const long steps = std::lround(kCfSeconds / scene.dt);
  for (long s = 0; s < steps && std::isnan(m.stop_time); ++s)
  {
    const double t0 = world.time();
    const BallState before{world.balls()[0].position, world.balls()[0].velocity, world.angularVelocity(0)};
    world.step();
    for (const auto& tr : world.lastTransitions())
    {
      if (tr.from == MotionKind::kSliding && std::isnan(m.slide_time))
      {
        m.slide_time = tr.time;
        if (tr.to == MotionKind::kRolling && tr.time > t0)
        {
          Scene part = scene;
          part.dt = tr.time - t0;
          part.balls[0].position = before.position;
          part.balls[0].velocity = before.velocity;
          part.balls[0].angular_velocity = before.angular_velocity;
          World probe(part);
          probe.step();
          m.roll_speed = horizontal(probe.balls()[0].velocity);
          m.slide_distance = horizontal(probe.balls()[0].position - p0);
        }
      }
      if ((tr.to == MotionKind::kStationary || tr.to == MotionKind::kSpinning) && std::isnan(m.stop_time))
      {
        m.stop_time = tr.time;
        m.stop_distance = horizontal(world.balls()[0].position - p0);
      }
    }
  }
  return m;
}

/// A peer, at step resolution: the first step after which the contact point's slip
/// |v + r n x w| is below kCfRollSlip v0 is the roll onset, the first after which the
/// speed is below kCfStopSpeed the stop.
CfMeasures measurePeer(Engine& engine, const Scene& scene)
{
  CfMeasures m;
  const double r = scene.balls[0].radius;
  const Vec3 p0 = engine.ballState(0).position;
  const long steps = std::lround(kCfSeconds / scene.dt);
  for (long s = 1; s <= steps; ++s)
  {
    engine.step();
    const BallState b = engine.ballState(0);
    const Vec3 slip = b.velocity + r * Vec3::UnitZ().cross(b.angular_velocity);
    const double t = static_cast<double>(s) * scene.dt;
    if (engine.spinsAlongFloor() && std::isnan(m.slide_time) && horizontal(slip) < kCfRollSlip * kCfSpeed)
    {
      m.slide_time = t;
      m.slide_distance = horizontal(b.position - p0);
      m.roll_speed = horizontal(b.velocity);
    }
    if (horizontal(b.velocity) < kCfStopSpeed)
    {
      m.stop_time = t;
      m.stop_distance = horizontal(b.position - p0);
      break;
    }
  }
  return m;
}

/// Both cases in one engine, as CSV rows.
std::vector<CfRow> closedForms(const std::string& name, const std::function<std::unique_ptr<Engine>(const Scene&)>& make)
{
  const double v0 = kCfSpeed, g = kCfGravity, mu_s = kCfSliding, mu_r = kCfRolling;
  const double t1 = 2 * v0 / (7 * mu_s * g), v1 = 5.0 / 7 * v0;
  const double x1 = v0 * t1 - mu_s * g * t1 * t1 / 2;
  std::vector<CfRow> rows;
  const bool ours = name == "ball_collision_sim";
  {
    const Scene scene = strikeScene();
    CfMeasures m;
    std::string slide_note, stop_note;
    if (ours)
    {
      m = measureCore(scene);
      slide_note = "exact transition time";
      stop_note = "exact transition time";
    }
    else
    {
      auto engine = make(scene);
      m = measurePeer(*engine, scene);
      slide_note = engine->spinsAlongFloor() ? "first step with slip below 1e-3 v0"
                                             : "not represented: no spin along the floor so no sliding phase";
      stop_note = std::isnan(m.stop_time) ? "never below 1e-6 m/s in 40 s" : "first step below 1e-6 m/s";
    }
    const std::string c = "a_struck_without_spin";
    rows.push_back({name, c, "slide_end_time_s", m.slide_time, t1, slide_note});
    rows.push_back({name, c, "slide_end_distance_m", m.slide_distance, x1, slide_note});
    rows.push_back({name, c, "roll_speed_m_per_s", m.roll_speed, v1, slide_note});
    rows.push_back({name, c, "stop_distance_m", m.stop_distance, x1 + v1 * v1 / (2 * mu_r * g), stop_note});
    rows.push_back({name, c, "stop_time_s", m.stop_time, t1 + v1 / (mu_r * g), stop_note});
  }
  {
    const Scene scene = stopShotScene();
    CfMeasures m;
    std::string note;
    if (ours)
    {
      m = measureCore(scene);
      note = "exact transition time";
    }
    else
    {
      auto engine = make(scene);
      m = measurePeer(*engine, scene);
      note = std::isnan(m.stop_time) ? "never below 1e-6 m/s in 40 s" : "first step below 1e-6 m/s";
      if (!engine->spinsAlongFloor())
        note += "; backspin not represented (no spin along the floor)";
    }
    const std::string c = "b_stop_shot";
    rows.push_back({name, c, "stop_distance_m", m.stop_distance, v0 * v0 / (2 * mu_s * g), note});
    rows.push_back({name, c, "stop_time_s", m.stop_time, v0 / (mu_s * g), note});
  }
  return rows;
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
            << "\nusage: compare_peers [--sizes 1000,10000,100000] [--friction-sizes 1000,10000]\n"
               "                     [--seconds 10] [--budget 20]\n"
               "                     [--engines ball_collision_sim,ode,bullet,box2d] [--scenes S1,S2,S1F|none]\n"
               "                     [--out file.csv] [--closed-forms file.csv] [--bullet-spec-restitution 0|1]\n";
  std::exit(2);
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<int> sizes = {1000, 10000, 100000};
  std::vector<int> friction_sizes = {1000, 10000};
  double seconds = 10, budget = 20;
  std::vector<std::string> engines = {"ball_collision_sim", "ode", "bullet", "box2d"};
  std::vector<std::string> scenes = {"S1", "S2", "S1F"};
  std::string out_path, closed_forms_path;
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
      else if (a == "--friction-sizes")
      {
        friction_sizes.clear();
        for (const auto& s : split(v))
          friction_sizes.push_back(std::stoi(s));
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
      else if (a == "--closed-forms")
        closed_forms_path = v;
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
  for (const auto& sc : scenes)
    if (!contains({"S1", "S2", "S1F", "none"}, sc))
      usage(("unknown scene " + sc).c_str());

  std::ofstream out;
  if (!out_path.empty())
  {
    out.open(out_path);
    if (!out)
      usage(("cannot write " + out_path).c_str());
  }
  std::ofstream closed_out;
  if (!closed_forms_path.empty())
  {
    closed_out.open(closed_forms_path);
    if (!closed_out)
      usage(("cannot write " + closed_forms_path).c_str());
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
  if (contains(scenes, "S1F"))
    for (int n : friction_sizes)
    {
      const Scene scene = ball_collision_sim::bench::billiardsFriction(n);
      runScene("S1F", scene, std::lround(seconds / scene.dt), false);
    }
  if (closed_out.is_open())
  {
    const std::string cf_header = "engine,case,quantity,measured,closed_form,abs_error,note";
    std::cout << cf_header << std::endl;
    closed_out << cf_header << std::endl;
    for (const auto& e : engines)
    {
      std::cerr << "closed forms in " << e << "..." << std::endl;
      for (const auto& row : closedForms(e, [&](const Scene& scene) { return make(e, scene, false); }))
      {
        std::cout << row.csv() << std::endl;
        closed_out << row.csv() << std::endl;
      }
    }
  }
  dCloseODE();
  return 0;
}
