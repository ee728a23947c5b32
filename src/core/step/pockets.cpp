// Pockets (Scene::pockets): a ball on the floor whose centre crosses a pocket's circle (in
// x and y) drops into it at that exact time. The drop is an event of the step, found with
// the ball's other events from its motion (circleEntry()) and handled in time order: from
// then on the ball has no motion and nothing meets it (MotionType::kPocketed), the rest of
// its resting group goes on without it, and the step's end takes it out of the world.
// Reads motions_, the scene's pockets; writes pocketed_, the ball's motion, balls_ at the
// step's end.
#include "spin_model.hpp"
#include "stages.hpp"
#include "step_types.hpp"

#include "ball_collision_sim/core/time_of_impact.hpp"

#include <algorithm>

namespace ball_collision_sim::core
{
using namespace step;

void StepContext::queuePockets(std::size_t i)
{
  const Motion& m = motions_[i];
  // (a ball in flight passes over a pocket; where it lands in one, its motion on the floor
  // starts inside the circle and it drops at once)
  if (m.frozen() || balls_[i].flying())
    return;
  const auto flat = [](const Vec3& a) { return Vec3(a.x(), a.y(), 0.0); };
  const Vec3 p = flat(startPosition(i)), e = flat(m.b);
  const Vec3 c = m.accelerates() ? flat(pathTerm(i)) : Vec3(Vec3::Zero());
  const double rest = (m.accelerates() ? 1.0 : chordEnd(i)) - m.x0;
  for (std::size_t k = 0; k < scene_.pockets.size(); ++k)
  {
    const PocketDef& pocket = scene_.pockets[k];
    const Vec3 d = p - Vec3(pocket.position.x(), pocket.position.y(), 0.0);
    if (const auto t = circleEntry(d, e, c, pocket.radius, rest))
      pushEvent(Event{m.x0 + *t, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k), m.epoch, 0,
                      EventKind::kPocket, WallFeature::kFace, MotionEnd::kPhase, Vec3::Zero()});
  }
}

void StepContext::resolvePocket(const Event& event)
{
  const std::size_t i = event.i;
  const Ball& ball = balls_[i];
  const Vec3 p = positionAt(i, event.x);
  const Vec3 n = floorNormalAt(i, p);
  const Vec3 v = onFloorVelocity(i, event.x, p, n);
  PocketedBall out;
  out.time = (static_cast<double>(stats_.steps) + event.x) * dt_;
  out.pocket = static_cast<int>(event.j);
  out.ball = ball;
  out.ball.position = p;
  out.ball.velocity = v;
  out.inertia = spin_->inertia(*this, i);
  if (scene_.friction)
  {
    out.angular_velocity = spinAtEvent(i, event.x, n, v);
    out.motion = frictionUnder(n).kindOf(out.inertia, ball.radius, v, out.angular_velocity);
  }
  else
  {
    out.angular_velocity = n.cross(v) / ball.radius;  // (rolling's)
    out.motion = v == Vec3::Zero() ? MotionKind::kStationary : MotionKind::kRolling;
  }
  pocketed_.push_back(out);
  ++stats_.pocketed_balls;
  // Out of the step from here: where it dropped, without motion or spin, its events stale.
  beginMotion(i, event.x, p, Vec3::Zero());
  Motion& m = motions_[i];
  m.type = MotionType::kPocketed;
  m.b = Vec3::Zero();
  spin_->cap(*this, i);
  renewMotion(i);
  // (what rested on it goes on without it)
  if (grouped(i))
    solveGroup(i, event.x);
}

bool StepContext::linkGone(const ContactLink& link) const
{
  return motions_[link.a].gone() || (!(link.b & kWallRow) && motions_[link.b].gone());
}

void StepContext::removePocketed()
{
  if (pocketed_.empty())
    return;
  std::vector<int> ids;
  for (const PocketedBall& out : pocketed_)
    ids.push_back(out.ball.id);
  std::sort(ids.begin(), ids.end());
  const auto dropped = [&](int id) { return std::binary_search(ids.begin(), ids.end(), id); };
  removeBalls([&](std::size_t s) { return dropped(balls_[s].id); });
  // (the step's end saw no motion in them: it reports no change of their kind after the drop)
  transitions_.erase(std::remove_if(transitions_.begin(), transitions_.end(),
                                    [&](const MotionTransition& t) {
                                      const auto it = std::find_if(pocketed_.begin(), pocketed_.end(),
                                                                   [&](const PocketedBall& b) { return b.ball.id == t.ball; });
                                      return it != pocketed_.end() && t.time > it->time;
                                    }),
                     transitions_.end());
}
}  // namespace ball_collision_sim::core
