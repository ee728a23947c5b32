// The public World: its state and the step live in a StepContext
// (src/core/step/step_context.hpp); here its making, its steps and its accessors. Its
// queries are in queries.cpp, its edits in edits.cpp, its lost balls in lost_balls.cpp.
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
bool World::recordsEvents() const { return c_->record_events_; }
const WorldStats& World::stats() const { return c_->stats_; }
const std::optional<FrictionDef>& World::friction() const { return c_->scene_.friction; }
const std::vector<MotionTransition>& World::lastTransitions() const { return c_->transitions_; }
const std::vector<PocketedBall>& World::lastPocketed() const { return c_->pocketed_; }
std::size_t World::indexOf(int id) const { return c_->rankOf(id); }
}  // namespace ball_collision_sim::core
