// The C++ rostests' collector of one topic's messages (test_node, test_play).
#pragma once

#include <ros/ros.h>

#include <mutex>
#include <string>
#include <vector>

namespace ball_collision_sim::test
{
/// Collects every message of one topic, from a subscription of its own.
template <class Msg>
class Inbox
{
public:
  explicit Inbox(const std::string& topic)
  {
    ros::NodeHandle nh;
    sub_ = nh.subscribe<Msg>(topic, 1000, [this](const boost::shared_ptr<const Msg>& msg) {
      std::lock_guard<std::mutex> lock(mutex_);
      msgs_.push_back(*msg);
    });
  }
  /// Unsubscribes first: roscpp waits for a callback in progress, which uses the members.
  ~Inbox() { sub_.shutdown(); }
  Inbox(const Inbox&) = delete;
  Inbox& operator=(const Inbox&) = delete;
  /// Every message so far.
  std::vector<Msg> all()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return msgs_;
  }
  /// Every message so far, taken out.
  std::vector<Msg> take()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Msg> out;
    out.swap(msgs_);
    return out;
  }
  /// Waits until `pred(all messages so far)` holds or the timeout passes.
  template <class Pred>
  bool waitFor(Pred pred, double timeout = 5.0)
  {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::WallTime::now() < end)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (pred(msgs_))
          return true;
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }
  bool connected() const { return sub_.getNumPublishers() > 0; }

private:
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::vector<Msg> msgs_;
};
}  // namespace ball_collision_sim::test
