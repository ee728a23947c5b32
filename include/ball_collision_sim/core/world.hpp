#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/broad_phase.hpp"
#include "ball_collision_sim/core/collision_event.hpp"
#include "ball_collision_sim/core/event_queue.hpp"
#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/friction.hpp"
#include "ball_collision_sim/core/ground.hpp"
#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/step_settings.hpp"
#include "ball_collision_sim/core/types.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <unordered_map>
#include <vector>

namespace ball_collision_sim::core
{
class StepContext;  // src/core/step/step_context.hpp

/// Energy of the world; potential is measured from the origin along gravity.
struct Energy
{
  double kinetic = 0.0;     ///< sum of m |v|^2 / 2 [J]
  double rotational = 0.0;  ///< sum of k m r^2 |w|^2 / 2 where the world has friction, else 0 [J]
  double potential = 0.0;   ///< sum of -m <g, p> [J]
  double total() const { return kinetic + rotational + potential; }
};

/// A ball's motion kind changed (a world with friction): at a phase's end or an impact.
struct MotionTransition
{
  double time = 0.0;  ///< exact [s]
  int ball = -1;      ///< id
  MotionKind from = MotionKind::kSliding;
  MotionKind to = MotionKind::kSliding;
};

/// Counters since construction or the last reset.
struct WorldStats
{
  std::uint64_t steps = 0;
  std::uint64_t events = 0;          ///< handled collisions, resting contacts included
  std::uint64_t resting_events = 0;  ///< of them, contacts met mid-step that rest
  /// resting contacts solved as constraints, each counted once for each step it is in
  std::uint64_t resting_contacts = 0;
  std::uint64_t stale_events = 0;    ///< queued impacts dropped because a ball moved on
  std::uint64_t frozen_balls = 0;    ///< balls stopped for a step by the per-step event cap
  /// motions on a curved floor stopped where they start, the ball's energy run out there
  /// (a turning point: no motion and no speed for the rest of it)
  std::uint64_t stopped_balls = 0;
  std::uint64_t sleeping_balls = 0;  ///< balls asleep after the last step (not a sum)
  std::uint64_t woken_balls = 0;     ///< balls woken by impacts
  std::uint64_t transitions = 0;     ///< changes of a ball's motion kind (friction, take-offs, landings)
  std::uint64_t floor_impacts = 0;   ///< landings of balls in flight on the floor (bounces included)
  /// solves of a group's resting contacts that ran out of sweeps with closing left
  /// (StepSettings::contact_sweeps)
  std::uint64_t unsettled_contacts = 0;
  std::uint64_t pocketed_balls = 0;  ///< balls dropped into pockets (Scene::pockets)
};

/// Result of adding or editing an object: ok, or the reason it was refused (the world
/// unchanged).
struct AddResult
{
  bool ok = false;
  int id = -1;
  std::string error;  ///< "radius: must be > 0"
};

/// What World::setBallState() sets of a ball: each field left unset keeps its value.
struct BallEdit
{
  /// [m], put on the floor as `landing` says; unset: the ball stays exactly where it is
  /// (resting on the floor it stays on it, in flight it flies on)
  std::optional<Vec3> position;
  /// [m/s]; unset: kept. Under Landing::kUnder, on the floor, its part along the floor's
  /// normal is dropped.
  std::optional<Vec3> velocity;
  /// [rad/s] (a world with friction); unset: kept where the velocity is kept, else rolling
  /// without slip with the new velocity, n x v / r
  std::optional<Vec3> angular_velocity;
  std::optional<double> inertia;  ///< k in I = k m r^2, in [kMinInertia, 1]; unset: kept
  Landing landing = Landing::kUnder;
};

/// A ball that left the world: off the floor, or outside the walls' bounds.
struct LostBall
{
  Ball ball;               ///< its state when it was found gone
  Vec3 angular_velocity;   ///< [rad/s], as World::angularVelocity() gave it then
  MotionKind motion = MotionKind::kStationary;  ///< as World::motionKind() gave it then
  double inertia = kSolidInertia;               ///< as World::inertia() gave it
  std::string reason;  ///< "left the floor (foot point at u = 1.02, v = 0.5)"
};

/// A ball that dropped into a pocket: its centre crossed the pocket's circle at `time`,
/// and the step took it out of the world then.
struct PocketedBall
{
  double time = 0.0;  ///< exact [s]
  int pocket = 0;     ///< index into Scene::pockets
  Ball ball;          ///< its state at that time (its orientation: at the step's start)
  Vec3 angular_velocity = Vec3::Zero();         ///< [rad/s] then
  MotionKind motion = MotionKind::kStationary;  ///< its kind of motion then
  double inertia = kSolidInertia;               ///< k in I = k m r^2
};

/// Ids of balls and walls start here and only grow: 0, the value of a field left empty,
/// names no object.
constexpr int kFirstId = 1;

/// The balls in id order: a view of the world's records, which the step keeps in the
/// order it visits them in (neighbours in space are neighbours in memory). Valid until
/// the world steps or is edited.
class BallList
{
public:
  class Iterator
  {
  public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = Ball;
    using difference_type = std::ptrdiff_t;
    using pointer = const Ball*;
    using reference = const Ball&;
    Iterator() = default;
    Iterator(const BallList* list, std::size_t k) : list_(list), k_(k) {}
    reference operator*() const { return (*list_)[k_]; }
    pointer operator->() const { return &(*list_)[k_]; }
    reference operator[](difference_type d) const { return (*list_)[k_ + d]; }
    Iterator& operator++() { ++k_; return *this; }
    Iterator operator++(int) { Iterator old = *this; ++k_; return old; }
    Iterator& operator--() { --k_; return *this; }
    Iterator operator--(int) { Iterator old = *this; --k_; return old; }
    Iterator& operator+=(difference_type d) { k_ += d; return *this; }
    Iterator& operator-=(difference_type d) { k_ -= d; return *this; }
    Iterator operator+(difference_type d) const { return Iterator(list_, k_ + d); }
    Iterator operator-(difference_type d) const { return Iterator(list_, k_ - d); }
    difference_type operator-(const Iterator& o) const
    {
      return static_cast<difference_type>(k_) - static_cast<difference_type>(o.k_);
    }
    bool operator==(const Iterator& o) const { return k_ == o.k_; }
    bool operator!=(const Iterator& o) const { return k_ != o.k_; }
    bool operator<(const Iterator& o) const { return k_ < o.k_; }
    bool operator>(const Iterator& o) const { return k_ > o.k_; }
    bool operator<=(const Iterator& o) const { return k_ <= o.k_; }
    bool operator>=(const Iterator& o) const { return k_ >= o.k_; }

  private:
    const BallList* list_ = nullptr;
    std::size_t k_ = 0;
  };

  BallList(const std::vector<Ball>& records, const std::vector<std::uint32_t>& by_id)
      : records_(&records), by_id_(&by_id)
  {
  }
  std::size_t size() const { return by_id_->size(); }
  bool empty() const { return by_id_->empty(); }
  /// The ball with the k-th lowest id.
  const Ball& operator[](std::size_t k) const { return (*records_)[(*by_id_)[k]]; }
  /// ... or std::out_of_range past the end.
  const Ball& at(std::size_t k) const { return (*records_)[by_id_->at(k)]; }
  const Ball& front() const { return (*this)[0]; }
  const Ball& back() const { return (*this)[size() - 1]; }
  Iterator begin() const { return Iterator(this, 0); }
  Iterator end() const { return Iterator(this, size()); }
  /// A copy of the balls, in id order.
  std::vector<Ball> copy() const { return std::vector<Ball>(begin(), end()); }

private:
  const std::vector<Ball>* records_;
  const std::vector<std::uint32_t>* by_id_;
};

/// The balls, walls and floor, advanced in fixed steps with exact continuous collision
/// detection: every impact inside a step is found at its exact time and handled in
/// time order.
class World
{
public:
  /// Builds the world of a scene; throws std::invalid_argument when check() finds issues.
  explicit World(const Scene& scene, const StepSettings& settings = StepSettings());
  /// ... from `checked`, what check(scene) gave (so that a caller who has checked the
  /// scene does not check and place it again).
  World(const Scene& scene, SceneCheck checked, const StepSettings& settings = StepSettings());
  World(const World&);
  World& operator=(const World&);
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  /// Advances one step of the scene's dt.
  void step();
  /// Back to the scene as constructed.
  void reset();

  double time() const;
  double dt() const;
  const Vec3& gravity() const;
  const Scene& scene() const;
  const StepSettings& stepSettings() const;
  /// The balls in id order (ids only grow, so also the order they were added in).
  BallList balls() const;
  const std::vector<Wall>& walls() const;
  const std::optional<Floor>& floor() const;
  /// The collisions handled in the last step, in the order they were handled; empty
  /// while events are not recorded.
  const std::vector<CollisionEvent>& lastEvents() const;
  /// Whether steps list their collisions in lastEvents() (on at first). Off, a large
  /// world saves the list's memory (88 bytes an event; S1 has 0.14 events per ball and
  /// step, a pile at rest 1.5); stats() counts them either way.
  void recordEvents(bool record);
  bool recordsEvents() const;
  const WorldStats& stats() const;
  /// The friction block of the scene, or none (balls slide without friction).
  const std::optional<FrictionDef>& friction() const;
  /// Changes of motion kind in the last step, in time order (without friction only take-offs
  /// and landings: a ball on the floor is rolling while it moves).
  const std::vector<MotionTransition>& lastTransitions() const;
  /// The balls that dropped into pockets in the last step, in time order; they are out of
  /// balls() already.
  const std::vector<PocketedBall>& lastPocketed() const;

  Energy energy() const;
  Vec3 momentum() const;
  /// Balls off the floor or outside the walls' bounds: 0 in a closed scene.
  int lostBalls() const;
  /// Takes the balls off the floor or outside the walls' bounds out of the world, and
  /// returns them in id order (a ball that left flies on for ever and stretches the
  /// broad phase's grid without end).
  std::vector<LostBall> removeLostBalls();
  /// FNV-1a of the exact bits of time and every ball's state.
  std::uint64_t stateHash() const;
  /// The ball with this id, or nullptr; valid until the world steps or is edited.
  const Ball* findBall(int id) const;
  /// The place of the ball with this id in balls(), or balls().size().
  std::size_t indexOf(int id) const;
  /// The angular velocity of balls()[k]: its own where the world has friction; else that
  /// of rolling without slip, n x v / r, n the floor's normal under it (up without a
  /// floor) [rad/s].
  Vec3 angularVelocity(std::size_t k) const;
  /// How balls()[k] moves: with friction its state; without, rolling while it moves.
  MotionKind motionKind(std::size_t k) const;
  /// k in balls()[k]'s moment of inertia k m r^2 (the scene's where the world keeps no
  /// spins: without friction it plays no part).
  double inertia(std::size_t k) const;

  /// Adds a ball (put on the floor as `landing` says) unless it is invalid, overlaps
  /// something or is off the floor; then nothing changes. Ids start at kFirstId.
  AddResult addBall(const BallDef& def, Landing landing = Landing::kNearest);
  /// Sets what `edit` gives of ball `id` (BallEdit: what it leaves unset is kept), keeping
  /// its id, radius, mass and orientation. Refused, nothing changed, when no ball has the
  /// id, a value is bad, or the ball would be off the floor or overlap a wall or another
  /// ball. Spin and inertia count only where the world has friction.
  AddResult setBallState(int id, const BallEdit& edit);
  /// Adds impulse / mass to ball `id`'s velocity [impulse: N s]. On a floor, a push into it
  /// comes back off it at floorRestitution(); the ball flies where what it then has along
  /// the floor's normal keeps it off the floor for StepSettings::min_flight_time, else the
  /// floor takes that part. Refused, nothing changed,
  /// when no ball has the id or the impulse is not finite or gives a speed past kMaxSpeed.
  AddResult applyImpulse(int id, const Vec3& impulse);
  /// A cue's strike: impulse J [N s] at `offset` [m] from the ball's centre (|offset| at
  /// most its radius): dv = J / m (its part along the floor's normal as applyImpulse()
  /// says: a jump shot), dw = offset x J / (k m r^2)
  /// where the world has friction. Refused, nothing changed, as applyImpulse().
  AddResult strike(int id, const Vec3& impulse, const Vec3& offset);
  /// Adds a wall unless it is degenerate or cuts through a ball.
  AddResult addWall(const WallDef& def);
  /// False when no ball has this id.
  bool removeBall(int id);
  bool removeWall(int id);

private:
  /// Its state and work space (src/core/step/step_context.hpp); a World moved from holds
  /// none, and may only be assigned to or destroyed.
  std::unique_ptr<StepContext> c_;
};
}  // namespace ball_collision_sim::core
