// Edits between steps: adding, moving, striking and removing balls, adding and removing
// walls. Each checks its input first and changes nothing when it refuses. Reads and
// writes balls_, spins_, feet_, walls_; an edit forgets the step's visiting order and
// wakes the sleeping balls it touches (a wall's, all: what held them may have changed).
#include "step/step_context.hpp"
#include "step/spin_model.hpp"

#include "step/flight.hpp"
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

AddResult World::addBall(const BallDef& def, Landing landing)
{
  StepContext& c = *c_;
  AddResult result;
  BallDef placed = def;
  Vec2 foot(0.5, 0.5);
  bool flying = false;
  result.error = c.place(placed, landing, -1, foot, flying);
  if (!result.error.empty())
    return result;
  result.ok = true;
  // (room first, so that the lists stay in step: the last pushes cannot throw)
  if (c.balls_.size() == c.balls_.capacity())
    c.balls_.reserve(2 * c.balls_.size() + 1);
  if (c.by_id_.size() == c.by_id_.capacity())
    c.by_id_.reserve(2 * c.by_id_.size() + 1);
  c.spin_->reserveOne(c);
  if (c.floor_motion_->keepsFeet())
    c.feet_.push_back(foot);
  c.spin_->addSpin(c, placed, foot, flying);
  c.by_id_.push_back(static_cast<std::uint32_t>(c.balls_.size()));  // (the highest id yet)
  c.balls_.push_back(c.makeBall(c.next_ball_id_, placed));
  c.balls_.back().support = flying ? Ball::Support::kAir : Ball::Support::kFloor;
  result.id = c.next_ball_id_++;
  c.forgetOrder();
  return result;
}

AddResult World::setBallState(int id, const BallEdit& edit)
{
  StepContext& c = *c_;
  const std::size_t k = indexOf(id);
  if (k == c.by_id_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  const std::size_t s = c.by_id_[k];
  const Ball& ball = c.balls_[s];
  AddResult result;
  result.id = id;
  BallDef def;
  def.position = edit.position.value_or(ball.position);
  def.velocity = edit.velocity.value_or(ball.velocity);
  def.radius = ball.radius;
  def.mass = ball.mass;
  // a spin is kept with the velocity; a new velocity without one rolls (BallDef's default)
  def.angular_velocity = edit.angular_velocity;
  if (!edit.angular_velocity && !edit.velocity)
    def.angular_velocity = angularVelocity(k);
  def.inertia = edit.inertia.value_or(this->inertia(k));
  // A ball left where it is stays there: resting on the floor it must rest there still
  // (kExact, which under kUnder drops the velocity's part off the floor), in flight the
  // floor is not to take it.
  Landing landing = edit.landing;
  if (!edit.position && landing != Landing::kAsGiven)
    landing = ball.flying() ? Landing::kAsGiven : Landing::kExact;
  Vec2 foot(0.5, 0.5);
  bool flying = false;
  result.error = c.place(def, landing, id, foot, flying);
  if (!result.error.empty())
    return result;
  if (!edit.position)
    def.position = ball.position;  // (kExact's projection may move it by round-off)
  // (what leaned on it where it was wakes, and what it touches where it is, and itself)
  c.wakeTouching(ball.position, ball.radius);
  c.wakeTouching(def.position, def.radius);
  Ball& set = c.balls_[s];
  set.position = def.position;
  set.velocity = def.velocity;
  set.support = flying ? Ball::Support::kAir : Ball::Support::kFloor;
  set.quiet_steps = 0;  // (the ball the edit moved counts its still steps again)
  c.spin_->setSpin(c, s, def, foot, flying);
  if (c.floor_motion_->keepsFeet())
    c.feet_[s] = foot;
  c.forgetOrder();
  result.ok = true;
  return result;
}

AddResult World::applyImpulse(int id, const Vec3& impulse)
{
  return strike(id, impulse, Vec3::Zero());
}

AddResult World::strike(int id, const Vec3& impulse, const Vec3& offset)
{
  StepContext& c = *c_;
  const std::size_t s = c.slotOf(id);
  if (s == c.balls_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  if (!impulse.allFinite())
    return refused(id, "impulse: must be finite");
  if (!offset.allFinite())
    return refused(id, "offset: must be finite");
  // (within kContactTolerance of the surface is on it)
  if (offset.norm() > c.balls_[s].radius + kContactTolerance)
    return refused(id, "offset: must be at most the ball's radius " + formatNumber(c.balls_[s].radius) + " m from its centre (got " +
                           formatNumber(offset.norm()) + " m)");
  AddResult result;
  result.id = id;
  Ball& ball = c.balls_[s];
  Vec3 velocity = ball.velocity + impulse / ball.mass;
  bool flying = ball.flying();
  if (c.ground_.floor() && !flying)
  {
    // Pressed into the floor, the ball comes back off it at the floor's restitution (a
    // jump shot); lifted enough to stay off it for min_flight_time, it flies; else the
    // floor takes the part along its normal.
    const Vec3 n = c.ground_.normalUnder(c.footOf(s));
    const double into = velocity.dot(n);
    const double away = into < 0 ? -step::floorRestitution(c) * into : into;
    const double g_n = -c.gravity_.dot(n);
    flying = away > 0 && !(2 * away < c.settings_.min_flight_time * g_n);
    velocity = c.ground_.along(velocity, n);
    if (flying)
      velocity += away * n;
  }
  if (!(velocity.stableNorm() <= kMaxSpeed))
  {
    result.error = "impulse: would give ball " + std::to_string(id) + " a speed of " +
                   formatNumber(velocity.stableNorm()) + " m/s, past the limit of " + formatNumber(kMaxSpeed) + " m/s";
    return result;
  }
  result.error = c.spin_->strike(c, s, impulse, offset, velocity, flying);
  if (!result.error.empty())
    return result;
  ball.velocity = velocity;
  c.wakeTouching(ball.position, ball.radius);  // (itself, and what it may push)
  if (flying)
    ball.support = Ball::Support::kAir;
  ball.quiet_steps = 0;  // (the ball the edit set going counts its still steps again)
  c.forgetOrder();
  result.ok = true;
  return result;
}

AddResult World::addWall(const WallDef& def)
{
  StepContext& c = *c_;
  AddResult result;
  result.error = joinIssues(validateWall(def, ""));
  if (!result.error.empty())
    return result;
  const Wall wall(c.next_wall_id_, def, c.scene_.restitution);
  for (const Ball& ball : BallList(c.balls_, c.by_id_))  // (the first in id order is named)
  {
    const double depth = ball.radius - wall.distance(ball.position);
    if (depth > kContactTolerance)
    {
      result.error = "point: the wall cuts through ball " + std::to_string(ball.id) + " (by " + formatNumber(depth) + " m)";
      return result;
    }
  }
  ++c.next_wall_id_;
  c.walls_.push_back(wall);
  c.edge_boxes_ = step::floorEdgeBoxes(c);  // (the floor's edges it covers are none to pass)
  c.wakeAll();
  result.ok = true;
  result.id = wall.id;
  return result;
}

bool World::removeBall(int id)
{
  StepContext& c = *c_;
  if (c.slotOf(id) == c.balls_.size())
    return false;
  c.sortById();  // (then its slot is its place in balls())
  const std::size_t k = indexOf(id);
  c.wakeTouching(c.balls_[k].position, c.balls_[k].radius);  // what leaned on it
  if (!c.feet_.empty())
    c.feet_.erase(c.feet_.begin() + static_cast<std::ptrdiff_t>(k));
  if (!c.spins_.empty())
    c.spins_.erase(c.spins_.begin() + static_cast<std::ptrdiff_t>(k));
  c.balls_.erase(c.balls_.begin() + static_cast<std::ptrdiff_t>(k));
  c.by_id_.pop_back();  // (in id order, slot k holds the k-th)
  c.forgetOrder();
  return true;
}

bool World::removeWall(int id)
{
  StepContext& c = *c_;
  const auto it = std::find_if(c.walls_.begin(), c.walls_.end(), [&](const Wall& w) { return w.id == id; });
  if (it == c.walls_.end())
    return false;
  c.walls_.erase(it);
  c.edge_boxes_ = step::floorEdgeBoxes(c);  // (an edge it covered can be passed now)
  c.wakeAll();  // what leaned on it
  return true;
}
}  // namespace ball_collision_sim::core
