// The world's lifecycle, the step as its named stages (each in src/core/step/) and
// the queries; the edits between steps are in edits.cpp.
#include "step_context.hpp"
#include "stages.hpp"
#include "flight.hpp"

#include "contact_group.hpp"
#include "floor_motion.hpp"
#include "spin_model.hpp"
#include "workers.hpp"

#include "ball_collision_sim/core/state_hash.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ball_collision_sim::core
{
using namespace step;

StepContext::StepContext(const Scene& scene, const StepSettings& settings) : StepContext(scene, check(scene), settings)
{
}

StepState::StepState(const Scene& scene, const StepSettings& settings)
    : scene_(scene)
    , settings_(settings)
    , dt_(scene.dt)
    , gravity_(scene.gravity)
    , ground_(scene.floor, scene.gravity, settings)
    , floor_motion_(&FloorMotion::of(ground_))
    , spin_(&SpinModel::of(scene.friction.has_value()))
    , flight_c_((0.5 * scene.dt * scene.dt) * scene.gravity)
    , path_c_((0.5 * scene.dt * scene.dt) * ground_.pathAcceleration())
{
}

StepContext::StepContext(const Scene& scene, SceneCheck checked, const StepSettings& settings)
    : StepState(scene, settings)
{
  if (!checked.issues.empty())
    throw std::invalid_argument(joinIssues(checked.issues));
  // (the plane's laws; on a curved floor each ball's are found under its normal)
  if (scene.friction)
    friction_.emplace(*scene.friction, ground_.flatNormal(),
                      scene.gravity, ground_.pathAcceleration(), settings_.slip_tolerance,
                      settings_.resting_speed_floor);
  // (a ball's event count is kept in 12 bits, up to one past the cap)
  if (settings_.max_events_per_ball_step > kMaxEventCap)
    throw std::invalid_argument("max_events_per_ball_step: must be at most " + std::to_string(kMaxEventCap));
  // (a chord of no length would be cut again and again where it starts)
  if (!(settings_.chord_turn > 0))
    throw std::invalid_argument("chord_turn: must be > 0");
  if (!(settings_.chord_sag > 0))
    throw std::invalid_argument("chord_sag: must be > 0");
  take_off_speed2_ = step::takeOffSpeedSquared(*this);
  sleep_steps_ = static_cast<std::uint16_t>(std::clamp(std::ceil(settings_.sleep_time / dt_), 1.0, 65535.0));
  load(std::move(checked.balls));
}

StepContext::StepContext(const StepContext&) = default;
StepContext& StepContext::operator=(const StepContext&) = default;
StepContext::StepContext(StepContext&&) noexcept = default;
StepContext& StepContext::operator=(StepContext&&) noexcept = default;
StepContext::~StepContext() = default;

void StepContext::load(PlacedBalls placed)
{
  walls_.clear();
  next_wall_id_ = kFirstId;
  for (const WallDef& def : scene_.walls)
    walls_.emplace_back(next_wall_id_++, def, scene_.restitution);
  edge_boxes_ = step::floorEdgeBoxes(*this);
  balls_.clear();
  by_id_.clear();
  feet_.clear();
  spins_.clear();
  next_ball_id_ = kFirstId;
  // (the records taken over as they are, not copied: loading holds one list of them)
  balls_ = std::move(placed.balls);
  by_id_.resize(balls_.size());
  for (std::size_t k = 0; k < balls_.size(); ++k)
  {
    by_id_[k] = static_cast<std::uint32_t>(k);
    balls_[k].id = next_ball_id_++;
  }
  spin_->makeSpins(*this, placed.feet);
  if (floor_motion_->keepsFeet())
    feet_ = std::move(placed.feet);
  stats_ = WorldStats{};
  events_.clear();
  transitions_.clear();
  forgetOrder();
}

void StepContext::reset()
{
  load(placeBalls(scene_));
}

void StepContext::forgetOrder()
{
  sortById();
  order_age_ = 0;
  motions_ready_ = false;
}

Ball StepContext::makeBall(int id, const BallDef& placed)
{
  Ball ball = ballRecord(placed);
  ball.id = id;
  return ball;
}

BallSpin StepContext::makeSpin(const BallDef& placed, const Vec2& foot, bool flying) const
{
  BallSpin spin;
  if (flying)
  {
    spin.angular_velocity = placed.angular_velocity ? *placed.angular_velocity : Vec3::Zero();
    spin.inertia = placed.inertia;
    spin.kind = MotionKind::kFlying;
    return spin;
  }
  const FrictionLaw law = frictionUnder(ground_.normalAt(placed.position, foot));
  spin.angular_velocity = spinOf(placed, law.normal());
  spin.inertia = placed.inertia;
  spin.kind = law.kindOf(placed.inertia, placed.radius, placed.velocity, spin.angular_velocity);
  return spin;
}

// ---- the step ------------------------------------------------------------------------

void step::startStep(StepContext& c)
{
  c.events_.clear();
  c.transitions_.clear();
  c.pocketed_.clear();
  // (each commit takes back what it kept of where balls started; a step cut short, or
  // balls added or removed since, leave that to do here)
  if (!c.step_starts_.empty() || c.step_start_of_.size() != c.balls_.size())
    c.step_start_of_.assign(c.balls_.size(), StepState::kNoStepStart);
  c.step_starts_.clear();
}

void StepContext::step()
{
  // (the stages: stages.hpp)
  startStep(*this);
  predictMotions(*this);            // each ball's free motion over the step, on the floor, and its swept box
  buildBroadPhase(*this);           // the swept boxes into a uniform grid
  formRestingGroups(*this);         // resting contacts as constraints, each group's motions solved
  findFirstImpacts(*this);          // exact times of impact of nearby pairs and walls
  resolveEventsInTimeOrder(*this);  // earliest first; re-detect only the balls involved
  // The next step visits the balls in this step's cell order, so that neighbours in
  // space are neighbours in memory too; not after every step, as balls move less than a
  // cell in one: while the order stays, the commit predicts the next step's motions, with
  // each ball's record at hand.
  const bool reorder = grid_.inCellOrder() && (order_age_ == 0 || order_age_ >= settings_.reorder_steps);
  commitToFloor(*this, !reorder);  // every ball to the step's end, back on the floor
  // (the step's changes of kind in time order: the commit reports kinds that began
  // before events its balls met later, and its threads report in their own order)
  std::stable_sort(transitions_.begin(), transitions_.end(), [](const MotionTransition& a, const MotionTransition& b) {
    return a.time < b.time || (a.time == b.time && a.ball < b.ball);
  });
  if (reorder)
  {
    std::vector<std::uint32_t> from;
    grid_.takeCellOrder(from);  // the slots in the grid's cell order
    permute(from);
  }
  order_age_ = reorder ? 1 : order_age_ + 1;
  motions_ready_ = !reorder;
  ++stats_.steps;
  removePocketed();  // (the balls that dropped into pockets leave the world)
}

// ---- queries -------------------------------------------------------------------------

std::size_t StepContext::rankOf(int id) const
{
  // by_id_ lists the records in id order.
  const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), id,
                                   [this](std::uint32_t s, int v) { return balls_[s].id < v; });
  return it != by_id_.end() && balls_[*it].id == id ? static_cast<std::size_t>(it - by_id_.begin()) : by_id_.size();
}

std::size_t StepContext::slotOf(int id) const
{
  const std::size_t k = rankOf(id);
  return k < by_id_.size() ? by_id_[k] : balls_.size();
}

}  // namespace ball_collision_sim::core
