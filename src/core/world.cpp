#include "ball_collision_sim/core/world.hpp"

#include "ball_collision_sim/core/format.hpp"
#include "ball_collision_sim/core/placement.hpp"
#include "ball_collision_sim/core/response.hpp"
#include "ball_collision_sim/core/state_hash.hpp"
#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace ball_collision_sim::core
{
namespace
{
/// A ball with more events than this in one step is stopped for the rest of the step
/// and acts as immovable: a guard against endless chatter in jammed piles.
constexpr std::uint32_t kMaxEventsPerBallStep = 256;
/// Two balls at a resting contact, one of which has had this many events in the step,
/// still or not, are in a jam that answers pair by pair only pass around (each pushes one
/// of them into a third ball, which pushes it back): they are held for the rest of the step.
constexpr std::uint32_t kJamEventsPerBallStep = 16;
/// A closing speed below what gravity along the floor adds in this many steps is a
/// resting contact: the motion is stopped along the normal instead of bounced, so a
/// ball leaning on a wall neither jitters nor makes endless events.
constexpr double kRestingSteps = 2.0;
/// ... and below this [m/s] always (flat floors, where gravity adds nothing).
constexpr double kRestingSpeedFloor = 1e-9;

/// A length [m] below the round-off of positions around p (with a ball of radius r):
/// where the corrections of a ball's motion on a curved floor are down to this, putting
/// it on the floor and out of what it leans on only trade round-off back and forth.
double roundoffAt(const Vec3& p, double r)
{
  return 16 * std::numeric_limits<double>::epsilon() * (p.cwiseAbs().maxCoeff() + r);
}

/// sin(x) / x and cos(x) from y = x^2 (both are even in x): series where |x| is small,
/// the usual way elsewhere; so a caller that has x^2 takes no square root. The series are
/// summed in pairs of terms (Estrin's scheme) so that they take a few dependent steps
/// rather than one per term.
void sincCosOfSquare(double y, double& sinc, double& c)
{
  if (!(y <= 0.25))
  {
    const double x = std::sqrt(y);
    sinc = std::sin(x) / x;
    c = std::cos(x);
    return;
  }
  // Taylor series to x^16 and x^18: the first term left out is below 3e-23 for |x| <= 1/2.
  // s[k] = (-1)^k / (2k + 1)!, c[k] = (-1)^k / (2k)!
  constexpr double s1 = -1.0 / 6, s2 = 1.0 / 120, s3 = -1.0 / 5040, s4 = 1.0 / 362880, s5 = -1.0 / 39916800,
                   s6 = 1.0 / 6227020800, s7 = -1.0 / 1307674368000, s8 = 1.0 / 355687428096000;
  constexpr double c1 = -1.0 / 2, c2 = 1.0 / 24, c3 = -1.0 / 720, c4 = 1.0 / 40320, c5 = -1.0 / 3628800,
                   c6 = 1.0 / 479001600, c7 = -1.0 / 87178291200, c8 = 1.0 / 20922789888000,
                   c9 = -1.0 / 6402373705728000;
  const double x2 = y, x4 = x2 * x2, x8 = x4 * x4;
  sinc = ((1 + s1 * x2) + x4 * (s2 + s3 * x2)) + x8 * (((s4 + s5 * x2) + x4 * (s6 + s7 * x2)) + x8 * s8);
  c = ((1 + c1 * x2) + x4 * (c2 + c3 * x2)) + x8 * (((c4 + c5 * x2) + x4 * (c6 + c7 * x2)) + x8 * (c8 + c9 * x2));
}
}  // namespace

/// A ball's straight motion inside the current step, in the step fraction x shared by all
/// balls: centre c(x) = p0 + (x - x0) b for x in [x0, 1]. A new one starts at every event.
/// It holds what detection reads, in one cache line; the ball's velocity at x0 is kept in
/// the ball itself while the step runs (startVelocity()), its counters in a MotionState.
struct alignas(64) World::Motion
{
  double x0 = 0.0;               ///< where this motion starts, fraction of the step
  Vec3 p0 = Vec3::Zero();        ///< centre at x0 [m]
  Vec3 b = Vec3::Zero();         ///< displacement per unit of x [m]; zero while frozen
  double radius = 0.0;           ///< the ball's [m]
};

/// The rest of a ball's state in the step.
struct World::MotionState
{
  std::uint32_t epoch = 0;       ///< bumped at every event of this ball
  std::uint16_t events = 0;      ///< events of this ball in this step, until it is frozen
  bool frozen = false;
  /// Held (see hold()): in a jam at a resting contact, or left no motion its energy allows;
  /// it stays where it is through resting contacts for the rest of the step (an impact
  /// lets it go).
  bool held = false;
  std::int32_t blocked = -1;     ///< its BlockedSet this step, if any
};
static_assert(kMaxEventsPerBallStep < 0xffff, "MotionState::events counts to one past the cap");

/// Unit directions a ball may not move along for the rest of the step: toward a wall it
/// leans on, or toward a ball that cannot give way. A ball in a corner or in a pile at
/// rest has several; most balls have none, and no set.
struct World::BlockedSet
{
  std::array<Vec3, 8> directions;
  std::uint8_t count = 0;

  /// `w` without its parts along the blocked directions: the nearest vector with
  /// <w, d> <= 0 for every blocked d, by cyclic projection; zero (which always qualifies)
  /// when that does not settle.
  Vec3 allowed(Vec3 w) const
  {
    const double scale = w.norm();
    for (int pass = 0; pass < 16; ++pass)
    {
      bool changed = false;
      for (std::uint8_t k = 0; k < count; ++k)
      {
        const double into = w.dot(directions[k]);
        if (into > 0)
        {
          w -= into * directions[k];
          changed = true;
        }
      }
      if (!changed)
        return w;
    }
    for (std::uint8_t k = 0; k < count; ++k)
      if (w.dot(directions[k]) > 1e-14 * scale)
        return Vec3::Zero();
    return w;
  }
  void add(const Vec3& direction)
  {
    for (std::uint8_t k = 0; k < count; ++k)
      if (directions[k].dot(direction) > 1 - 1e-12)
        return;
    if (count < directions.size())
      directions[count++] = direction;
  }
};

Vec3 World::allowed(std::size_t i, const Vec3& w) const
{
  const std::int32_t blocked = states_[i].blocked;
  return blocked < 0 ? w : blocked_sets_[static_cast<std::size_t>(blocked)].allowed(w);
}

void World::addBlocked(std::size_t i, const Vec3& direction)
{
  MotionState& m = states_[i];
  if (m.blocked < 0)
  {
    m.blocked = static_cast<std::int32_t>(blocked_sets_.size());
    blocked_sets_.emplace_back();
  }
  blocked_sets_[static_cast<std::size_t>(m.blocked)].add(direction);
}

/// A predicted impact; stale once either ball's epoch has moved on.
struct World::Event
{
  double x;                  ///< step fraction of the impact
  std::uint32_t i;           ///< ball index (the lower one for ball-ball)
  std::uint32_t j;           ///< other ball index, or wall index
  std::uint32_t epoch_i;
  std::uint32_t epoch_j;
  bool wall;
  WallFeature feature;
  Vec3 normal;               ///< ball-wall: unit, from the wall toward the ball
};

bool World::EventLater::operator()(const QueuedEvent& qa, const QueuedEvent& qb) const
{
  // Earliest first; ties broken by the balls' ids (their places in `balls_`), not by the
  // order the step visits them in, so that a run is the same whatever that order was.
  if (qa.x != qb.x)
    return qa.x > qb.x;
  const Event& a = (*pool)[qa.slot];
  const Event& b = (*pool)[qb.slot];
  const auto key = [&](const Event& e) {
    const std::uint32_t i = (*order)[e.i];
    const std::uint32_t j = e.wall ? e.j : (*order)[e.j];
    using Key = std::array<std::uint32_t, 3>;
    return e.wall ? Key{i, 0, j} : Key{std::min(i, j), 1, std::max(i, j)};
  };
  return key(a) > key(b);
}

World::World(const Scene& scene) : scene_(scene), dt_(scene.dt), gravity_(scene.gravity)
{
  const std::vector<SceneIssue> issues = validate(scene);
  if (!issues.empty())
    throw std::invalid_argument(joinIssues(issues));
  load();
}

World::World(const World&) = default;
World& World::operator=(const World&) = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

void World::load()
{
  dt_ = scene_.dt;
  gravity_ = scene_.gravity;
  floor_.reset();
  if (scene_.floor)
    floor_.emplace(*scene_.floor, gravity_);
  const double g = gravity_.norm();
  up_ = floor_ ? floor_->up() : g > 0 ? Vec3(-gravity_ / g) : Vec3(Vec3::UnitZ());
  plane_ = floor_ && floor_->isPlane();
  if (plane_)
  {
    plane_normal_ = floor_->planeNormal();
    plane_offset_ = floor_->planeOffset();
  }
  plane_resting_speed_ = 0.0;
  if (plane_)
    plane_resting_speed_ = restingSpeed(plane_normal_);
  const Vec3 along = plane_ ? tangentPart(gravity_, plane_normal_) : gravity_;
  straight_ = !curved() && along.norm() <= 1e-12 * g;
  walls_.clear();
  next_wall_id_ = kFirstId;
  for (const WallDef& def : scene_.walls)
    walls_.emplace_back(next_wall_id_++, def, scene_.restitution);
  balls_.clear();
  feet_.clear();
  next_ball_id_ = kFirstId;
  const std::vector<BallDef> defs = allBalls(scene_);
  balls_.reserve(defs.size());
  if (curved())
    feet_.reserve(defs.size());
  for (BallDef def : defs)
  {
    Vec2 foot(0.5, 0.5);
    placeOnFloor(def, floor_, &foot);  // validate() has checked that it stands
    balls_.push_back(makeBall(next_ball_id_++, def));
    if (curved())
      feet_.push_back(foot);
  }
  stats_ = WorldStats{};
  events_.clear();
  forgetOrder();
}

void World::reset()
{
  load();
}

void World::forgetOrder()
{
  order_.clear();
  order_age_ = 0;
  motions_ready_ = false;
}

Ball World::makeBall(int id, const BallDef& placed)
{
  Ball ball;
  ball.id = id;
  ball.radius = placed.radius;
  ball.mass = placed.mass;
  ball.position = placed.position;
  ball.velocity = placed.velocity;
  return ball;
}

// ---- the step ------------------------------------------------------------------------

void World::step()
{
  events_.clear();
  resting_.clear();
  blocked_sets_.clear();
  if (order_.size() != balls_.size())
  {
    order_.resize(balls_.size());
    for (std::size_t k = 0; k < order_.size(); ++k)
      order_[k] = static_cast<std::uint32_t>(k);
  }
  wall_boxes_.resize(walls_.size());
  for (std::size_t w = 0; w < walls_.size(); ++w)
    wall_boxes_[w] = Box32::around(Aabb{walls_[w].box_min, walls_[w].box_max});
  predictMotions();            // each ball's free motion over the step, on the floor, and its swept box
  buildBroadPhase();           // the swept boxes into a uniform grid
  findFirstImpacts();          // exact times of impact of nearby pairs and walls
  resolveEventsInTimeOrder();  // earliest first; re-detect only the balls involved
  // The next step visits the balls in this step's cell order, so that neighbours in
  // space are neighbours in memory too; not after every step, as balls move less than a
  // cell in one: while the order stays, the commit predicts the next step's motions, with
  // each ball's record at hand.
  const bool reorder = grid_.inCellOrder() && (order_age_ == 0 || order_age_ >= kReorderSteps);
  commitToFloor(!reorder);     // every ball to the step's end, back on the floor
  if (reorder)
    grid_.reorder(order_);
  order_age_ = reorder ? 1 : order_age_ + 1;
  motions_ready_ = !reorder;
  ++stats_.steps;
}

void World::prefetchBall(std::size_t k, bool write) const
{
  if (k >= order_.size())
    return;
  const char* at = reinterpret_cast<const char*>(&balls_[order_[k]]);
  if (write)
  {
    __builtin_prefetch(at, 1);
    __builtin_prefetch(at + 64, 1);
    __builtin_prefetch(at + sizeof(Ball) - 1, 1);
  }
  else
  {
    __builtin_prefetch(at);
    __builtin_prefetch(at + 64);
  }
}

void World::predictMotions()
{
  static_assert(sizeof(Motion) == 64, "a Motion fills one cache line");
  grid_.start(balls_.size(), up_);
  // (taken back at once, so that a step cut short by an exception leaves none ready)
  if (std::exchange(motions_ready_, false))
    return;  // the last step's commit predicted them
  motions_.resize(balls_.size());
  states_.resize(balls_.size());
  floor_uv_.resize(curved() ? balls_.size() : 0);
  for (std::size_t i = 0; i < balls_.size(); ++i)
  {
    prefetchBall(i + kPrefetchAhead, false);
    predictMotion(i);
  }
}

void World::predictMotion(std::size_t i)
{
  const Ball& ball = balls_[order_[i]];
  Motion& m = motions_[i];
  m = Motion{};
  states_[i] = MotionState{};
  m.radius = ball.radius;
  m.p0 = ball.position;
  if (!floor_uv_.empty())
    floor_uv_[i] = feet_[order_[i]];
  const Vec3 end = predictedEnd(i, m.p0, ball.velocity, dt_);
  m.b = end - m.p0;
  if (curved())
    keepEnergy(i);  // on a plane the first chord ends where the exact path does
  const Vec3 reach = m.p0 + m.b;
  grid_.setBox(static_cast<std::uint32_t>(i), sweptBox(m.p0, reach, ball.radius));
}

Vec3 World::predictedEnd(std::size_t i, const Vec3& p, const Vec3& v, double span)
{
  // seed (1): ds = dt v + dt^2 g / 2, then back onto the floor, seed (2)-(4)
  const Vec3 q = p + span * v + (0.5 * span * span) * gravity_;
  if (!curved())
    return onFloor(i, q);
  const FloorFoot foot = floor_->project(q, floor_uv_[i]);
  floor_uv_[i] = foot.uv;
  return floor_->ballCentre(foot, motions_[i].radius);
}

Aabb World::currentBox(std::size_t i) const
{
  const Motion& m = motions_[i];
  return sweptBox(m.p0, m.p0 + (1 - m.x0) * m.b, m.radius);
}

void World::buildBroadPhase()
{
  heap_.clear();
  event_pool_.clear();
  free_slots_.clear();
  grid_.build();  // on the swept boxes of the predicted motions
  grid_.markObstacles(wall_boxes_);
}

void World::findFirstImpacts()
{
  grid_.forEachNearObstacle([&](std::uint32_t i) { detectWalls(i); });
  grid_.forEachPair([&](std::uint32_t i, std::uint32_t j) { detectBall(i, j); });
}

void World::resolveEventsInTimeOrder()
{
  const EventLater later{&event_pool_, &order_};
  while (!heap_.empty())
  {
    {
      // the first event's balls' data are fetched while the queue is put in order
      const auto fetch = [&](std::uint32_t k) {
        __builtin_prefetch(&states_[k]);
        __builtin_prefetch(&motions_[k]);
        __builtin_prefetch(&order_[k]);
      };
      const Event& next = event_pool_[heap_.front().slot];
      fetch(next.i);
      if (!next.wall)
        fetch(next.j);
    }
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const std::uint32_t slot = heap_.back().slot;
    heap_.pop_back();
    const Event event = event_pool_[slot];
    free_slots_.push_back(slot);
    // The next event is most likely the one now first: its record is fetched while this
    // one is handled (events in time order reach the balls' data at random).
    if (!heap_.empty())
      __builtin_prefetch(&event_pool_[heap_.front().slot]);
    if (states_[event.i].epoch != event.epoch_i || (!event.wall && states_[event.j].epoch != event.epoch_j))
    {
      ++stats_.stale_events;  // a ball involved has had an event since this was found
      continue;
    }
    if (event.wall)
      resolveBallWall(event);
    else
      resolveBallBall(event);
  }
}

void World::commitToFloor(bool predict_next)
{
  // Without resting contacts every ball is finished in one pass; with them, velocities
  // are settled across the contacts first.
  const bool settle = !resting_.empty() || !blocked_sets_.empty();
  if (curved())
    floor_normals_.resize(balls_.size());
  for (std::size_t i = 0; i < balls_.size(); ++i)
  {
    prefetchBall(i + kPrefetchAhead, true);
    Motion& m = motions_[i];
    Ball& ball = balls_[order_[i]];
    Vec3 p = positionAt(i, 1.0);
    Vec3 normal = up_;
    if (plane_)
    {
      p = onFloor(i, p);
      normal = plane_normal_;
    }
    else if (floor_)
    {
      // The chord ends on the floor (endOnFloor) except where a ball was stopped by the
      // event cap, was held, or its constraints did not settle: then it stays at its
      // chord's end, clear of everything, a little off the floor until the next step puts
      // it back.
      const FloorFoot foot = floor_->project(p, floor_uv_[i]);
      feet_[order_[i]] = foot.uv;
      normal = foot.normal;
      floor_normals_[i] = normal;
    }
    const Vec3 moved = p - ball.position;
    ball.position = p;
    ball.velocity = states_[i].frozen ? Vec3::Zero() : onFloorVelocity(i, 1.0, p, normal);
    if (!settle)
    {
      roll(i, normal, moved);
      if (predict_next)
        predictMotion(i);
    }
    else
      m.p0 = moved;  // the motion is done with: p0 keeps the step's move for roll()
  }
  if (!settle)
    return;
  // Resting contacts keep no closing speed into the step that follows.
  for (std::size_t i = 0; i < balls_.size(); ++i)
    balls_[order_[i]].velocity = allowed(i, balls_[order_[i]].velocity);
  for (const RestingContact& contact : resting_)
  {
    Ball& a = balls_[order_[contact.ball]];
    Ball& b = balls_[order_[contact.other]];
    const double inv_a = states_[contact.ball].frozen ? 0.0 : 1.0 / a.mass;
    const double inv_b = states_[contact.other].frozen ? 0.0 : 1.0 / b.mass;
    const double closing = a.velocity.dot(contact.dir_ball) - b.velocity.dot(contact.dir_other);
    if (closing > 0)
    {
      const double j = collisionImpulse(closing, inv_a, contact.dir_ball, inv_b, contact.dir_other, 0.0);
      a.velocity -= (j * inv_a) * contact.dir_ball;
      b.velocity += (j * inv_b) * contact.dir_other;
    }
  }
  for (std::size_t i = 0; i < balls_.size(); ++i)
  {
    const Vec3& normal = plane_ ? plane_normal_ : floor_ ? floor_normals_[i] : up_;
    Ball& ball = balls_[order_[i]];
    if (floor_ && !resting_.empty())
      ball.velocity -= ball.velocity.dot(normal) * normal;
    roll(i, normal, motions_[i].p0);
    if (predict_next)
      predictMotion(i);
  }
}

void World::roll(std::size_t i, const Vec3& normal, const Vec3& d)
{
  // Rolling without slip: turned by |d| / r about n x d, d the move along the floor
  // (|n x d| is its length). Its angular velocity follows from n and v when asked for.
  Ball& ball = balls_[order_[i]];
  const double half_inv_radius = 0.5 / ball.radius;
  const Vec3 axis = normal.cross(d);
  const double axis_squared = axis.squaredNorm();
  if (axis_squared > 0)
  {
    // the half angle x = |n x d| / 2r; sin(x) / |n x d| = sinc(x) / 2r
    double sinc_half = 1, cos_half = 1;
    sincCosOfSquare(axis_squared * (half_inv_radius * half_inv_radius), sinc_half, cos_half);
    const Vec3 k = (sinc_half * half_inv_radius) * axis;
    Quat q = Quat(cos_half, k.x(), k.y(), k.z()) * ball.orientation;
    // back to unit length: the product of unit quaternions is off by round-off only, so
    // one Newton step of 1/sqrt does
    q.coeffs() *= 1.5 - 0.5 * q.coeffs().squaredNorm();
    ball.orientation = q;
  }
}

// ---- detection -----------------------------------------------------------------------

void World::pushEvent(const Event& event)
{
  std::uint32_t slot = 0;
  if (free_slots_.empty())
  {
    slot = static_cast<std::uint32_t>(event_pool_.size());
    event_pool_.push_back(event);
  }
  else
  {
    slot = free_slots_.back();
    free_slots_.pop_back();
    event_pool_[slot] = event;
  }
  heap_.push_back({event.x, slot});
  std::push_heap(heap_.begin(), heap_.end(), EventLater{&event_pool_, &order_});
}

void World::detect(std::size_t i)
{
  detectWalls(i);
  grid_.query(static_cast<std::uint32_t>(i), [&](std::uint32_t j) { detectBall(i, j); });
}

void World::detectWalls(std::size_t i)
{
  const Motion& m = motions_[i];
  if (states_[i].frozen || !grid_.nearObstacle(static_cast<std::uint32_t>(i)))
    return;
  const Box32& box = grid_.box(static_cast<std::uint32_t>(i));
  for (std::size_t w = 0; w < wall_boxes_.size(); ++w)
  {
    if (!box.overlaps(wall_boxes_[w]))
      continue;
    const Wall& wall = walls_[w];
    const auto hit = sweepWall(wall, m.p0, m.b, m.radius, 1 - m.x0);
    if (hit)
      pushEvent(Event{m.x0 + hit->t, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(w), states_[i].epoch, 0,
                      true, hit->feature, hit->normal});
  }
}

void World::detectBall(std::size_t i, std::size_t j)
{
  // Always in index order, so that the same pair gives the same bits whoever asks.
  const std::size_t a = std::min(i, j), b = std::max(i, j);
  const Motion& ma = motions_[a];
  const Motion& mb = motions_[b];
  // (two frozen balls have no motion, so no impact)
  const double xs = std::max(ma.x0, mb.x0);
  const Vec3 d = (ma.p0 + (xs - ma.x0) * ma.b) - (mb.p0 + (xs - mb.x0) * mb.b);
  const auto t = sphereSweep(d, ma.b - mb.b, ma.radius + mb.radius, 1 - xs);
  if (t)
    pushEvent(Event{xs + *t, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), states_[a].epoch, states_[b].epoch,
                    false, WallFeature::kFace, Vec3::Zero()});
}

// ---- response ------------------------------------------------------------------------

Vec3 World::positionAt(std::size_t i, double x) const
{
  const Motion& m = motions_[i];
  return m.p0 + (x - m.x0) * m.b;
}

Vec3 World::floorNormalAt(std::size_t i, const Vec3& position) const
{
  if (plane_)
    return plane_normal_;
  if (!floor_)
    return up_;
  return floor_->project(position, floor_uv_[i]).normal;
}

Vec3 World::onFloorVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const
{
  const Motion& m = motions_[i];
  const Vec3& v0 = startVelocity(i);
  Vec3 v = v0 + ((x - m.x0) * dt_) * gravity_;
  if (floor_)
    v -= v.dot(normal) * normal;
  if (straight_)
    return v;  // no force along the floor: the motion is the chord itself
  // Under a force along the floor the ball's path is a curve and its motion in the step
  // the chord across it, which runs off the curve; so where an impact stops the chord,
  // the velocity the force gave by then does not go with the height the chord reached.
  // Keep the frictionless ball's |v|^2 = |v0|^2 + 2 <g, p - p0> (the course code's
  // correction on its curved floor).
  const double target = v0.squaredNorm() + 2 * gravity_.dot(position - m.p0);
  const double norm = v.norm();
  if (target <= 0 || norm == 0)
    return Vec3::Zero();
  return v * (std::sqrt(target) / norm);
}

double World::restingSpeed(const Vec3& floor_normal) const
{
  if (plane_ && plane_resting_speed_ > 0)
    return plane_resting_speed_;
  const Vec3 along = floor_ ? tangentPart(gravity_, floor_normal) : gravity_;
  return kRestingSteps * dt_ * along.norm() + kRestingSpeedFloor;
}

void World::startMotion(std::size_t i, double x, const Vec3& position, const Vec3& velocity, bool impact)
{
  Motion& m = motions_[i];
  Vec3& v0 = startVelocity(i);
  if (impact)
    states_[i].held = false;
  m.x0 = x;
  m.p0 = position;
  if (states_[i].frozen)
  {
    v0 = m.b = Vec3::Zero();
    return;
  }
  v0 = allowed(i, velocity);
  if (states_[i].held)
  {
    m.b = Vec3::Zero();  // still held (no impact let it go): it keeps no motion
    return;
  }
  const double rest = 1 - x;
  m.b = rest > 0 ? Vec3((predictedEnd(i, position, v0, rest * dt_) - position) / rest) : Vec3(dt_ * v0);
  m.b = allowed(i, m.b);
  endOnFloor(i);
  keepEnergy(i);
  if (states_[i].held)
    m.b = Vec3::Zero();
}

void World::endOnFloor(std::size_t i)
{
  // The chord must end on the floor, where the step's end puts the ball: a ball moved
  // there after its motion was checked could be pressed into what it touches. Taking
  // out the blocked directions moves the end off a curved floor; back onto it and out of
  // them again, in turn, until both hold.
  Motion& m = motions_[i];
  const double rest = 1 - m.x0;
  if (!curved() || states_[i].frozen || !(rest > 0))
    return;
  const double roundoff = roundoffAt(m.p0, m.radius);
  for (int pass = 0; pass < 32; ++pass)
  {
    const Vec3 on = (onFloor(i, m.p0 + rest * m.b) - m.p0) / rest;
    const Vec3 free = allowed(i, on);
    const double off = (free - on).norm();
    const bool done = off <= 1e-15 * on.norm() || rest * off <= roundoff;
    // (a pass that leaves the motion as it was would be repeated as it is: fully blocked
    // off the floor, say)
    const bool same = free == m.b;
    m.b = done ? on : free;
    if (done || same)
      return;
  }
}

Vec3 World::onFloor(std::size_t i, const Vec3& q) const
{
  if (plane_)
    return q + (motions_[i].radius + plane_offset_ - plane_normal_.dot(q)) * plane_normal_;
  if (!floor_)
    return q;
  return floor_->ballCentre(floor_->project(q, floor_uv_[i]), motions_[i].radius);
}

void World::keepEnergy(std::size_t i)
{
  Motion& m = motions_[i];
  const double rest = 1 - m.x0;
  if (straight_ || states_[i].frozen || !(rest > 0))
    return;
  const Vec3& v0 = startVelocity(i);
  // |v|^2 at the end of the step with the displacement b per unit of x, put on the floor
  const auto speedSquaredWith = [&](const Vec3& b) {
    return v0.squaredNorm() + 2 * gravity_.dot(onFloor(i, m.p0 + rest * b) - m.p0);
  };
  // ... with the motion cut to the fraction s of its chord
  const auto speedSquared = [&](double s) { return speedSquaredWith(s * m.b); };
  // ... where the chord itself ends: a motion kept out of its blocked directions can end
  // off the floor, higher than where the floor under its end is
  const auto chordSpeedSquared = [&](const Vec3& b) { return v0.squaredNorm() + 2 * rest * gravity_.dot(b); };
  // (on a curved floor endOnFloor has put the chord's end on it, or as near as its blocked
  // directions let it: the chord's own end is what counts)
  const double full = curved() ? chordSpeedSquared(m.b) : speedSquared(1.0);
  if (full >= 0)
    return;
  // The chord ends higher than the ball's energy reaches (a turning point on a curved
  // floor, or a ball in a pile whose constraints turned its motion uphill): it stops
  // where the energy runs out instead, so that no energy is made.
  const double start = speedSquared(0.0);
  double lo = 0.0;
  if (start > 0)
  {
    if (!curved())
      lo = start / (start - full);  // linear in s
    else
    {
      // the root of the speed on [0, 1], kept bracketed: false position with the
      // Illinois rule (a stalled end's value halved), bisection where that gains less
      double hi = 1.0, f_lo = start, f_hi = full;
      int last = 0;  // the end moved last: +1 lo, -1 hi
      for (int k = 0; k < 50 && hi - lo > 1e-15; ++k)
      {
        const double width = hi - lo;
        double mid = lo + width * (f_lo / (f_lo - f_hi));
        if (!(mid > lo && mid < hi))
          mid = 0.5 * (lo + hi);
        const double f = speedSquared(mid);
        if (f >= 0)
        {
          lo = mid;
          f_lo = f;
          if (last > 0)
            f_hi *= 0.5;
          last = 1;
        }
        else
        {
          hi = mid;
          f_hi = f;
          if (last < 0)
            f_lo *= 0.5;
          last = -1;
        }
        if (hi - lo > 0.5 * width && hi - lo > 1e-15)
        {
          // one end stuck: halve the bracket as well
          const double half = 0.5 * (lo + hi);
          const double g = speedSquared(half);
          (g >= 0 ? lo : hi) = half;
          (g >= 0 ? f_lo : f_hi) = g;
          last = 0;
        }
      }
    }
    // (round-off may leave the end a hair too high; the speed is clamped to zero then)
  }
  m.b *= lo;
  if (!curved())
    return;
  if (lo > 0)
  {
    const Vec3 b = allowed(i, (onFloor(i, m.p0 + rest * m.b) - m.p0) / rest);
    m.b = chordSpeedSquared(b) >= 0 ? b : Vec3::Zero();
    if (m.b == Vec3::Zero())
      hold(i);
    return;
  }
  // A motion that starts at an impact inside the step starts on the chord, below or
  // above the floor; where the floor above it is higher than the energy reaches, the
  // ball slides downhill from there instead, as far as it takes to be low enough.
  // Where it finds no way, it is held: it stays put through the step's resting contacts.
  // (keepEnergy only ever holds a ball: an impact, not a new motion, lets it go)
  const Vec3 foot = onFloor(i, m.p0);
  const Vec3 downhill = tangentPart(gravity_, floorNormalAt(i, foot));
  const double slope = downhill.norm();
  if (!(slope > 0))
    return hold(i);
  // (a short way only: the chord's sag is small next to the ball; else it stays put)
  // The reaches tried are first * 2^k below half the radius. Where the energy left grows
  // with the reach (the lower the end, the more), halving the range of k after the
  // longest has shown that one does finds the shortest that does; elsewhere it finds one
  // that does, or, where the longest does not, holds the ball (which makes no energy).
  const double first = std::max(-start / slope, 1e-12 * m.radius);
  int count = 0;
  while (count < 64 && std::ldexp(first, count) < 0.5 * m.radius)
    ++count;
  const auto motionTo = [&](int k) {
    return allowed(i, (onFloor(i, foot + (std::ldexp(first, k) / slope) * downhill) - m.p0) / rest);
  };
  const auto keeps = [&](const Vec3& b) { return speedSquaredWith(b) >= 0 && chordSpeedSquared(b) >= 0; };
  if (count == 0)
    return hold(i);
  Vec3 found = motionTo(count - 1);
  if (!keeps(found))
    return hold(i);
  int fails = -1, works = count - 1;  // the largest k known to fail, the smallest known to work
  while (works - fails > 1)
  {
    const int k = fails + (works - fails) / 2;
    const Vec3 b = motionTo(k);
    if (keeps(b))
    {
      works = k;
      found = b;
    }
    else
      fails = k;
  }
  m.b = found;
}

void World::countEvent(std::size_t i)
{
  MotionState& m = states_[i];
  ++m.epoch;  // what was predicted for this ball before is stale now
  // (counted up to one past the cap only: a frozen ball can still be hit by many others)
  if (!m.frozen && ++m.events > kMaxEventsPerBallStep)
  {
    m.frozen = true;
    startVelocity(i) = Vec3::Zero();
    motions_[i].b = Vec3::Zero();
    ++stats_.frozen_balls;
  }
  // its new motion may reach beyond where the grid has it
  grid_.update(static_cast<std::uint32_t>(i), currentBox(i));
}

void World::hold(std::size_t i)
{
  if (!states_[i].held)
    ++stats_.held_balls;
  states_[i].held = true;
}

void World::recordEvent(CollisionEvent::Kind kind, int ball, int other, const Vec3& point, const Vec3& normal,
                        double impulse, double closing, bool resting, const Event& event)
{
  ++stats_.events;
  if (resting)
    ++stats_.resting_events;
  if (!record_events_)
    return;
  CollisionEvent out;
  out.kind = kind;
  out.time = (static_cast<double>(stats_.steps) + event.x) * dt_;
  out.ball = ball;
  out.other = other;
  out.feature = event.feature;
  out.point = point;
  out.normal = normal;
  out.impulse = impulse;
  out.approach_speed = closing;
  out.resting = resting;
  events_.push_back(out);
}

void World::recordEvents(bool record)
{
  record_events_ = record;
  if (!record)
    std::vector<CollisionEvent>().swap(events_);
}

void World::resolveBallWall(const Event& event)
{
  const std::size_t i = event.i;
  const Wall& wall = walls_[event.j];
  const Ball& ball = balls_[order_[i]];
  const Vec3 p = positionAt(i, event.x);
  const Vec3 floor_normal = floorNormalAt(i, p);
  Vec3 v = onFloorVelocity(i, event.x, p, floor_normal);

  const Vec3 n = -event.normal;  // from the ball toward the wall
  Vec3 dir = floor_ ? tangentPart(n, floor_normal) : n;
  if (dir.squaredNorm() < 1e-12)
    dir = n;  // a wall parallel to the floor: answer in space
  dir.normalize();
  const double closing = v.dot(dir);
  const bool resting = closing <= restingSpeed(floor_normal);
  const double inv_mass = states_[i].frozen ? 0.0 : 1.0 / ball.mass;
  const double impulse =
      collisionImpulse(std::max(closing, 0.0), inv_mass, dir, 0.0, dir, resting ? 0.0 : wall.restitution);
  v -= (impulse * inv_mass) * dir;

  if (resting)
  {
    // leaning on the wall until the step ends; where the floor is not square to the wall,
    // also no motion into the wall itself (else it comes back at once, again and again)
    addBlocked(i, dir);
    if (dir.dot(n) < 1 - 1e-12)
      addBlocked(i, n);
  }
  startMotion(i, event.x, p, v, !resting);
  recordEvent(CollisionEvent::Kind::kBallWall, ball.id, wall.id, p + ball.radius * n, n, impulse, closing, resting,
              event);
  countEvent(i);
  detect(i);
}

void World::resolveBallBall(const Event& event)
{
  const std::size_t i = event.i, j = event.j;
  const Ball& a = balls_[order_[i]];
  const Ball& b = balls_[order_[j]];
  const Vec3 pa = positionAt(i, event.x);
  const Vec3 pb = positionAt(j, event.x);
  const Vec3 na = floorNormalAt(i, pa);
  const Vec3 nb = floorNormalAt(j, pb);
  Vec3 va = onFloorVelocity(i, event.x, pa, na);
  Vec3 vb = onFloorVelocity(j, event.x, pb, nb);
  if (states_[i].frozen)
    va = Vec3::Zero();
  if (states_[j].frozen)
    vb = Vec3::Zero();

  Vec3 n = pb - pa;
  const double dist = n.norm();
  n = dist > 0 ? Vec3(n / dist) : Vec3(Vec3::UnitX());
  Motion& ma = motions_[i];
  Motion& mb = motions_[j];
  // Each ball is pushed along the normal's part tangent to the floor under it, less any
  // part toward what it leans on (that part of the impulse goes into the wall).
  const Vec3 along_a = floor_ ? tangentPart(n, na) : n;
  const Vec3 along_b = floor_ ? tangentPart(n, nb) : n;
  const Vec3 ta = -allowed(i, -along_a);
  const Vec3 tb = allowed(j, along_b);
  const double inv_a = states_[i].frozen ? 0.0 : 1.0 / a.mass;
  const double inv_b = states_[j].frozen ? 0.0 : 1.0 / b.mass;
  const double closing = va.dot(ta) - vb.dot(tb);
  const bool resting = closing <= std::max(restingSpeed(na), restingSpeed(nb));
  const double impulse =
      collisionImpulse(std::max(closing, 0.0), inv_a, ta, inv_b, tb, resting ? 0.0 : scene_.restitution);
  va -= (impulse * inv_a) * ta;
  vb += (impulse * inv_b) * tb;

  bool both_still = false;
  if (resting)
  {
    // A ball that cannot give way along the contact blocks the other's approach for the
    // rest of the step, and two balls that are both all but still (a pile at rest) block
    // each other, so that piles settle in one event per contact instead of passing
    // vanishing impulses back and forth.
    const double still = std::max(restingSpeed(na), restingSpeed(nb));
    both_still = va.norm() <= still && vb.norm() <= still;
    // (a held ball gives no way either)
    const bool a_fixed =
        both_still || states_[i].held || inv_a * ta.squaredNorm() < 1e-12 * inv_b * tb.squaredNorm();
    const bool b_fixed =
        both_still || states_[j].held || inv_b * tb.squaredNorm() < 1e-12 * inv_a * ta.squaredNorm();
    if (a_fixed && along_b.squaredNorm() > 0)
      addBlocked(j, -along_b.normalized());
    if (b_fixed && along_a.squaredNorm() > 0)
      addBlocked(i, along_a.normalized());
  }
  MotionState& sa = states_[i];
  MotionState& sb = states_[j];
  startMotion(i, event.x, pa, va, !resting);
  startMotion(j, event.x, pb, vb, !resting);
  if (resting)
  {
    // (a held ball does not give way)
    const double move_a = sa.held ? 0.0 : inv_a, move_b = sb.held ? 0.0 : inv_b;
    // No approach left in the motions either (gravity along the floor would press them
    // together again at once). On a curved floor, putting the ends back on the floor can
    // bring some back: in turn, a few times.
    // (until what approach is left is round-off of the positions)
    const double rest = 1 - event.x;
    const double roundoff = curved() ? roundoffAt(pa, ma.radius) + roundoffAt(pb, mb.radius) : 0.0;
    for (int pass = 0; pass < (curved() ? 32 : 1); ++pass)
    {
      const Vec3 ua = curved() ? n : ta, ub = curved() ? n : tb;
      const double into = ma.b.dot(ua) - mb.b.dot(ub);
      const double k = move_a * ta.dot(ua) + move_b * tb.dot(ub);
      if (!(into > 0 && k > 0 && rest * into > roundoff))
        break;
      const double jb = into / k;
      ma.b -= (jb * move_a) * ta;
      mb.b += (jb * move_b) * tb;
      if (!sa.held)
        endOnFloor(i);
      if (!sb.held)
        endOnFloor(j);
    }
    // Two balls all but still whose motions still close in (a pile in a corner of a
    // curved floor, where the floor, the walls and each other leave no room to settle
    // into), or that are in a jam: they stay where they are for the rest of the step,
    // whatever resting contact comes next (else each such contact would start them
    // again, and one the next, without end). So do two whose motions keepEnergy turned
    // back into each other (shortened or slid downhill) by more than detection lets
    // pass: it would find this contact again at once, and again.
    keepEnergy(i);
    keepEnergy(j);
    const bool jammed = sa.events >= kJamEventsPerBallStep || sb.events >= kJamEventsPerBallStep;
    const double closing_in = rest * (ma.b.dot(n) - mb.b.dot(n));
    const bool again = closing_in > kClosingSlop * (ma.radius + mb.radius);
    if (jammed || (both_still && closing_in > 0) || again)
    {
      ma.b = mb.b = Vec3::Zero();
      hold(i);
      hold(j);
    }
    resting_.push_back({i, j, ta, tb});
  }
  recordEvent(CollisionEvent::Kind::kBallBall, a.id, b.id, pa + a.radius * n, n, impulse, closing, resting, event);
  countEvent(i);
  countEvent(j);
  detect(i);
  detect(j);
}

// ---- queries -------------------------------------------------------------------------

Energy World::energy() const
{
  Energy e;
  for (const Ball& ball : balls_)
  {
    e.kinetic += 0.5 * ball.mass * ball.velocity.squaredNorm();
    e.potential -= ball.mass * gravity_.dot(ball.position);
  }
  return e;
}

Vec3 World::momentum() const
{
  Vec3 p = Vec3::Zero();
  for (const Ball& ball : balls_)
    p += ball.mass * ball.velocity;
  return p;
}

World::Bounds World::wallBounds() const
{
  Bounds bounds;
  for (const Wall& wall : walls_)
  {
    bounds.lo = bounds.any ? bounds.lo.cwiseMin(wall.box_min) : wall.box_min;
    bounds.hi = bounds.any ? bounds.hi.cwiseMax(wall.box_max) : wall.box_max;
    bounds.any = true;
  }
  return bounds;
}

std::string World::whyLost(std::size_t k, const Bounds& bounds) const
{
  const Ball& ball = balls_[k];
  if (floor_)
  {
    const Vec2 uv = plane_ ? floor_->planeParameters(ball.position) : feet_[k];
    if ((uv.array() >= -1e-9).all() && (uv.array() <= 1 + 1e-9).all())
      return "";
    return "left the floor (its foot point at u = " + formatNumber(uv.x()) + ", v = " + formatNumber(uv.y()) +
           " is outside [0, 1]^2)";
  }
  if (bounds.any && ((ball.position.array() < bounds.lo.array() - ball.radius).any() ||
                     (ball.position.array() > bounds.hi.array() + ball.radius).any()))
    return "left the walls' bounds";
  return "";
}

int World::lostBalls() const
{
  const Bounds bounds = wallBounds();
  int lost = 0;
  for (std::size_t k = 0; k < balls_.size(); ++k)
    lost += whyLost(k, bounds).empty() ? 0 : 1;
  return lost;
}

std::vector<LostBall> World::removeLostBalls()
{
  std::vector<LostBall> lost;
  if (!floor_ && walls_.empty())
    return lost;
  const Bounds bounds = wallBounds();
  std::size_t kept = 0;
  for (std::size_t k = 0; k < balls_.size(); ++k)
  {
    std::string why = whyLost(k, bounds);
    if (!why.empty())
    {
      lost.push_back({balls_[k], angularVelocity(k), std::move(why)});
      continue;
    }
    if (kept != k)
    {
      balls_[kept] = balls_[k];
      if (!feet_.empty())
        feet_[kept] = feet_[k];
    }
    ++kept;
  }
  if (lost.empty())
    return lost;
  balls_.resize(kept);
  if (!feet_.empty())
    feet_.resize(kept);
  forgetOrder();
  return lost;
}

std::uint64_t World::stateHash() const
{
  Fnv1a h;
  h.add(stats_.steps);
  h.add(balls_.size());
  for (const Ball& ball : balls_)
  {
    h.add(ball.id);
    h.add(ball.radius);
    h.add(ball.mass);
    h.add(ball.position.data(), 3 * sizeof(double));
    h.add(ball.velocity.data(), 3 * sizeof(double));
    h.add(ball.orientation.coeffs().data(), 4 * sizeof(double));
  }
  return h.value();
}

std::size_t World::indexOf(int id) const
{
  // Ids only grow and removal keeps order, so the list is sorted by id.
  const auto it = std::lower_bound(balls_.begin(), balls_.end(), id, [](const Ball& b, int v) { return b.id < v; });
  return it != balls_.end() && it->id == id ? static_cast<std::size_t>(it - balls_.begin()) : balls_.size();
}

const Ball* World::findBall(int id) const
{
  const std::size_t k = indexOf(id);
  return k < balls_.size() ? &balls_[k] : nullptr;
}

Vec3 World::angularVelocity(std::size_t k) const
{
  const Ball& ball = balls_.at(k);
  const Vec3 normal = plane_ ? plane_normal_ : floor_ ? floor_->normal(feet_[k]) : up_;
  return normal.cross(ball.velocity) / ball.radius;
}

// ---- editing -------------------------------------------------------------------------

std::string World::place(BallDef& def, Landing landing, int ignore_id, Vec2& foot) const
{
  const std::vector<SceneIssue> issues = validateBall(def, "");
  if (!issues.empty())
    return joinIssues(issues);
  const std::string why = placeOnFloor(def, floor_, &foot, landing);
  if (!why.empty())
    return "position: " + why;
  if (const auto overlap = wallOverlap(def, walls_))
    return "position: overlaps wall " + std::to_string(walls_[overlap->index].id) + " by " +
           formatNumber(overlap->depth) + " m";
  for (const Ball& other : balls_)
  {
    const double depth = def.radius + other.radius - (def.position - other.position).norm();
    if (other.id != ignore_id && depth > kContactTolerance)
      return "position: overlaps ball " + std::to_string(other.id) + " by " + formatNumber(depth) + " m";
  }
  return "";
}

AddResult World::addBall(const BallDef& def, Landing landing)
{
  AddResult result;
  BallDef placed = def;
  Vec2 foot(0.5, 0.5);
  result.error = place(placed, landing, -1, foot);
  if (!result.error.empty())
    return result;
  result.ok = true;
  const Ball ball = makeBall(next_ball_id_, placed);
  if (curved())
  {
    feet_.push_back(foot);
    try
    {
      balls_.push_back(ball);
    }
    catch (...)
    {
      feet_.pop_back();  // the two lists stay in step
      throw;
    }
  }
  else
    balls_.push_back(ball);
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

AddResult World::setBallState(int id, const Vec3& position, const Vec3& velocity, Landing landing)
{
  const std::size_t k = indexOf(id);
  if (k == balls_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  AddResult result;
  result.id = id;
  BallDef def;
  def.position = position;
  def.velocity = velocity;
  def.radius = balls_[k].radius;
  def.mass = balls_[k].mass;
  Vec2 foot(0.5, 0.5);
  result.error = place(def, landing, id, foot);
  if (!result.error.empty())
    return result;
  balls_[k].position = def.position;
  balls_[k].velocity = def.velocity;
  if (curved())
    feet_[k] = foot;
  forgetOrder();
  result.ok = true;
  return result;
}

AddResult World::applyImpulse(int id, const Vec3& impulse)
{
  const std::size_t k = indexOf(id);
  if (k == balls_.size())
    return refused(id, "id: no ball has id " + std::to_string(id));
  if (!impulse.allFinite())
    return refused(id, "impulse: must be finite");
  AddResult result;
  result.id = id;
  Ball& ball = balls_[k];
  Vec3 velocity = ball.velocity + impulse / ball.mass;
  if (floor_)
  {
    const Vec3 normal = plane_ ? plane_normal_ : floor_->normal(feet_[k]);
    velocity -= velocity.dot(normal) * normal;
  }
  if (!(velocity.stableNorm() <= kMaxSpeed))
  {
    result.error = "impulse: would give ball " + std::to_string(id) + " a speed of " +
                   formatNumber(velocity.stableNorm()) + " m/s, past the limit of " + formatNumber(kMaxSpeed) + " m/s";
    return result;
  }
  ball.velocity = velocity;
  forgetOrder();
  result.ok = true;
  return result;
}

AddResult World::addWall(const WallDef& def)
{
  AddResult result;
  result.error = joinIssues(validateWall(def, ""));
  if (!result.error.empty())
    return result;
  const Wall wall(next_wall_id_, def, scene_.restitution);
  for (const Ball& ball : balls_)
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
  result.ok = true;
  result.id = wall.id;
  return result;
}

bool World::removeBall(int id)
{
  const std::size_t k = indexOf(id);
  if (k == balls_.size())
    return false;
  if (!feet_.empty())
    feet_.erase(feet_.begin() + static_cast<std::ptrdiff_t>(k));
  balls_.erase(balls_.begin() + static_cast<std::ptrdiff_t>(k));
  forgetOrder();
  return true;
}

bool World::removeWall(int id)
{
  const auto it = std::find_if(walls_.begin(), walls_.end(), [&](const Wall& w) { return w.id == id; });
  if (it == walls_.end())
    return false;
  walls_.erase(it);
  return true;
}
}  // namespace ball_collision_sim::core
