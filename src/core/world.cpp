// The public World: its state and the step live in a StepContext
// (src/core/step/step_context.hpp); every call goes there.
#include "ball_collision_sim/core/world.hpp"

#include "step/step_context.hpp"

namespace ball_collision_sim::core
{
World::World(const Scene& scene, const StepSettings& settings) : c_(std::make_unique<StepContext>(scene, settings))
{
}

World::World(const Scene& scene, SceneCheck checked, const StepSettings& settings)
    : c_(std::make_unique<StepContext>(scene, std::move(checked), settings))
{
}

World::World(const World& other) : c_(std::make_unique<StepContext>(*other.c_)) {}

World& World::operator=(const World& other)
{
  if (this != &other)
    c_ = std::make_unique<StepContext>(*other.c_);
  return *this;
}

World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

void World::step() { c_->step(); }
void World::reset() { c_->reset(); }
double World::time() const { return static_cast<double>(c_->stats_.steps) * c_->dt_; }
double World::dt() const { return c_->dt_; }
const Vec3& World::gravity() const { return c_->gravity_; }
const Scene& World::scene() const { return c_->scene_; }
const StepSettings& World::stepSettings() const { return c_->settings_; }
BallList World::balls() const { return BallList(c_->balls_, c_->by_id_); }
const std::vector<Wall>& World::walls() const { return c_->walls_; }
const std::optional<Floor>& World::floor() const { return c_->ground_.floor(); }
const std::vector<CollisionEvent>& World::lastEvents() const { return c_->events_; }
void World::recordEvents(bool record) { c_->recordEvents(record); }
bool World::recordsEvents() const { return c_->record_events_; }
const WorldStats& World::stats() const { return c_->stats_; }
const std::optional<FrictionDef>& World::friction() const { return c_->scene_.friction; }
const std::vector<MotionTransition>& World::lastTransitions() const { return c_->transitions_; }
Energy World::energy() const { return c_->energy(); }
Vec3 World::momentum() const { return c_->momentum(); }
int World::lostBalls() const { return c_->lostBalls(); }
std::vector<LostBall> World::removeLostBalls() { return c_->removeLostBalls(); }
std::uint64_t World::stateHash() const { return c_->stateHash(); }
const Ball* World::findBall(int id) const { return c_->findBall(id); }
std::size_t World::indexOf(int id) const { return c_->indexOf(id); }
Vec3 World::angularVelocity(std::size_t k) const { return c_->angularVelocity(k); }
MotionKind World::motionKind(std::size_t k) const { return c_->motionKind(k); }
double World::inertia(std::size_t k) const { return c_->inertia(k); }

AddResult World::addBall(const BallDef& def, Landing landing) { return c_->addBall(def, landing); }

AddResult World::setBallState(int id, const Vec3& position, const Vec3& velocity, Landing landing,
                              const std::optional<Vec3>& angular_velocity, const std::optional<double>& inertia)
{
  return c_->setBallState(id, position, velocity, landing, angular_velocity, inertia);
}

AddResult World::applyImpulse(int id, const Vec3& impulse) { return c_->applyImpulse(id, impulse); }
AddResult World::strike(int id, const Vec3& impulse, const Vec3& offset) { return c_->strike(id, impulse, offset); }
AddResult World::addWall(const WallDef& def) { return c_->addWall(def); }
bool World::removeBall(int id) { return c_->removeBall(id); }
bool World::removeWall(int id) { return c_->removeWall(id); }
}  // namespace ball_collision_sim::core
