// The records in the step's cell order: the step visits balls_ in the order of the grid's
// cells, so that neighbours in space are neighbours in memory; an edit puts them back in
// id order. Reads and writes balls_, feet_, spins_ and by_id_ (the slot of each ball by
// its place in id order).
#include "permutation.hpp"

#include "step/step_context.hpp"

namespace ball_collision_sim::core
{
void StepContext::sortById()
{
  bool sorted = true;
  for (std::size_t k = 0; k < by_id_.size() && sorted; ++k)
    sorted = by_id_[k] == k;
  if (sorted)
    return;
  std::vector<std::uint32_t> from = by_id_;  // slot k takes the k-th by id
  permute(from);
}

void StepContext::permute(std::vector<std::uint32_t>& from)
{
  // Where each slot's record goes, for by_id_: slot from[k] -> slot k (the inverse of
  // `from`, turned in place and back, so that no second list is needed).
  invertInPlace(from);
  for (std::uint32_t& slot : by_id_)
    slot = from[slot];
  invertInPlace(from);
  // In place, cycle by cycle (each ball's foot point and spin with it, where kept)
  struct Records
  {
    StepContext& w;
    Ball ball;
    Vec2 foot;
    BallSpin spin;
    void save(std::uint32_t k)
    {
      ball = w.balls_[k];
      foot = w.feet_.empty() ? w.no_foot_ : w.feet_[k];
      spin = w.spins_.empty() ? BallSpin{} : w.spins_[k];
    }
    void move(std::uint32_t into, std::uint32_t out)
    {
      w.balls_[into] = w.balls_[out];
      if (!w.feet_.empty())
        w.feet_[into] = w.feet_[out];
      if (!w.spins_.empty())
        w.spins_[into] = w.spins_[out];
    }
    void restore(std::uint32_t k)
    {
      w.balls_[k] = ball;
      if (!w.feet_.empty())
        w.feet_[k] = foot;
      if (!w.spins_.empty())
        w.spins_[k] = spin;
    }
  } records{*this, Ball{}, Vec2::Zero(), BallSpin{}};
  gatherInPlace(from, records);
}
}  // namespace ball_collision_sim::core
