#include "ball_collision_sim/core/event_queue.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace ball_collision_sim::core
{
void EventQueue::start(const std::vector<Ball>* balls)
{
  balls_ = balls;
  heap_.clear();
  pool_.clear();
  free_slots_.clear();
}

bool EventQueue::later(const Entry& qa, const Entry& qb) const
{
  if (qa.x != qb.x)
    return qa.x > qb.x;
  const StepEvent& a = pool_[qa.slot];
  const StepEvent& b = pool_[qb.slot];
  const auto key = [&](const StepEvent& e) {
    // (ids are positive)
    const auto i = static_cast<std::uint32_t>((*balls_)[e.i].id);
    const auto j = e.wall ? e.j : static_cast<std::uint32_t>((*balls_)[e.j].id);
    using Key = std::array<std::uint32_t, 3>;
    if (e.transition)
      return Key{i, 0, std::numeric_limits<std::uint32_t>::max()};  // after the ball's wall events
    return e.wall ? Key{i, 0, j} : Key{std::min(i, j), 1, std::max(i, j)};
  };
  return key(a) > key(b);
}

void EventQueue::push(const StepEvent& event)
{
  std::uint32_t slot = 0;
  if (free_slots_.empty())
  {
    slot = static_cast<std::uint32_t>(pool_.size());
    pool_.push_back(event);
  }
  else
  {
    slot = free_slots_.back();
    free_slots_.pop_back();
    pool_[slot] = event;
  }
  heap_.push_back({event.x, slot});
  std::push_heap(heap_.begin(), heap_.end(), [this](const Entry& a, const Entry& b) { return later(a, b); });
}

StepEvent EventQueue::pop()
{
  std::pop_heap(heap_.begin(), heap_.end(), [this](const Entry& a, const Entry& b) { return later(a, b); });
  const std::uint32_t slot = heap_.back().slot;
  heap_.pop_back();
  free_slots_.push_back(slot);
  // The next event is most likely the one now first: its record is fetched while this
  // one is handled (events in time order reach the balls' data at random).
  if (!heap_.empty())
    __builtin_prefetch(&pool_[heap_.front().slot]);
  return pool_[slot];
}
}  // namespace ball_collision_sim::core
