// The step's threads (workers.hpp): a loop split into contiguous runs, one a thread; and
// StepContext's loop over the balls on them, with what the runs record put together.
#include "workers.hpp"

#include "step_context.hpp"

#include <algorithm>

namespace ball_collision_sim::core::step
{
namespace
{
// (initial-exec: read as one load from the thread's block, not a call, in the shared
// library too, which is linked at start, never opened later)
thread_local Tally* tally_here __attribute__((tls_model("initial-exec"))) = nullptr;

/// Sets the calling thread's tally for as long as it lives.
struct TallyScope
{
  explicit TallyScope(Tally* tally) { tally_here = tally; }
  ~TallyScope() { tally_here = nullptr; }
  TallyScope(const TallyScope&) = delete;
  TallyScope& operator=(const TallyScope&) = delete;
};
}  // namespace

Tally* tallyHere()
{
  return tally_here;
}

Workers::~Workers()
{
  resize(1);
}

void Workers::resize(unsigned threads, std::chrono::microseconds spin)
{
  threads = std::max(threads, 1u);
  if (threads == this->threads() && spin == spin_)
    return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  start_.notify_all();
  for (std::thread& t : pool_)
    t.join();
  pool_.clear();
  quit_ = false;
  spin_ = spin;  // (no thread of its own reads it now)
  // (thread k serves run k; the caller's thread runs run 0)
  for (std::size_t k = 1; k < threads; ++k)
    pool_.emplace_back([this, k] { serve(k); });
}

template <class Ready>
bool Workers::spinFor(Ready&& ready) const
{
  // (a thread that sleeps between a step's loops can take far longer to wake, in a
  // virtual machine, than the loop it is woken for)
  if (spin_.count() <= 0)
    return ready();
  const auto until = std::chrono::steady_clock::now() + spin_;
  for (unsigned k = 1;; ++k)
  {
    if (ready())
      return true;
    if (k % 64 == 0 && std::chrono::steady_clock::now() > until)
      return false;
    std::this_thread::yield();
  }
}

void Workers::split(std::size_t n, std::vector<Tally>& tallies,
                    const std::function<void(std::size_t, std::size_t, std::size_t)>& body)
{
  const std::size_t runs = threads();
  tallies.resize(runs);
  for (Tally& tally : tallies)
  {
    // (emptied, their memory kept for the next loop)
    tally.transitions.clear();
    tally.events.clear();
    tally.stopped = 0;
    tally.flights = 0;
  }
  errors_.assign(runs, nullptr);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    n_ = n;
    tallies_ = &tallies;
    body_ = &body;
    pending_.store(runs - 1);
    generation_.fetch_add(1);
  }
  start_.notify_all();
  runPart(0);
  if (!spinFor([this] { return pending_.load() == 0; }))
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_.load() == 0; });
  }
  body_ = nullptr;
  tallies_ = nullptr;
  for (const std::exception_ptr& error : errors_)
    if (error)
      std::rethrow_exception(error);
}

void Workers::runPart(std::size_t k)
{
  const std::size_t runs = threads();
  // run k: [k n / runs, (k + 1) n / runs), as even as whole balls allow
  const std::size_t begin = k * n_ / runs, end = (k + 1) * n_ / runs;
  TallyScope scope(&(*tallies_)[k]);
  try
  {
    (*body_)(k, begin, end);
  }
  catch (...)
  {
    errors_[k] = std::current_exception();
  }
}

void Workers::serve(std::size_t k)
{
  std::uint64_t seen = 0;
  for (;;)
  {
    const auto handed_out = [&] { return quit_.load() || generation_.load() != seen; };
    if (!spinFor(handed_out))
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, handed_out);
    }
    if (quit_)
      return;
    seen = generation_.load();
    runPart(k);
    if (pending_.fetch_sub(1) == 1)
    {
      // (the caller may be asleep on done_: told under the mutex, so that it cannot miss it)
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}
}  // namespace ball_collision_sim::core::step

namespace ball_collision_sim::core
{
void StepContext::forEachBall(const std::function<void(std::size_t, std::size_t)>& run)
{
  splitLoop(balls_.size(), balls_.size(), run);
}

void StepContext::splitLoop(std::size_t n, std::size_t balls, const std::function<void(std::size_t, std::size_t)>& run)
{
  const unsigned threads = settings_.threads != 0 ? settings_.threads : std::thread::hardware_concurrency();
  if (threads <= 1 || balls < settings_.parallel_min_balls)
  {
    run(0, n);
    return;
  }
  step::Workers& workers = workers_.get();
  workers.resize(threads, std::chrono::microseconds(settings_.thread_spin_us));
  std::vector<step::Tally>& tallies = tallies_.get();
  workers.split(n, tallies, [&](std::size_t, std::size_t begin, std::size_t end) { run(begin, end); });
  // (what the runs recorded, in their order: the order of one run over [0, n))
  for (const step::Tally& tally : tallies)
  {
    transitions_.insert(transitions_.end(), tally.transitions.begin(), tally.transitions.end());
    stats_.transitions += tally.transitions.size();
    stats_.stopped_balls += tally.stopped;
    flights_ += tally.flights;
    for (const Event& event : tally.events)
      queue_.push(event);
  }
}

void StepContext::pushEvent(const Event& event)
{
  if (step::Tally* tally = step::tallyHere())
    tally->events.push_back(event);
  else
    queue_.push(event);
}

void StepContext::noteTransition(std::size_t i, double x, MotionKind from, MotionKind to)
{
  const MotionTransition t{(static_cast<double>(stats_.steps) + x) * dt_, balls_[i].id, from, to};
  if (step::Tally* tally = step::tallyHere())
  {
    tally->transitions.push_back(t);
    return;
  }
  ++stats_.transitions;
  transitions_.push_back(t);
}

void StepContext::noteStopped()
{
  if (step::Tally* tally = step::tallyHere())
    ++tally->stopped;
  else
    ++stats_.stopped_balls;
}

void StepContext::noteFlight()
{
  if (step::Tally* tally = step::tallyHere())
    ++tally->flights;
  else
    ++flights_;
}
}  // namespace ball_collision_sim::core
