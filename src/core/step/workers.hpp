// The threads a step's per-ball stages run on: one loop at a time over [0, n), cut into
// as many contiguous runs as there are threads, the caller's thread taking the first.
// What a run records (transitions, events found, counts) goes to that run's Tally and is
// put together in the runs' order afterwards: the order one thread would have made, so
// that every count of threads gives the same bits. Not part of the public interface.
#pragma once

#include "ball_collision_sim/core/event_queue.hpp"
#include "ball_collision_sim/core/world.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace ball_collision_sim::core::step
{
/// What one run of balls records that is the whole step's, kept apart while the runs go
/// on at once.
struct Tally
{
  std::vector<MotionTransition> transitions;
  std::vector<StepEvent> events;  ///< events found, for the queue
  std::uint64_t stopped = 0;  ///< balls whose energy ran out (WorldStats::stopped_balls)
  std::uint32_t flights = 0;  ///< flights started (StepState::flights_)
};

/// The tally of the run the calling thread works on, or null outside a split loop (then
/// what it records goes straight to the step).
Tally* tallyHere();

/// A fixed set of threads for split loops (none of its own where it runs on one).
class Workers
{
public:
  Workers() = default;
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  ~Workers();
  /// Runs on `threads` threads from now on (at least 1), starting or ending its own; a
  /// thread waiting for work, and the caller waiting for the threads, looks for it
  /// without sleeping for `spin` first.
  void resize(unsigned threads, std::chrono::microseconds spin = std::chrono::microseconds(0));
  unsigned threads() const { return static_cast<unsigned>(pool_.size()) + 1; }
  /// Calls body(k, begin, end) for run k of [0, n), runs in order of k, each on a thread
  /// of its own with tallyHere() its tallies[k] (tallies is resized to the runs); returns
  /// once every run is done, with the exception of the first run that threw, if any.
  void split(std::size_t n, std::vector<Tally>& tallies,
             const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

private:
  void serve(std::size_t k);
  void runPart(std::size_t k);
  /// Whether ready() holds within the spin time, looked at without sleeping.
  template <class Ready>
  bool spinFor(Ready&& ready) const;

  std::vector<std::thread> pool_;
  std::chrono::microseconds spin_{0};
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  /// Bumped (under mutex_) when a loop is handed out; its fields are set before.
  std::atomic<std::uint64_t> generation_{0};
  /// The runs of the loop handed out still going, but the caller's.
  std::atomic<std::size_t> pending_{0};
  std::atomic<bool> quit_{false};
  // the loop being split
  std::size_t n_ = 0;
  std::vector<Tally>* tallies_ = nullptr;
  const std::function<void(std::size_t, std::size_t, std::size_t)>* body_ = nullptr;
  std::vector<std::exception_ptr> errors_;
};
}  // namespace ball_collision_sim::core::step
