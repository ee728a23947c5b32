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
namespace step
{
struct ExactSettings;  // src/core/step/contact_solver.hpp
}

/// Energy of the world; potential is measured from the origin along gravity.
struct Energy
{
  double kinetic = 0.0;     ///< sum of m |v|^2 / 2 [J]
  double rotational = 0.0;  ///< sum of k m r^2 |w|^2 / 2 where the world has friction, else 0 [J]
  double potential = 0.0;   ///< sum of -m <g, p> [J]
  double total() const { return kinetic + rotational + potential; }
};

/// A ball's own spin, kept where the world has friction.
struct BallSpin
{
  Vec3 angular_velocity = Vec3::Zero();      ///< [rad/s]
  double inertia = kSolidInertia;            ///< k in I = k m r^2
  MotionKind kind = MotionKind::kStationary;
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
};

/// Result of adding or editing an object: ok, or the reason it was refused (the world
/// unchanged).
struct AddResult
{
  bool ok = false;
  int id = -1;
  std::string error;  ///< "radius: must be > 0"
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

/// Ids of balls and walls start here and only grow: 0, the value of a field left empty,
/// names no object.
constexpr int kFirstId = 1;

/// Working memory a World keeps between steps only so as not to allocate it again: not
/// part of its state, so a copy starts without it. T may be incomplete where this is
/// declared, and complete where the owner's special members are defined.
template <class T>
class Scratch
{
public:
  Scratch() = default;
  Scratch(const Scratch& /*other*/) {}
  Scratch& operator=(const Scratch& /*other*/) { return *this; }
  Scratch(Scratch&&) noexcept = default;
  Scratch& operator=(Scratch&&) noexcept = default;
  ~Scratch() = default;
  /// The work space, made on first use.
  T& get()
  {
    if (!held_)
      held_ = std::make_unique<T>();
    return *held_;
  }
  /// The work space a get() made before.
  const T& made() const
  {
    assert(held_);
    return *held_;
  }

private:
  std::unique_ptr<T> held_;
};

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

  double time() const { return static_cast<double>(stats_.steps) * dt_; }
  double dt() const { return dt_; }
  const Vec3& gravity() const { return gravity_; }
  const Scene& scene() const { return scene_; }
  const StepSettings& stepSettings() const { return settings_; }
  /// The balls in id order (ids only grow, so also the order they were added in).
  BallList balls() const { return BallList(balls_, by_id_); }
  const std::vector<Wall>& walls() const { return walls_; }
  const std::optional<Floor>& floor() const { return ground_.floor(); }
  /// The collisions handled in the last step, in the order they were handled; empty
  /// while events are not recorded.
  const std::vector<CollisionEvent>& lastEvents() const { return events_; }
  /// Whether steps list their collisions in lastEvents() (on at first). Off, a large
  /// world saves the list's memory (88 bytes an event; S1 has 0.14 events per ball and
  /// step, a pile at rest 1.5); stats() counts them either way.
  void recordEvents(bool record);
  bool recordsEvents() const { return record_events_; }
  const WorldStats& stats() const { return stats_; }
  /// The friction block of the scene, or none (balls slide without friction).
  const std::optional<FrictionDef>& friction() const { return scene_.friction; }
  /// Changes of motion kind in the last step, in time order (empty without friction).
  const std::vector<MotionTransition>& lastTransitions() const { return transitions_; }

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
  /// Moves ball `id` to `position` (put on the floor as `landing` says) with `velocity`
  /// (less its part normal to the floor), keeping its id, radius, mass and orientation.
  /// Refused, nothing changed, when no ball has the id, a value is bad, or the ball would
  /// be off the floor or overlap a wall or another ball.
  /// With friction, `angular_velocity` sets its spin (unset: rolling without slip) and
  /// `inertia` its k (unset: kept).
  AddResult setBallState(int id, const Vec3& position, const Vec3& velocity, Landing landing = Landing::kUnder,
                         const std::optional<Vec3>& angular_velocity = std::nullopt,
                         const std::optional<double>& inertia = std::nullopt);
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
  struct Motion;
  struct SpinMotion;
  /// How a ball's motion and spin go within the step with friction
  /// (src/core/step/spin_phase.hpp): a type per phase, not a branch in the step.
  struct SpinPhase;
  /// How balls move on this world's ground within a step (src/core/step/floor_motion.hpp):
  /// a type the ground provides, exact paths on a plane or without a floor, chords on a
  /// curved floor.
  struct FloorMotion;
  struct ExactMotion;
  struct ChordMotion;
  using Event = StepEvent;
  /// A resting contact as a constraint of the step: balls a and b (visiting indices), or
  /// ball a and wall w (b = kWallRow | w); next_a and next_b link the rows of each ball.
  struct ContactLink
  {
    std::uint32_t a;
    std::uint32_t b;
    std::uint32_t next_a;
    std::uint32_t next_b;
    /// the last solve's impulse per unit of the step it spanned, its next solve's warm
    /// start (the last step's, until solved in this one)
    double rate;
  };
  static constexpr std::uint32_t kWallRow = 0x80000000u;
  static constexpr std::uint32_t kNone32 = 0xffffffffu;
  /// A group of balls joined by resting contacts, as the contact solver takes it
  /// (src/core/step/contact_group.hpp).
  struct ContactGroup;

  void load(PlacedBalls placed);
  /// After an edit: the next step visits the balls in id order and predicts afresh.
  void forgetOrder();
  /// The ball of `placed`, a definition already put on the floor.
  static Ball makeBall(int id, const BallDef& placed);
  /// The spin record of `placed`, whose foot point is `foot` (worlds with friction); in
  /// flight (`flying`) its spin is its own or none.
  BallSpin makeSpin(const BallDef& placed, const Vec2& foot, bool flying) const;
  /// Why `def` cannot stand in the world (ignoring ball `ignore_id`), or ""; else `def`
  /// is put on the floor as `landing` says, `foot` gets its foot point (u, v) and
  /// `flying` whether it is in flight there (Landing::kAsGiven).
  std::string place(BallDef& def, Landing landing, int ignore_id, Vec2& foot, bool& flying) const;
  /// The box the walls span, which a ball without a floor must not leave; empty without walls.
  Ground::Bounds wallBounds() const;
  /// Why the ball in slot s is out of the world (Ground::whyOff()), or "".
  std::string whyLost(std::size_t s, const Ground::Bounds& bounds) const;
  /// The record of the ball with this id in balls_, or balls_.size().
  std::size_t slotOf(int id) const;
  /// The records in id order again, as an edit leaves them (the next step visits them so).
  void sortById();
  /// Moves the records (balls_, feet_, spins_) so that slot k holds the one that was in
  /// slot from[k]; `from` is left as the identity.
  void permute(std::vector<std::uint32_t>& from);
  /// Ball i's foot point guess in this step (curved floors), or a value the ground does
  /// not read.
  const Vec2& guessOf(std::size_t i) const { return floor_uv_.empty() ? no_foot_ : floor_uv_[i]; }
  Vec2& guessOf(std::size_t i) { return floor_uv_.empty() ? no_foot_ : floor_uv_[i]; }
  /// The foot point of the record in slot s (curved floors), or a value the ground does not read.
  const Vec2& footOf(std::size_t s) const { return feet_.empty() ? no_foot_ : feet_[s]; }

  // The stages of a step, in order.
  void predictMotions();
  /// Ball i's free motion over the next step from its record, and its swept box; at the
  /// step's start (not at the last one's commit, which saw to it) a ball that the floor
  /// cannot hold on its bend leaves it.
  void predictMotion(std::size_t i, bool at_step_start = false);
  void buildBroadPhase();
  void findFirstImpacts();
  void resolveEventsInTimeOrder();
  /// With predict_next, also predicts each ball's motion for the next step (which keeps
  /// this step's visiting order).
  void commitToFloor(bool predict_next);
  /// Ball i to the step's end, on the floor, with its velocity there (the normal kept in
  /// floor_normals_ when `settle`): its move over the step and the normal there.
  struct Committed
  {
    Vec3 moved;
    Vec3 normal;
  };
  Committed commitBall(std::size_t i, bool settle);
  /// Velocities across the step's resting contacts: out of blocked directions, bounced
  /// where gravity closed a pair fast enough, then no closing speed left at any contact
  /// (the contact solver), along the floor.
  void settleRestingVelocities();
  /// Turns ball i by its rolling over the step's move d (its angular velocity follows
  /// from its velocity when asked for: angularVelocity()).
  void roll(std::size_t i, const Vec3& floor_normal, const Vec3& d);

  Vec3 predictedEnd(std::size_t i, const Vec3& p, const Vec3& v, double span);
  Aabb currentBox(std::size_t i) const;
  void detect(std::size_t i);
  void detectWalls(std::size_t i);
  void detectBall(std::size_t i, std::size_t j);
  void resolveBallWall(const Event& event);
  void resolveBallBall(const Event& event);
  /// A ball-ball contact as resolveBallBall() works it out: visiting indices, the normal
  /// from i to j, the floor normals under them, the normal's parts along the floor, the
  /// directions of the impulse on each, and their inverse masses (0: immovable).
  struct PairContact
  {
    std::size_t i, j;
    Vec3 n, na, nb, along_a, along_b, ta, tb;
    double inv_a, inv_b;
  };
  /// Where ball i's chord ends: 1, or on a curved floor where it was cut (cutChord()).
  double chordEnd(std::size_t i) const { return chord_ends_.empty() ? 1.0 : chord_ends_[i]; }
  /// A chord of ball i (from `position` with start velocity v0) longer than the floor
  /// allows (Ground::longestChord()) is cut where it reaches that length, and ends there
  /// on the floor; the ball goes on from there by an event (queueCut(), resolveMotionEnd()).
  void cutChord(std::size_t i, const Vec3& position, const Vec3& v0);
  void queueCut(std::size_t i);
  /// Ball i's motion ends within the step (StepEvent::transition): its friction phase's,
  /// made exact by FrictionLaw::finish(), or its chord at a cut; a new one starts there.
  void resolveMotionEnd(const Event& event);
  // Flight (src/core/step/flight.cpp).
  /// Ball i's motion from its start is a flight: the parabola of gravity (flight_c_),
  /// its spin kept.
  void startFlight(std::size_t i);
  /// Ball i's velocity at x in flight [m/s].
  Vec3 flightVelocity(std::size_t i, double x) const;
  /// Queues where ball i's flight reaches the floor within the step, if it does there
  /// over the floor.
  void queueLanding(std::size_t i);
  /// Where ball i's flight first reaches the floor after its motion's start, as a part of
  /// the rest of the step (at most `rest`), or none.
  std::optional<double> landingIn(std::size_t i, double rest) const;
  /// ... over a plane: the root of a quadratic.
  std::optional<double> landingOverPlane(std::size_t i, double rest) const;
  /// ... over a curved floor: a bracket from samples of the height, refined.
  std::optional<double> landingOverCurve(std::size_t i, double rest) const;
  /// Ball i's flight meets the floor (StepEvent::end kLanding): it bounces at the floor's
  /// restitution, with friction's impulse against the slip of its contact point; a
  /// bounce too low to fly for StepSettings::min_flight_time puts it on the floor.
  void resolveLanding(const Event& event);
  /// A ball on a curved floor at `position` with velocity v leaves it: the floor would
  /// have to pull it to keep it on its bend (the normal force m (kappa |v|^2 + g_n) below
  /// zero, kappa the curvature of the centre's path along v).
  bool leavesFloor(std::size_t i, const Vec3& position, const Vec3& v) const;
  /// The same where its foot point uv and the normal n there are known.
  bool leavesFloorAt(std::size_t i, const Vec2& uv, const Vec3& n, const Vec3& v) const;
  /// The normal force per unit mass the floor gives ball i with foot point uv, normal n
  /// there and velocity v, kappa |v|^2 + g_n [m/s^2]: below zero it would have to pull.
  double floorPush(std::size_t i, const Vec2& uv, const Vec3& n, const Vec3& v) const;
  /// Queues the exact time at which ball i's motion on a curved floor reaches where the
  /// floor's push on it falls to zero, if that is within the motion.
  void queueTakeOff(std::size_t i);
  /// Ball i takes off (StepEvent::end kTakeOff): it flies from where it is on the floor,
  /// with its velocity there.
  void resolveTakeOff(const Event& event);
  /// Ball i leaves the floor at x: in flight from there, its kind recorded.
  void liftOff(std::size_t i, double x);
  /// The restitution of impacts on the floor: the floor's own, else the scene's.
  double floorRestitution() const;
  // Resting groups (src/core/step/resting_groups.cpp).
  /// The step's resting contacts at its start: touching pairs and walls that close no
  /// faster than they rest, each group of balls they join solved together.
  void formRestingGroups();
  /// The group of ball i (its union-find root), or kNone32.
  std::uint32_t groupOf(std::size_t i);
  /// The groups' per-ball data, made for the step at its first contact.
  void startGroups();
  /// Ball i is in a group (alone, if it was in none).
  void joinGroup(std::size_t i);
  /// The groups of balls i and j become one.
  void mergeGroups(std::size_t i, std::size_t j);
  /// Whether ball i is in a resting group this step.
  bool grouped(std::size_t i) const { return !group_parent_.empty() && group_parent_[i] != kNone32; }
  /// Whether ball i has a contact with `other` (a ball's visiting index, or kWallRow | w).
  bool linked(std::size_t i, std::uint32_t other) const;
  /// A resting contact between ball a and `other` (a ball, or kWallRow | w).
  void link(std::size_t a, std::uint32_t other);
  /// Ball i, on its group's motion, takes a change of velocity dv at x, where it is at
  /// `position` (its group is to be solved again).
  void takeImpulse(std::size_t i, double x, const Vec3& position, const Vec3& dv);
  /// Ball i's velocity at x on its group's motion: its velocity where the motion starts,
  /// plus the share so far of the impulses that its solve gave it over the rest of the
  /// step (gravity's and its contacts', spread evenly); the motion's own at the step's end.
  Vec3 groupVelocityAt(std::size_t i, double x) const;
  /// The kinetic energy an impulse at x that takes ball i's velocity from `before` to
  /// `after` (its chord's, as the impact sees it) gives it [J].
  double impulseEnergy(std::size_t i, double x, const Vec3& before, const Vec3& after) const;
  /// The motions of the group of ball i from x on: each member's free motion from where it
  /// is at x, with no contact of the group closing by more than its gap (the contact
  /// solver); each member gets the new motion, and mid-step (x > 0) is detected again.
  void solveGroup(std::size_t i, double x);
  /// The stages of formRestingGroups(): the resting contacts with walls, and between
  /// balls, within `reach` [m] at the step's start, linked; how near a contact closing at
  /// its resting speed, pulled along the floor at `pull`, must be to be linked [m].
  void linkRestingWalls(double reach);
  void linkRestingPairs(double reach);
  double speculativeReach(double rest_speed, double pull) const;
  /// The contacts of the group being solved (members_), exactly, from free_u_ over the
  /// rest of the step, `rest`: contact_group_'s u and impulses.
  void solveGroupContacts(ContactGroup& group, double span, double slack);
  /// Each member of the group solved gets its motion from x over `span` (and with
  /// friction, the spin of rolling with it).
  void finishGroup(double x, double span);
  /// The stages of solveGroup(): the members of ball i's group, in id order (members_);
  /// where they are at x, their velocities there and what gravity adds per unit of the
  /// step; the part of the rest of the step the solve spans; the rows of their contacts
  /// (contact_group_); their motions over the span, solved.
  void gatherGroup(std::size_t i);
  void startMembers(double x);
  double groupSpan(double x) const;
  void makeRows(double span);
  void solveRows(double span);
  /// Ball i rolls in its group, under a floor of normal n: friction holds rolling there.
  bool rollsInGroup(std::size_t i, const Vec3& n) const;
  /// What an impulse along the floor moves ball i by, in a group: 1 / m, and where it
  /// rolls (rolls) 1 / ((1 + k) m) [1/kg].
  double groupInverseMass(std::size_t i, bool rolls) const;
  /// Ball i's motion starts anew at x from `position` with velocity v0 (its record, and
  /// where the step started it).
  void beginMotion(std::size_t i, double x, const Vec3& position, const Vec3& v0);
  /// The contacts of the step's groups that touch at its end, as the contact solver takes
  /// them, and the resting contacts that sleeping reads.
  ContactGroup& endGroup();
  /// The step's contacts in the order of their keys (linkKey()), made at the commit.
  const std::vector<std::uint32_t>& linksInKeyOrder();
  /// The key of a contact of ball a with `other` by ids, whatever the records' order.
  std::uint64_t linkKey(std::size_t a, std::uint32_t other) const;
  /// No contact of the step's groups overlaps at its end: the overlapping ones opened by
  /// moves along the floor, solved together (a few passes, each ball back on the floor
  /// after each).
  void separateAtEnd();
  /// separateAtEnd()'s rows (contact_group_): the step's contacts within touch_slack, each
  /// to close by no more than its gap along the floor; the deepest overlap [m].
  double separationRows();

  /// Each group ends the step with no more energy than its members had at its start plus
  /// what impacts gave them: where the time step gives more, its velocities are scaled down.
  void boundGroupEnergies();
  /// Ball i's energy [J], kinetic with velocity v at position p (and where friction
  /// grips, its spin's, the spin it has now), and potential.
  double energyOf(std::size_t i, const Vec3& p, const Vec3& v) const
  {
    const Ball& ball = balls_[i];
    double e = ball.mass * (0.5 * v.squaredNorm() - gravity_.dot(p));
    if (friction_ && friction_->grips())
      e += 0.5 * spins_[i].inertia * ball.mass * ball.radius * ball.radius * spins_[i].angular_velocity.squaredNorm();
    return e;
  }
  /// After an impact: its balls' groups solved again from its time on, or the balls
  /// detected again.
  void goOnAfter(const Event& event);
  /// Ball i's velocity v after an impact's impulse at x, where it is at p on the floor
  /// with this normal (`before`: its velocity before): its new motion, or its group's
  /// free velocity; what the impulse gave it counts toward the energy its group may end
  /// with.
  void takeVelocity(std::size_t i, double x, const Vec3& p, const Vec3& normal, const Vec3& before, const Vec3& v);
  /// Ball i's new motion from x on, from `position` with `velocity` (`impact`: an impact
  /// gave it, not a resting contact or a chord's or phase's end).
  void startMotion(std::size_t i, double x, const Vec3& position, const Vec3& velocity, bool impact);
  void countEvent(std::size_t i);
  /// Ball i has a new motion that no event of its own made (its group's): what was
  /// predicted for it is stale, and its box follows the motion.
  void renewMotion(std::size_t i);
  /// Ball i's energy has run out where its motion starts (a turning point): it has no
  /// motion and no speed from there (until an event gives it some); with friction its
  /// spin then follows its contacts (constrainSpin()).
  void stop(std::size_t i);
  /// An impact between balls i and j closing at `closing` along their normal wakes the
  /// group of the one asleep, where it is faster than the pair's resting speed.
  void wakeOnImpact(std::size_t i, std::size_t j, double closing, double rest_speed);
  /// Wakes sleeping ball i, and the sleeping balls that touch it, and those that touch
  /// them: the group it rests in. Their motions start at the next step.
  void wakeGroup(std::size_t i);
  /// After the step's resting contacts are settled: counts the balls that lean on
  /// something while all but still, and puts to sleep each group of them held together
  /// by resting contacts whose every ball has been so for sleep_steps steps.
  void sleepStillGroups();
  /// Every ball awake (an edit of the walls: what held a group may be gone).
  void wakeAll();
  /// Wakes the sleeping balls that touch a ball of `radius` at `position` (an edit there:
  /// what they lean on may have changed; the rest of their group wakes as they move).
  void wakeTouching(const Vec3& position, double radius);
  /// Whether a wall parts two balls that touch (they then lean on it, not on each other).
  bool wallBetween(const Ball& a, const Ball& b) const;
  void recordEvent(CollisionEvent::Kind kind, int ball, int other, const Vec3& point, const Vec3& normal,
                   double impulse, double closing, bool resting, const Event& event);
  Vec3 positionAt(std::size_t i, double x) const;
  /// Ball i's motion's rate of change at x, per unit of x [m], and its parabola term (zero for a chord).
  Vec3 rateAt(std::size_t i, double x) const;
  Vec3 parabolaOf(std::size_t i) const;
  /// The parabola term of ball i's free motion: the world's path_c_, or with friction its own.
  const Vec3& pathTerm(std::size_t i) const;

  // Friction (src/core/step/friction.cpp).
  /// Ball i's friction phase from x on, from its start velocity and spin_motions_[i].w0;
  /// a change of motion kind is recorded when `record`. A phase without friction force
  /// (a frictionless SpinPhase) is left for the caller to move as a frictionless ball,
  /// and on a curved floor every moving phase to move on its chord under
  /// SpinMotion::pull: returns whether the caller is to move it. On a curved floor a ball
  /// that was rolling, and not hit (`impact`), rolls on under the normal where it is now.
  bool startFriction(std::size_t i, double x, bool record, bool impact);
  /// Ball i has no motion for the rest of the step (frozen by the cap, or asleep): its
  /// spin stays as it is.
  void keepSpin(std::size_t i);
  /// Ball i's motion from its start on is not its phase's (its group's, or stopped where
  /// its energy ran out): its spin follows FrictionLaw::constrained().
  void constrainSpin(std::size_t i);
  /// Records a transition at x where ball i's kind is not the one last reported.
  void recordKind(std::size_t i, double x);
  Vec3 spinAt(std::size_t i, double x) const;
  /// Ball i's spin at an event at x where its velocity is v on the floor with this normal:
  /// spinAt(), and on a curved floor a rolling ball's rolling with v (never more energy).
  Vec3 spinAtEvent(std::size_t i, double x, const Vec3& normal, const Vec3& v) const;
  /// Queues the end of ball i's phase when it falls within the step.
  void queueTransition(std::size_t i);
  /// An impact with friction, the balls' spins at it in SpinMotion::w0: the tangential
  /// impulse (ball_ball and wall friction) opposing the slip of the touching points, at
  /// most mu times the normal impulse (0 for a resting contact), never reversing the slip.
  void ballBallFriction(const PairContact& c, double normal_impulse, Vec3& va, Vec3& vb);
  /// The same at a wall; n is the contact normal toward the wall.
  void ballWallFriction(std::size_t i, const Vec3& n, const Vec3& floor_normal, double normal_impulse, Vec3& v);
  /// The friction laws under the floor's normal n (the plane's, or on a curved floor the
  /// local one).
  FrictionLaw frictionUnder(const Vec3& n) const;
  /// What pulls ball i's chord on a curved floor: gravity, and with friction the phase's
  /// friction force per unit mass [m/s^2].
  const Vec3& pullOf(std::size_t i) const;
  /// |v|^2 of ball i at x where its motion's chord is at p, from the energy: on a curved
  /// floor a sliding ball's is what gravity's work along the chord leaves after its spin's
  /// change and the slip's loss, mu_s g_n (|u0| t - rate t^2 / 2); elsewhere |v0|^2 +
  /// 2 <pull, p - p0> [m^2/s^2].
  double speedSquaredAt(std::size_t i, double x, const Vec3& p) const;
  /// |v0|^2 + 2 <pull, p - p0>: ball i's speed squared at p where its pull does all the
  /// work [m^2/s^2].
  double pulledSpeedSquared(std::size_t i, const Vec3& p) const;
  /// |v|^2 where ball i's chord b ends, `rest` of the step on, with its pull's work along
  /// the chord (linear in b).
  double linearChordSpeedSquared(std::size_t i, double rest, const Vec3& b) const
  {
    return startVelocity(i).squaredNorm() + 2 * rest * pullOf(i).dot(b);
  }
  /// Turns ball i by the rotation vector `angle` [rad].
  void turn(std::size_t i, const Vec3& angle);
  /// The spin of a ball defined by `def` on the floor with normal n: its own, or rolling's.
  static Vec3 spinOf(const BallDef& def, const Vec3& n);
  /// Ball i's inverse mass in the step's responses: 0 while frozen (it does not give way).
  double inverseMass(std::size_t i) const;  // (step_types.hpp)
  /// While the step runs, a ball's position and velocity are those at the start of its
  /// motion (Motion::x0); where the step started it, step_starts_ keeps once it moved on.
  Vec3& startPosition(std::size_t i) { return balls_[i].position; }
  const Vec3& startPosition(std::size_t i) const { return balls_[i].position; }
  Vec3& startVelocity(std::size_t i) { return balls_[i].velocity; }
  const Vec3& startVelocity(std::size_t i) const { return balls_[i].velocity; }
  Vec3 floorNormalAt(std::size_t i, const Vec3& position) const;
  /// Where the ball i centred at q is put back on the floor (q itself without a floor).
  Vec3 onFloor(std::size_t i, const Vec3& q) const;
  /// The speed ball i's motion would end with, from its energy at the motion's start.
  struct EnergyCheck
  {
    const World* world;
    std::size_t i;
    double rest;  ///< the part of the step the motion runs for
    /// |v|^2 at the step's end with the displacement b per unit of x, put on the floor
    double speedSquaredWith(const Vec3& b) const;
    /// ... with the motion cut to the fraction s of its chord
    double speedSquared(double s) const;
    /// ... where the chord itself ends: a motion kept out of its blocked directions can
    /// end off the floor, higher than the floor under its end
    double chordSpeedSquared(const Vec3& b) const;
  };
  Vec3 onFloorVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const;
  /// The contact solver's exact stage as settings_ ask (step_types.hpp).
  step::ExactSettings exactSettings() const;
  /// The direction a wall pushes a ball along, n the unit normal from the ball toward it:
  /// n's part along the floor with this normal, or n itself where the floor all but faces
  /// the wall (a wall parallel to the floor is met in space).
  Vec3 wallPush(const Vec3& n, const Vec3& floor_normal) const;
  /// The closing speed at or below which an impact at restitution e is a resting contact.
  /// (At a ball of this radius centred at `position`: the round-off of positions there.)
  double restingSpeed(const Vec3& floor_normal, double restitution, const Vec3& position, double radius) const;
  /// The resting speed of a contact between two balls at the scene's restitution: the
  /// larger of the two balls' (whichever floor is which).
  double pairRestingSpeed(const Vec3& na, const Vec3& pa, double ra, const Vec3& nb, const Vec3& pb, double rb) const;
  /// A ball slower than this is all but still: gravity along the floor gives it as much
  /// in resting_steps steps [m/s].
  double stillSpeed(const Vec3& floor_normal) const;

  Scene scene_;
  StepSettings settings_;
  double dt_;
  /// sleep_time in steps of dt (at least one, at most what Ball::quiet_steps counts)
  std::uint16_t sleep_steps_ = 1;
  Vec3 gravity_;
  Ground ground_;
  /// The ground's motion type (FloorMotion::of(ground_)); the step asks it whatever
  /// depends on the kind of floor.
  const FloorMotion* floor_motion_ = nullptr;
  /// The parabola term of flights, g dt^2 / 2 [m].
  Vec3 flight_c_ = Vec3::Zero();
  /// Balls whose predicted motion for the step is a flight (their landings are looked
  /// for at its start only where there are some).
  std::uint32_t flights_ = 0;
  /// The parabola term of free balls' motions, a dt^2 / 2 with the ground's path
  /// acceleration a [m]; parabolas_ where it is not zero.
  Vec3 path_c_ = Vec3::Zero();
  /// Free balls without friction move on parabolas (path_c_ not zero).
  bool free_parabolas_ = false;
  /// Some motions are parabolas: free_parabolas_, or a world with friction, where each
  /// ball's phase has its own (SpinMotion::c).
  bool parabolas_ = false;
  std::vector<Wall> walls_;
  /// The balls' records in the order the step visits them (its work space is indexed the
  /// same way): a recent step's cell order, so that neighbours in space are neighbours in
  /// memory; in id order after an edit.
  std::vector<Ball> balls_;
  /// The slot in balls_ of the ball with the k-th lowest id (balls() lists them so).
  std::vector<std::uint32_t> by_id_;
  /// Curved floors: each ball's foot point (u, v), beside balls_ (empty otherwise).
  std::vector<Vec2> feet_;
  int next_ball_id_ = 0;
  int next_wall_id_ = 0;
  WorldStats stats_;

  /// Steps since the records were put in cell order; they are so anew every
  /// settings_.reorder_steps steps.
  std::uint32_t order_age_ = 0;
  /// motions_ (and the grid's boxes) hold the next step's predicted motions.
  bool motions_ready_ = false;
  // per-step work space, kept between steps to avoid allocation
  std::vector<Motion> motions_;
  /// Per ball, where step_starts_ keeps the position it had at the step's start, once a
  /// new motion started elsewhere (startMotion()); kNoStepStart while it has none.
  std::vector<std::uint32_t> step_start_of_;
  std::vector<Vec3> step_starts_;
  static constexpr std::uint32_t kNoStepStart = 0xffffffffu;
  EventQueue queue_;
  StepGrid grid_;
  std::vector<Aabb> wall_boxes_;  ///< the walls' boxes, handed to the grid each step (its obstacles)
  std::vector<Vec3> floor_normals_;
  std::vector<Vec2> floor_uv_;  ///< curved floors: each ball's last foot point, Newton's guess
  std::vector<double> chord_ends_;  ///< curved floors: where each ball's chord ends (chordEnd())
  Vec2 no_foot_ = Vec2(0.5, 0.5);  ///< the foot point where the ground keeps none
  std::vector<CollisionEvent> events_;
  bool record_events_ = true;
  /// Resting groups: per ball its union-find parent (kNone32: in none), the next member of
  /// its group (a ring), and its first contact; the step's contacts.
  std::vector<std::uint32_t> group_parent_;
  std::vector<std::uint32_t> group_next_;
  std::vector<std::uint32_t> first_link_;
  std::vector<ContactLink> links_;
  /// per ball: its motion is its group's (a chord at the constant velocity it starts with),
  /// and its velocity where that motion starts, before the step's impulses
  std::vector<std::uint8_t> group_motion_;
  std::vector<Vec3> group_velocity_;
  std::vector<std::uint32_t> row_links_;
  std::vector<std::uint32_t> link_order_;
  /// each contact's last impulse, by its balls' ids (and wall), for the next step's warm start
  std::unordered_map<std::uint64_t, double> warm_;
  std::vector<std::uint32_t> members_;
  std::vector<Vec3> member_positions_;
  std::vector<Vec3> member_normals_;
  std::vector<Vec3> member_velocities_;
  std::vector<Vec3> free_u_;
  /// per member of the group being solved: its motion before rolling resistance [m],
  /// gravity's pull [m/s per unit of the step], the most resistance takes from it [m per
  /// unit of the step], whether it rolls, and what resistance took [m]
  std::vector<Vec3> base_u_;
  std::vector<Vec3> member_pulls_;
  std::vector<double> member_caps_;
  std::vector<char> member_rolls_;
  std::vector<Vec3> resisted_;
  /// per ball: its energy at the step's start plus what its impacts in the step gave it
  /// [J]; a group ends the step with no more than its members' sum
  std::vector<double> energy_ref_;
  /// the contact solver's work space
  Scratch<ContactGroup> contact_group_;

  /// With friction: the laws under the plane's normal, each ball's spin beside balls_,
  /// the step's phases by visiting index, and the step's changes of kind.
  std::optional<FrictionLaw> friction_;
  std::vector<BallSpin> spins_;
  std::vector<SpinMotion> spin_motions_;
  std::vector<MotionTransition> transitions_;
};
}  // namespace ball_collision_sim::core
