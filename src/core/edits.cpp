// Edits between steps: adding, moving, striking and removing balls, adding and removing
// walls. Each checks its input first and changes nothing when it refuses. Reads and
// writes balls_, spins_, feet_, walls_; an edit forgets the step's visiting order and
// wakes the sleeping balls it touches (a wall's, all: what held them may have changed).
#include "step/step_context.hpp"

#include "step/floor_motion.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/placement.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ball_collision_sim::core
{

std::string StepContext::place(BallDef& def, Landing landing, int ignore_id, Vec2& foot, bool& flying) const
{
  const std::vector<SceneIssue> issues = validateBall(def, "");
  if (!issues.empty())
    return joinIssues(issues);
  const std::string why = placeAmongWalls(
      def, ground_.floor(), walls_, landing, &foot, [&](std::size_t k) { return "wall " + std::to_string(walls_[k].id); },
      &flying);
  if (!why.empty())
    return "position: " + why;
  for (const Ball& other : BallList(balls_, by_id_))  // (the first in id order is named)
  {
    const double depth = def.radius + other.radius - (def.position - other.position).norm();
    if (other.id != ignore_id && depth > kContactTolerance)
      return "position: " + overlapMessage("ball " + std::to_string(other.id), depth);
  }
  return "";
}

AddResult StepContext::addBall(const BallDef& def, Landing landing)
{
  AddResult result;
  BallDef placed = def;
  Vec2 foot(0.5, 0.5);
  bool flying = false;
  result.error = place(placed, landing, -1, foot, flying);
  if (!result.error.empty())
    return result;
  result.ok = true;
  // (room first, so that the lists stay in step: the last pushes cannot throw)
  if (balls_.size() == balls_.capacity())
    balls_.reserve(2 * balls_.size() + 1);
  if (by_id_.size() == by_id_.capacity())
    by_id_.reserve(2 * by_id_.size() + 1);
  if (friction_ && spins_.size() == spins_.capacity())
    spins_.reserve(2 * spins_.size() + 1);
  if (floor_motion_->keepsFeet())
    feet_.push_back(foot);
  if (friction_)
    spins_.push_back(makeSpin(placed, foot, flying));
  by_id_.push_back(static_cast<std::uint32_t>(balls_.size()));  // (the highest id yet)
  balls_.push_back(makeBall(next_ball_id_, placed));
  balls_.back().flying = flying;
  result.id = next_ball_id_++;
  forgetOrder();
  return result;
}

namespace
{
AddResult refused(int id, std::string error)
{
  AddResult result;
  result.id = id;
  result.error = std::move(error);
  return result;
}
}  // namespace

AddResult StepContext::setBallState(int id, const Vec3& position, const Vec3& velocity, Landing landing,
                               const std::optional<Vec3>& angular_velocity, const std::optional<double>& inertia)
{
  const std::size_t k = indexOf(id);
  if (k == by_id_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  const std::size_t s = by_id_[k];
  AddResult result;
  result.id = id;
  BallDef def;
  def.position = position;
  def.velocity = velocity;
  def.radius = balls_[s].radius;
  def.mass = balls_[s].mass;
  def.angular_velocity = angular_velocity;
  def.inertia = inertia ? *inertia : this->inertia(k);
  Vec2 foot(0.5, 0.5);
  bool flying = false;
  result.error = place(def, landing, id, foot, flying);
  if (!result.error.empty())
    return result;
  // (what leaned on it where it was wakes, and what it touches where it is, and itself)
  wakeTouching(balls_[s].position, balls_[s].radius);
  wakeTouching(def.position, def.radius);
  balls_[s].position = def.position;
  balls_[s].velocity = def.velocity;
  balls_[s].flying = flying;
  balls_[s].asleep = false;
  balls_[s].quiet_steps = 0;  // (the ball the edit moved counts its still steps again)
  if (friction_)
    spins_[s] = makeSpin(def, foot, flying);
  if (floor_motion_->keepsFeet())
    feet_[s] = foot;
  forgetOrder();
  result.ok = true;
  return result;
}

AddResult StepContext::applyImpulse(int id, const Vec3& impulse)
{
  return strike(id, impulse, Vec3::Zero());
}

AddResult StepContext::strike(int id, const Vec3& impulse, const Vec3& offset)
{
  const std::size_t s = slotOf(id);
  if (s == balls_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  if (!impulse.allFinite())
    return refused(id, "impulse: must be finite");
  if (!offset.allFinite())
    return refused(id, "offset: must be finite");
  // (within kContactTolerance of the surface is on it)
  if (offset.norm() > balls_[s].radius + kContactTolerance)
    return refused(id, "offset: must be at most the ball's radius " + formatNumber(balls_[s].radius) + " m from its centre (got " +
                           formatNumber(offset.norm()) + " m)");
  AddResult result;
  result.id = id;
  Ball& ball = balls_[s];
  Vec3 velocity = ball.velocity + impulse / ball.mass;
  bool flying = ball.flying;
  if (ground_.floor() && !flying)
  {
    // Pressed into the floor, the ball comes back off it at the floor's restitution (a
    // jump shot); lifted enough to stay off it for min_flight_time, it flies; else the
    // floor takes the part along its normal.
    const Vec3 n = ground_.normalUnder(footOf(s));
    const double into = velocity.dot(n);
    const double away = into < 0 ? -floorRestitution() * into : into;
    const double g_n = -gravity_.dot(n);
    flying = away > 0 && !(2 * away < settings_.min_flight_time * g_n);
    velocity = ground_.along(velocity, n);
    if (flying)
      velocity += away * n;
  }
  if (!(velocity.stableNorm() <= kMaxSpeed))
  {
    result.error = "impulse: would give ball " + std::to_string(id) + " a speed of " +
                   formatNumber(velocity.stableNorm()) + " m/s, past the limit of " + formatNumber(kMaxSpeed) + " m/s";
    return result;
  }
  if (friction_)
  {
    BallSpin& spin = spins_[s];
    const Vec3 w = spin.angular_velocity + offset.cross(impulse) / (spin.inertia * ball.mass * ball.radius * ball.radius);
    if (!(w.stableNorm() <= kMaxSpin))
    {
      result.error = "impulse: would give ball " + std::to_string(id) + " a spin of " + formatNumber(w.stableNorm()) +
                     " rad/s, past the limit of " + formatNumber(kMaxSpin) + " rad/s";
      return result;
    }
    spin.angular_velocity = w;
    spin.kind = flying ? MotionKind::kFlying
                       : frictionUnder(ground_.normalUnder(footOf(s))).kindOf(spin.inertia, ball.radius, velocity, w);
  }
  ball.velocity = velocity;
  ball.flying = flying;
  wakeTouching(ball.position, ball.radius);  // (itself, and what it may push)
  ball.quiet_steps = 0;  // (the ball the edit set going counts its still steps again)
  forgetOrder();
  result.ok = true;
  return result;
}

AddResult StepContext::addWall(const WallDef& def)
{
  AddResult result;
  result.error = joinIssues(validateWall(def, ""));
  if (!result.error.empty())
    return result;
  const Wall wall(next_wall_id_, def, scene_.restitution);
  for (const Ball& ball : BallList(balls_, by_id_))  // (the first in id order is named)
  {
    const double depth = ball.radius - wall.distance(ball.position);
    if (depth > kContactTolerance)
    {
      result.error = "point: the wall cuts through ball " + std::to_string(ball.id) + " (by " + formatNumber(depth) + " m)";
      return result;
    }
  }
  ++next_wall_id_;
  walls_.push_back(wall);
  edge_boxes_ = floorEdgeBoxes();  // (the floor's edges it covers are none to pass)
  wakeAll();
  result.ok = true;
  result.id = wall.id;
  return result;
}

bool StepContext::removeBall(int id)
{
  if (slotOf(id) == balls_.size())
    return false;
  sortById();  // (then its slot is its place in balls())
  const std::size_t k = indexOf(id);
  wakeTouching(balls_[k].position, balls_[k].radius);  // what leaned on it
  if (!feet_.empty())
    feet_.erase(feet_.begin() + static_cast<std::ptrdiff_t>(k));
  if (!spins_.empty())
    spins_.erase(spins_.begin() + static_cast<std::ptrdiff_t>(k));
  balls_.erase(balls_.begin() + static_cast<std::ptrdiff_t>(k));
  by_id_.pop_back();  // (in id order, slot k holds the k-th)
  forgetOrder();
  return true;
}

bool StepContext::removeWall(int id)
{
  const auto it = std::find_if(walls_.begin(), walls_.end(), [&](const Wall& w) { return w.id == id; });
  if (it == walls_.end())
    return false;
  walls_.erase(it);
  edge_boxes_ = floorEdgeBoxes();  // (an edge it covered can be passed now)
  wakeAll();  // what leaned on it
  return true;
}
}  // namespace ball_collision_sim::core
