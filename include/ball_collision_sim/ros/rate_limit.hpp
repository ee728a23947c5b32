#pragma once

#include <limits>

namespace ball_collision_sim::bridge
{
/// When to send something at a given rate from the ticks of a timer. A send is due a
/// period after the last one was due, not after it was sent: the ticks would otherwise
/// round the rate down to a whole number of them (30 Hz on ticks of 10 ms would be
/// 25 Hz). After a gap of more than a period (a pause, a stall) the count starts afresh
/// instead of catching up in a burst.
class RateLimit
{
public:
  /// Whether a send is due at time `now` [s] at `rate` [Hz] (never at rate 0); `force`
  /// makes it due now, and the count starts afresh from it.
  bool due(double rate, double now, bool force)
  {
    if (!(rate > 0))
      return false;
    const double period = 1.0 / rate;
    const double since = now - last_;
    if (!force && since < period)
      return false;
    last_ = !force && since < 2 * period ? last_ + period : now;
    return true;
  }

private:
  double last_ = -std::numeric_limits<double>::infinity();
};
}  // namespace ball_collision_sim::bridge
