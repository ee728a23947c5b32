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
  normals_.clear();
  free_normals_.clear();
}

namespace
{
/// Puts `value` into `pool` at a free place (the last freed one), or at its end; its index.
template <class T>
std::uint32_t place(std::vector<T>& pool, std::vector<std::uint32_t>& free, const T& value)
{
  if (free.empty())
  {
    pool.push_back(value);
    return static_cast<std::uint32_t>(pool.size() - 1);
  }
  const std::uint32_t at = free.back();
  free.pop_back();
  pool[at] = value;
  return at;
}
}  // namespace

bool EventQueue::later(const Entry& qa, const Entry& qb) const
{
  if (qa.x != qb.x)
    return qa.x > qb.x;
  const Queued& a = pool_[qa.slot];
  const Queued& b = pool_[qb.slot];
  const auto key = [&](const Queued& e) {
    // (ids are positive)
    const auto i = static_cast<std::uint32_t>((*balls_)[e.i].id);
    using Key = std::array<std::uint32_t, 3>;
    constexpr std::uint32_t kLast = std::numeric_limits<std::uint32_t>::max();
    switch (e.kind)
    {
      case EventKind::kBallWall:
        return Key{i, 0, e.j};
      case EventKind::kMotionEnd:  // after the ball's wall events
        return Key{i, 0, kLast - (e.end == MotionEnd::kLanding ? 1 : 0)};
      case EventKind::kPocket:  // after its walls, before its motion's end
        return Key{i, 0, kLast - 2};
      case EventKind::kBallBall:
        break;
    }
    const auto j = static_cast<std::uint32_t>((*balls_)[e.j].id);
    return Key{std::min(i, j), 1, std::max(i, j)};
  };
  return key(a) > key(b);
}

void EventQueue::push(const StepEvent& event)
{
  static_assert(sizeof(Queued) == 20, "a queued event is its fields but the time and the normal");
  static_assert(sizeof(Entry) == 12, "a heap entry is a time and a slot");
  Queued queued{event.i, event.j, event.epoch_i, event.epoch_j, event.kind, event.feature, event.end, 0};
  if (event.kind == EventKind::kBallWall)
    queued.normal = place(normals_, free_normals_, event.normal);
  const std::uint32_t slot = place(pool_, free_slots_, queued);
  heap_.push_back({event.x, slot});
  std::push_heap(heap_.begin(), heap_.end(), byTime());
}

void EventQueue::forget(std::uint32_t ball)
{
  const auto of_ball = [&](const Entry& entry) {
    const Queued& q = pool_[entry.slot];
    if (q.i != ball && (ofOneBall(q.kind) || q.j != ball))
      return false;
    free_slots_.push_back(entry.slot);
    if (q.kind == EventKind::kBallWall)
      free_normals_.push_back(q.normal);
    return true;
  };
  heap_.erase(std::remove_if(heap_.begin(), heap_.end(), of_ball), heap_.end());
  std::make_heap(heap_.begin(), heap_.end(), byTime());
}

StepEvent EventQueue::pop()
{
  std::pop_heap(heap_.begin(), heap_.end(), byTime());
  const auto [x, slot] = heap_.back();
  heap_.pop_back();
  free_slots_.push_back(slot);
  // The next event is most likely the one now first: its record is fetched while this
  // one is handled (events in time order reach the balls' data at random).
  if (!heap_.empty())
    __builtin_prefetch(&pool_[heap_.front().slot]);
  const Queued& q = pool_[slot];
  StepEvent event{x, q.i, q.j, q.epoch_i, q.epoch_j, q.kind, q.feature, q.end, Vec3::Zero()};
  if (q.kind == EventKind::kBallWall)
  {
    event.normal = normals_[q.normal];
    free_normals_.push_back(q.normal);
  }
  return event;
}
}  // namespace ball_collision_sim::core
