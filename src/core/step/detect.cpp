// Stages 2 and 3, broad phase and detection: the swept boxes into the grid, then the
// exact first time of impact of each nearby pair and wall, into the event queue.
// Reads motions_, the start positions, walls_, the grid; writes wall_boxes_ (the grid's
// obstacles), queue_.
#include "step_types.hpp"
#include "stages.hpp"
#include "flight.hpp"

#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

void step::buildBroadPhase(StepContext& c)
{
  c.queue_.start(&c.balls_);
  c.grid_.build();  // on the swept boxes of the predicted motions
  c.wall_boxes_.resize(c.walls_.size());
  for (std::size_t w = 0; w < c.walls_.size(); ++w)
    c.wall_boxes_[w] = Aabb{c.walls_[w].box_min, c.walls_[w].box_max};
  c.wall_boxes_.insert(c.wall_boxes_.end(), c.edge_boxes_.begin(), c.edge_boxes_.end());
  c.grid_.markObstacles(c.wall_boxes_);
}

void step::findFirstImpacts(StepContext& c)
{
  c.grid_.forEachNearObstacle([&](std::uint32_t i) { c.detectWalls(i); });
  // (the pairs' times of impact are each their own: on the step's threads, the events
  // queued in the scan's order)
  c.splitLoop(c.grid_.pairScan(), c.balls_.size(), [&](std::size_t from, std::size_t to) {
    c.grid_.forEachPairIn(from, to, [&](std::uint32_t i, std::uint32_t j) { c.detectBall(i, j); });
  });
  c.grid_.forEachMovedPair([&](std::uint32_t i, std::uint32_t j) { c.detectBall(i, j); });
  if (c.motionsEnd())
    c.forEachBall([&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        c.queueMotionEnds(i);
    });
  if (!c.scene_.pockets.empty())
    c.forEachBall([&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        c.queuePockets(i);
    });
}

void StepContext::detect(std::size_t i, std::size_t done_with)
{
  detectWalls(i);
  grid_.query(static_cast<std::uint32_t>(i), [&](std::uint32_t j) {
    if (j != done_with)
      detectBall(i, j);
  });
  if (motionsEnd())
    queueMotionEnds(i);
  if (!scene_.pockets.empty())
    queuePockets(i);
}

void StepContext::detectWalls(std::size_t i)
{
  const Motion& m = motions_[i];
  if (motions_[i].frozen() || !grid_.nearObstacle(static_cast<std::uint32_t>(i)))
    return;
  for (std::size_t w = 0; w < walls_.size(); ++w)
  {
    if (!grid_.reaches(static_cast<std::uint32_t>(i), w) ||
        (grouped(i) && linked(i, kWallRow | static_cast<std::uint32_t>(w))))
      continue;  // (a wall the ball rests on is its group's constraint)
    const Wall& wall = walls_[w];
    const Ball& ball = balls_[i];
    const double rest = 1 - m.x0, slop = settings_.closing_slop;
    const auto hit = m.accelerates() ? sweepWall(wall, ball.position, m.b, parabolaOf(i), ball.radius, rest, slop)
                                     : sweepWall(wall, ball.position, m.b, ball.radius, rest, slop);
    if (hit)
      pushEvent(Event{m.x0 + hit->t, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(w), m.epoch, 0, EventKind::kBallWall,
                        hit->feature, MotionEnd::kPhase, hit->normal});
  }
  // (near an edge of the floor, where it may pass it)
  for (std::size_t e = 0; e < edge_boxes_.size(); ++e)
    if (grid_.reaches(static_cast<std::uint32_t>(i), walls_.size() + e))
      return queueEdgeFall(*this, i);
}

void StepContext::detectBall(std::size_t i, std::size_t j)
{
  // Always in index order, so that the same pair gives the same bits whoever asks.
  const std::size_t a = std::min(i, j), b = std::max(i, j);
  const Motion& ma = motions_[a];
  const Motion& mb = motions_[b];
  if (ma.type != MotionType::kLine || mb.type != MotionType::kLine || grouped(a))
    return detectPairApart(a, b);
  // (the common pair: two free lines, neither in a group)
  const double xs = std::max(ma.x0, mb.x0);
  if (const auto t = linesMeet(a, b, xs))
    pushPairEvent(a, b, xs + *t);
}

std::optional<double> StepContext::linesMeet(std::size_t a, std::size_t b, double xs) const
{
  const Motion& ma = motions_[a];
  const Motion& mb = motions_[b];
  const Vec3 d = (balls_[a].position + (xs - ma.x0) * ma.b) - (balls_[b].position + (xs - mb.x0) * mb.b);
  return sphereSweep(d, ma.b - mb.b, balls_[a].radius + balls_[b].radius, 1 - xs, settings_.closing_slop);
}

void StepContext::detectPairApart(std::size_t a, std::size_t b)
{
  if ((motions_[a].frozen() && motions_[b].frozen()) || motions_[a].gone() || motions_[b].gone())
    return;  // neither moves (asleep, or stopped by the cap), or one dropped into a pocket: no impact
  if (grouped(a) && linked(a, static_cast<std::uint32_t>(b)))
    return;  // a resting contact: a constraint of their group
  const Motion& ma = motions_[a];
  const Motion& mb = motions_[b];
  const double xs = std::max(ma.x0, mb.x0);
  std::optional<double> t;
  if (!ma.accelerates() && !mb.accelerates())
    t = linesMeet(a, b, xs);
  else
  {
    // a parabola and a line, or two parabolas of different terms: a quartic (of the same
    // term, their difference is a line, and its quartic's higher terms are zero)
    const Vec3 d = positionAt(a, xs) - positionAt(b, xs);
    t = sphereSweepAccelerated(d, rateAt(a, xs) - rateAt(b, xs), parabolaOf(a) - parabolaOf(b),
                               balls_[a].radius + balls_[b].radius, 1 - xs, settings_.closing_slop);
  }
  if (t)
    pushPairEvent(a, b, xs + *t);
}

void StepContext::pushPairEvent(std::size_t a, std::size_t b, double x)
{
  pushEvent(Event{x, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), motions_[a].epoch, motions_[b].epoch,
                  EventKind::kBallBall, WallFeature::kFace, MotionEnd::kPhase, Vec3::Zero()});
}
}  // namespace ball_collision_sim::core
