// A group of balls joined by resting contacts, as the contact solver takes it: the
// balls by a local index, their vectors and inverse masses, and one row per contact
// (with friction, the balls' spins and the contacts' friction). Reused from step to
// step, so that it allocates only as it grows. Not part of the public interface.
#pragma once

#include "contact_friction.hpp"
#include "step_types.hpp"

namespace ball_collision_sim::core
{
struct StepState::ContactGroup
{
  std::vector<Vec3> u;
  std::vector<double> inv_mass;
  std::vector<step::ContactRow> rows;
  /// with friction at the contacts: each ball's spin [rad/s] and what an impulse turns it
  /// by, and the contacts' friction (none without)
  std::vector<Vec3> w;
  std::vector<double> inv_inertia;
  std::vector<step::FrictionPair> friction;

  std::size_t size() const { return balls_.size(); }
  /// The visiting index of the group's k-th ball.
  std::size_t ballAt(std::size_t k) const { return balls_[k]; }
  /// The local index of the ball with visiting index i, which joins the group if new.
  std::uint32_t localOf(std::size_t i)
  {
    if (local_.size() <= i)
      local_.resize(i + 1, kNone);
    if (local_[i] == kNone)
    {
      local_[i] = static_cast<std::uint32_t>(balls_.size());
      balls_.push_back(static_cast<std::uint32_t>(i));
      u.emplace_back(Vec3::Zero());
      inv_mass.push_back(0.0);
      w.emplace_back(Vec3::Zero());
      inv_inertia.push_back(0.0);
    }
    return local_[i];
  }
  /// A contact between balls i and j (visiting indices), pushed apart along push_i and
  /// push_j (the normal from i toward j, along each one's floor).
  void addPair(std::size_t i, std::size_t j, const Vec3& push_i, const Vec3& push_j)
  {
    step::ContactRow row;
    row.a = localOf(i);
    row.b = localOf(j);
    row.push_a = push_i;
    row.push_b = push_j;
    rows.push_back(row);
  }
  void clear()
  {
    for (const std::uint32_t i : balls_)
      local_[i] = kNone;
    balls_.clear();
    u.clear();
    inv_mass.clear();
    rows.clear();
    w.clear();
    inv_inertia.clear();
    friction.clear();
  }

private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> balls_;
  std::vector<std::uint32_t> local_;
};
}  // namespace ball_collision_sim::core
