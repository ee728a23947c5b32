// The step's event queue: earliest first, and ties in the balls' order in the world
// (ids), whatever order the step visits them in.
#include "ball_collision_sim/core/event_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace ball_collision_sim::core;

namespace
{
StepEvent ballEvent(double x, std::uint32_t i, std::uint32_t j)
{
  return StepEvent{x, i, j, 0, 0, EventKind::kBallBall, WallFeature::kFace, MotionEnd::kPhase, Vec3::Zero()};
}

StepEvent wallEvent(double x, std::uint32_t i, std::uint32_t wall)
{
  return StepEvent{x, i, wall, 0, 0, EventKind::kBallWall, WallFeature::kFace, MotionEnd::kPhase, Vec3::UnitX()};
}

/// Every field of an event that came out of the queue is as it went in.
void expectSameEvent(const StepEvent& out, const StepEvent& in)
{
  EXPECT_EQ(out.x, in.x);
  EXPECT_EQ(out.i, in.i);
  EXPECT_EQ(out.j, in.j);
  EXPECT_EQ(out.epoch_i, in.epoch_i);
  EXPECT_EQ(out.epoch_j, in.epoch_j);
  EXPECT_EQ(out.kind, in.kind);
  EXPECT_EQ(out.feature, in.feature);
  EXPECT_EQ(out.end, in.end);
  EXPECT_EQ(out.normal, in.normal) << "event " << out.epoch_i;
}

/// The balls by visiting index k, ball k having id order[k] + 1 (ids start at 1).
std::vector<Ball> ballsWithIds(const std::vector<std::uint32_t>& order)
{
  std::vector<Ball> balls(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    balls[k].id = static_cast<int>(order[k]) + 1;
  return balls;
}
}  // namespace

TEST(EventQueue, EarliestFirstAndTiesByTheBallsIdsNotTheVisitingOrder)
{
  // visiting index k is ball order[k] of the world's list, in id order
  const std::vector<std::uint32_t> order{3, 0, 4, 1, 2};
  const std::vector<Ball> balls = ballsWithIds(order);
  EventQueue queue;
  queue.start(&balls);
  queue.push(ballEvent(0.7, 0, 1));   // balls 3 and 0
  queue.push(ballEvent(0.5, 2, 3));   // balls 4 and 1
  queue.push(wallEvent(0.5, 2, 7));   // ball 4, wall 7
  queue.push(ballEvent(0.5, 1, 4));   // balls 0 and 2
  queue.push(wallEvent(0.5, 1, 9));   // ball 0, wall 9
  queue.push(wallEvent(0.5, 1, 2));   // ball 0, wall 2
  queue.push(ballEvent(0.25, 4, 0));  // balls 2 and 3
  ASSERT_EQ(queue.size(), 7u);
  std::vector<std::pair<double, std::vector<std::uint32_t>>> got;
  while (!queue.empty())
  {
    const StepEvent e = queue.pop();
    got.push_back({e.x, {order[e.i], e.kind == EventKind::kBallWall ? 100 + e.j : order[e.j]}});
  }
  const std::vector<std::pair<double, std::vector<std::uint32_t>>> expected{
      {0.25, {2, 3}},
      // at 0.5: ball 0's walls (2 then 9), then the pairs by lower then higher ball:
      // (0, 2), then ball 1's pair with 4, then ball 4's wall
      {0.5, {0, 102}}, {0.5, {0, 109}}, {0.5, {0, 2}}, {0.5, {4, 1}}, {0.5, {4, 107}},
      {0.7, {3, 0}},
  };
  EXPECT_EQ(got, expected);
}

// Many events pushed and popped in between, with slots reused: once the last is pushed,
// what comes out is in order of time, then of the balls' ids as above.
TEST(EventQueue, DrainsInOrderWithSlotsReused)
{
  std::vector<std::uint32_t> order(50);
  for (std::uint32_t k = 0; k < order.size(); ++k)
    order[k] = (k * 17) % 50;  // a scrambled visiting order
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::uint32_t> ball(0, 49);
  std::uniform_int_distribution<int> time(0, 20);  // few distinct times: many ties
  const std::vector<Ball> balls = ballsWithIds(order);
  EventQueue queue;
  queue.start(&balls);
  std::size_t pushed = 0, popped = 0;
  for (int k = 0; k < 2000; ++k)
  {
    const std::uint32_t a = ball(rng), b = ball(rng);
    queue.push((k % 3 == 0) ? wallEvent(time(rng) / 20.0, a, b % 6) : ballEvent(time(rng) / 20.0, a, b));
    ++pushed;
    if (k % 5 == 4)
    {
      queue.pop();
      ++popped;
    }
  }
  using Key = std::array<double, 4>;
  const auto key = [&](const StepEvent& e) {
    const double i = order[e.i], j = e.kind == EventKind::kBallWall ? e.j : order[e.j];
    return e.kind == EventKind::kBallWall ? Key{e.x, i, 0, j} : Key{e.x, std::min(i, j), 1, std::max(i, j)};
  };
  std::vector<Key> drained;
  while (!queue.empty())
    drained.push_back(key(queue.pop()));
  EXPECT_EQ(drained.size(), pushed - popped);
  EXPECT_TRUE(std::is_sorted(drained.begin(), drained.end()));
  // a queue that came out unsorted would fail here: the same keys shuffled are not
  std::vector<Key> shuffled = drained;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  EXPECT_FALSE(std::is_sorted(shuffled.begin(), shuffled.end()));
}

// Every event comes out as it went in, fields and all: a wall event's normal is kept
// apart from the queued record, in places that are freed and reused as events come and
// go; each must come back with its own.
TEST(EventQueue, EachEventComesBackWithItsOwnNormalAndFields)
{
  const std::vector<Ball> balls = ballsWithIds({0, 1, 2, 3, 4, 5, 6, 7});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<std::uint32_t> ball(0, 7);
  EventQueue queue;
  queue.start(&balls);
  // each event is told apart by its epochs, which carry its number
  std::vector<StepEvent> sent;
  std::size_t checked = 0;
  const auto take = [&] {
    const StepEvent out = queue.pop();
    ASSERT_LT(out.epoch_i, sent.size());
    expectSameEvent(out, sent[out.epoch_i]);
    ++checked;
  };
  for (std::uint32_t k = 0; k < 3000; ++k)
  {
    const double x = 0.5 + 0.5 * u(rng);
    StepEvent e = k % 2 == 0 ? wallEvent(x, ball(rng), k % 5) : ballEvent(x, ball(rng), ball(rng));
    if (e.kind == EventKind::kBallWall)
    {
      e.normal = Vec3(u(rng), u(rng), u(rng)).normalized();
      e.feature = k % 3 == 0 ? WallFeature::kEdge : WallFeature::kFace;
    }
    e.epoch_i = static_cast<std::uint16_t>(k);
    e.epoch_j = static_cast<std::uint16_t>(7 * k);  // (below 2^16)
    e.end = k % 7 == 0 ? MotionEnd::kCut : (k % 11 == 0 ? MotionEnd::kLanding : MotionEnd::kPhase);
    sent.push_back(e);
    queue.push(e);
    if (k % 3 == 2)
      take();
  }
  while (!queue.empty())
    take();
  EXPECT_EQ(checked, sent.size());
}

// forget(ball) drops that ball's events, wall, pair and transition alike, and keeps the
// rest in order, each with its own fields; the places it frees are reused.
TEST(EventQueue, ForgetDropsOneBallsEventsAndKeepsTheRestInOrder)
{
  const std::vector<Ball> balls = ballsWithIds({0, 1, 2, 3, 4, 5, 6, 7});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<std::uint32_t> ball(0, 7);
  EventQueue queue;
  queue.start(&balls);
  std::vector<StepEvent> sent;
  const auto push = [&](StepEvent e) {
    e.epoch_i = static_cast<std::uint16_t>(sent.size());  // its number
    if (e.kind == EventKind::kBallWall)
      e.normal = Vec3(u(rng), u(rng), 1).normalized();
    sent.push_back(e);
    queue.push(e);
  };
  const auto involves = [](const StepEvent& e, std::uint32_t k) {
    return e.i == k || (e.kind != EventKind::kBallWall && e.j == k);
  };
  for (int k = 0; k < 600; ++k)
  {
    const std::uint32_t a = ball(rng);
    if (k % 7 == 0)
      push(StepEvent{u(rng), a, a, 0, 0, EventKind::kMotionEnd, WallFeature::kFace, MotionEnd::kPhase, Vec3::Zero()});
    else
      push(k % 3 == 0 ? wallEvent(u(rng), a, 3) : ballEvent(u(rng), a, ball(rng)));
  }
  queue.forget(3);
  // more after the forgetting, into the freed places
  for (int k = 0; k < 200; ++k)
    push(k % 3 == 0 ? wallEvent(u(rng), ball(rng), 1) : ballEvent(u(rng), ball(rng), ball(rng)));
  std::size_t kept = 0;
  for (std::size_t k = 0; k < sent.size(); ++k)
    kept += k >= 600 || !involves(sent[k], 3);
  ASSERT_LT(kept, sent.size() - 50) << "ball 3 had events to forget";
  std::size_t out = 0;
  double last = -1;
  while (!queue.empty())
  {
    const StepEvent e = queue.pop();
    ASSERT_LT(e.epoch_i, sent.size());
    const StepEvent& in = sent[e.epoch_i];
    EXPECT_TRUE(e.epoch_i >= 600 || !involves(in, 3)) << "event " << e.epoch_i << " was forgotten";
    EXPECT_GE(e.x, last);
    expectSameEvent(e, in);
    last = e.x;
    ++out;
  }
  EXPECT_EQ(out, kept);
}
