// The world's state and the step's per-ball work space, as plain data: the balls'
// records and spins, the walls and ground, and what each step predicts, queues, groups
// and solves per ball. StepContext (step_context.hpp) adds what reads and writes it.
#pragma once

#include "ball_collision_sim/core/floor_flow.hpp"
#include "ball_collision_sim/core/world.hpp"

#include <cassert>
#include <memory>
#include <unordered_map>

namespace ball_collision_sim::core
{
namespace step
{
struct ExactSettings;  // src/core/step/contact_solver.hpp
class Workers;         // src/core/step/workers.hpp
struct Tally;
}

/// A ball's own spin, kept where the world has friction.
struct BallSpin
{
  Vec3 angular_velocity = Vec3::Zero();      ///< [rad/s]
  double inertia = kSolidInertia;            ///< k in I = k m r^2
  MotionKind kind = MotionKind::kStationary;
};

/// Working memory a StepContext keeps between steps only so as not to allocate it again: not
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

/// What a World is made of between and within steps; every stage of the step reads and
/// writes it through StepContext.
struct StepState
{
  StepState(const Scene& scene, const StepSettings& settings);

  struct Motion;
  struct SpinMotion;
  /// How a ball's motion and spin go within the step with friction
  /// (src/core/step/spin_phase.hpp): a type per phase, not a branch in the step.
  struct SpinPhase;
  /// What a ball's spin is in the step, by whether friction acts (src/core/step/spin_model.hpp):
  /// a type the scene provides, not a branch in the step.
  struct SpinModel;
  /// How balls move on this world's ground within a step (src/core/step/floor_motion.hpp):
  /// a type the ground provides, exact paths on a plane or without a floor, chords on a
  /// curved floor.
  struct FloorMotion;
  struct ExactMotion;
  struct PathMotion;
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
  /// The scene's spin type (SpinModel::of()); the step asks it whatever depends on friction.
  const SpinModel* spin_ = nullptr;
  /// The parabola term of flights, g dt^2 / 2 [m].
  Vec3 flight_c_ = Vec3::Zero();
  /// Flights started since the step's motions were predicted (startFlight()): while
  /// there are none, no motion is a flight, so that landings are not looked for and
  /// pairs on a level plane take the straight sweep without asking.
  std::uint32_t flights_ = 0;
  /// The parabola term of free balls' motions (MotionType::kPath), a dt^2 / 2 with the
  /// ground's path acceleration a (PathMotion: where it is not zero) [m].
  Vec3 path_c_ = Vec3::Zero();
  /// A line's parabola term [m].
  Vec3 zero_c_ = Vec3::Zero();
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
  /// the walls' boxes, then the floor's edges' (edge_boxes_), handed to the grid each step
  /// (its obstacles)
  std::vector<Aabb> wall_boxes_;
  std::vector<Aabb> edge_boxes_;  ///< floorEdgeBoxes()
  /// A ball slower than this on the floor cannot take off from its bend anywhere
  /// (takeOffSpeedSquared(); infinite where the ground does not bend, or bends only
  /// toward its normal) [m^2/s^2].
  double take_off_speed2_ = 0.0;
  std::vector<Vec3> floor_normals_;
  std::vector<Vec2> floor_uv_;  ///< curved floors: each ball's last foot point, Newton's guess
  std::vector<double> chord_ends_;  ///< curved floors: where each ball's chord ends (chordEnd())
  /// curved floors: where a ball's chord ends as its laws take it (FloorFlow), its
  /// velocity there, and the x it holds at (-1: none; the chord is the first-order one)
  struct FlowEnd
  {
    Vec3 velocity = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();  ///< the floor's there
    Vec3 spin = Vec3::Zero();     ///< sliding, free: the spin there
    double spin_n = 0.0;          ///< rolling: the spin about the normal there
    double x = -1.0;
    std::uint8_t ends = kPhaseRuns;  ///< what ended it there (PhaseEnd bits; kTakesOff: it leaves the floor)
  };
  std::vector<FlowEnd> flow_ends_;
  Vec2 no_foot_ = Vec2(0.5, 0.5);  ///< the foot point where the ground keeps none
  std::vector<CollisionEvent> events_;
  bool record_events_ = true;
  /// Resting groups: per ball its union-find parent (kNone32: in none), the next member of
  /// its group (a ring), and its first contact; the step's contacts.
  std::vector<std::uint32_t> group_parent_;
  std::vector<std::uint32_t> group_next_;
  std::vector<std::uint32_t> first_link_;
  std::vector<ContactLink> links_;
  /// per ball following its group (MotionType::kGrouped): its velocity where that motion
  /// starts, before the step's impulses
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
  /// with friction at the contacts, the members' spins before the solve [rad/s]
  std::vector<Vec3> free_w_;
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
  /// The threads the per-ball stages run on (forEachBall()), and what each run of balls
  /// recorded, made at the first loop split among them; a copy starts without them.
  Scratch<step::Workers> workers_;
  Scratch<std::vector<step::Tally>> tallies_;

  /// With friction: the laws under the plane's normal, each ball's spin beside balls_,
  /// the step's phases by visiting index, and the step's changes of kind.
  std::optional<FrictionLaw> friction_;
  std::vector<BallSpin> spins_;
  std::vector<SpinMotion> spin_motions_;
  std::vector<MotionTransition> transitions_;
  /// The step's pocketed balls, in time order (World::lastPocketed()).
  std::vector<PocketedBall> pocketed_;
};
}  // namespace ball_collision_sim::core
