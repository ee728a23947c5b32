// Stages 2 and 3, broad phase and detection: the swept boxes into the grid, then the
// exact first time of impact of each nearby pair and wall, into the event queue.
// Reads motions_, states_, walls_, the grid; writes heap_, event_pool_, free_slots_.
#include "step_types.hpp"

#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

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
  if (states_[a].frozen && states_[b].frozen)
    return;  // neither moves (asleep, or stopped by the cap): no impact
  const Motion& ma = motions_[a];
  const Motion& mb = motions_[b];
  const double xs = std::max(ma.x0, mb.x0);
  const Vec3 d = (ma.p0 + (xs - ma.x0) * ma.b) - (mb.p0 + (xs - mb.x0) * mb.b);
  const auto t = sphereSweep(d, ma.b - mb.b, ma.radius + mb.radius, 1 - xs);
  if (t)
    pushEvent(Event{xs + *t, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), states_[a].epoch, states_[b].epoch,
                    false, WallFeature::kFace, Vec3::Zero()});
}
}  // namespace ball_collision_sim::core
