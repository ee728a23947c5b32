#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/types.hpp"
#include "ball_collision_sim/core/wall.hpp"

#include <cstdint>
#include <vector>

namespace ball_collision_sim::core
{
/// How a ball's motion ends within the step where that is not an impact
/// (EventKind::kMotionEnd): its friction phase ends, its chord reaches the longest a
/// curved floor allows, its flight reaches the floor, or the floor's bend stops holding
/// it (it takes off).
enum class MotionEnd : std::uint8_t
{
  kPhase,
  kCut,
  kLanding,
  kTakeOff,
};

/// What a step's event is: an impact of two balls, or of a ball and a wall, the end of
/// a ball's motion (MotionEnd says why), or a ball's drop into a pocket.
enum class EventKind : std::uint8_t
{
  kBallBall,
  kBallWall,
  kMotionEnd,
  kPocket,
};

/// Whether an event of this kind concerns one ball (j is a wall's or a pocket's index, or
/// the ball itself), not two.
inline bool ofOneBall(EventKind kind) { return kind != EventKind::kBallBall; }

/// An impact predicted inside the step; stale once either ball's epoch has moved on (it
/// has had an event since).
struct StepEvent
{
  double x;                  ///< step fraction of the impact
  std::uint32_t i;           ///< visiting index of the ball (the lower one for ball-ball)
  std::uint32_t j;           ///< visiting index of the other ball, or the wall's or pocket's index
  std::uint16_t epoch_i;     ///< the balls' epochs when it was found (World::Motion::epoch)
  std::uint16_t epoch_j;
  EventKind kind;
  WallFeature feature;
  /// kMotionEnd: why ball i's motion ends (j = i)
  MotionEnd end;
  Vec3 normal;               ///< ball-wall: unit, from the wall toward the ball
};

/// The step's pending events, earliest first. Ties go by the balls' ids, not by the order
/// the step visits them in, so that a run is the same whatever that order is: a ball's
/// wall events before its ball events, and pairs by their lower, then higher, ball.
/// Events live in a pool and the heap holds their times and slots, so that sifting moves
/// 12 bytes, not an event.
class EventQueue
{
public:
  /// Empties the queue; `balls` are the balls by visiting index, whose ids break ties, and
  /// must outlive the queue's use until the next start().
  void start(const std::vector<Ball>* balls);
  void push(const StepEvent& event);
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  /// An event as the queue keeps it, in 20 bytes: StepEvent's fields but its time, which
  /// the heap holds, and the normal, which only a wall event has and which is kept apart
  /// (by its index).
  struct Queued
  {
    std::uint32_t i;
    std::uint32_t j;
    std::uint16_t epoch_i;
    std::uint16_t epoch_j;
    EventKind kind;
    WallFeature feature;
    MotionEnd end;
    std::uint32_t normal;
  };
  /// Drops every queued event of the ball at visiting index `ball` (its transitions too).
  void forget(std::uint32_t ball);
  /// The earliest event, still queued (without its normal).
  const Queued& top() const { return pool_[heap_.front().slot]; }
  /// Takes the earliest event out.
  StepEvent pop();

private:
  // (12 bytes, not 16: packed to 4, a time's 8 bytes read in one unaligned load)
#pragma pack(push, 4)
  struct Entry
  {
    double x;
    std::uint32_t slot;
  };
#pragma pack(pop)
  /// Whether a comes after b.
  bool later(const Entry& a, const Entry& b) const;
  /// later() as the heap's order.
  auto byTime() const
  {
    return [this](const Entry& a, const Entry& b) { return later(a, b); };
  }

  const std::vector<Ball>* balls_ = nullptr;
  std::vector<Entry> heap_;
  std::vector<Queued> pool_;
  std::vector<std::uint32_t> free_slots_;
  /// the queued wall events' normals, and the free places among them
  std::vector<Vec3> normals_;
  std::vector<std::uint32_t> free_normals_;
};
}  // namespace ball_collision_sim::core
