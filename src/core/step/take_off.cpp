// Take-off: a ball on the floor leaves it where an edit or a landing sends it away from
// it fast enough, where a curved floor would have to pull it to keep it on its bend (the
// zero of the floor's push along the motion, found to neighbouring doubles), or where its
// foot point passes the floor's edge: from there it flies (flight.cpp).
// Reads motions_, the start positions and velocities, the floor; writes the queue, the
// balls' flying flags, transitions_.
#include "spin_model.hpp"
#include "flight.hpp"

#include "floor_motion.hpp"

#include "../bracketed_root.hpp"

#include <algorithm>
#include <vector>
#include <cmath>
#include <limits>
#include <utility>

namespace ball_collision_sim::core::step
{

void liftOff(StepContext& c, std::size_t i, double x)
{
  const bool flew = std::exchange(c.balls_[i].support, Ball::Support::kAir) == Ball::Support::kAir;
  c.spin_->liftOff(c, i, x, flew);
}

bool leavesCurvedFloor(const StepContext& c, std::size_t i, const Vec3& position, const Vec3& v)
{
  // (where even the floor's largest bend away from its normal, take_off_margin times the
  // largest its grid found, asks less than gravity gives along the normal, the ball stays, without the
  // floor's derivatives: first with the least of gravity's part over its grid, over the
  // margin again, before the foot point is looked for, then with the normal there)
  if (!(v.squaredNorm() > c.take_off_speed2_))
    return false;
  const FloorFoot foot = c.ground_.floor()->project(position, c.guessOf(i));
  if (c.settings_.take_off_margin * c.ground_.floor()->awayCurvature() * v.squaredNorm() <= -c.gravity_.dot(foot.normal))
    return false;
  return floorPush(c, i, foot.uv, foot.normal, v) < 0;
}

double floorPush(const StepContext& c, std::size_t i, const Vec2& uv, const Vec3& n, const Vec3& v)
{
  const double g_n = -c.gravity_.dot(n);
  const Vec3 t = v - v.dot(n) * n;
  const double speed2 = t.squaredNorm();
  if (!(speed2 > 0))
    return g_n;
  // The floor's normal curvature along t, kappa_s = <n, S''> / |t|^2 with t = a S_u + b S_v
  // (negative where it bends away from its normal, as over a crest); the centre, r off it,
  // moves on a path of curvature kappa_s / (1 - r kappa_s).
  const Floor& floor = *c.ground_.floor();
  Vec3 s, su, sv, suu, suv, svv;
  floor.derivatives(uv, s, su, sv, suu, suv, svv);
  const double e = su.dot(su), f = su.dot(sv), g = sv.dot(sv);
  const double det = e * g - f * f;
  if (!(det > 0))
    return g_n;
  const double tu = su.dot(t), tv = sv.dot(t);
  const double a = (g * tu - f * tv) / det, b = (e * tv - f * tu) / det;
  const double kappa_s = n.dot(a * a * suu + 2 * a * b * suv + b * b * svv) / speed2;
  const double bend = 1 - c.balls_[i].radius * kappa_s;
  if (!(bend > 0))
    return std::numeric_limits<double>::max();  // (a hollow tighter than the ball: it rests on its rim)
  return kappa_s / bend * v.squaredNorm() + g_n;
}

void searchTakeOff(StepContext& c, std::size_t i)
{
  const Motion& m = c.motions_[i];
  const double end = c.chordEnd(i);
  if (!(end > m.x0) || c.grouped(i))
    return;
  // Where the ball's laws took it (FloorFlow), the integrated motion found where the
  // floor lets go, on the side past it.
  const StepContext::FlowEnd& flow = c.flow_ends_[i];
  if (flow.x > m.x0 && flow.ends == kTakesOff)
  {
    c.queueMotionEnd(i, flow.x, MotionEnd::kTakeOff);
    return;
  }
  // The floor's push where the motion is at x, on the floor under it, with the velocity
  // it has there: where it falls below zero within the motion, found to neighbouring
  // doubles, the ball takes off.
  const Floor& floor = *c.ground_.floor();
  const double r = c.balls_[i].radius;
  const auto push = [&](double x) {
    const FloorFoot foot = floor.project(c.positionAt(i, x), c.guessOf(i));
    return floorPush(c, i, foot.uv, foot.normal, c.onFloorVelocity(i, x, floor.ballCentre(foot, r), foot.normal));
  };
  const double at_end = push(end);
  if (!(at_end < 0))
    return;
  const double at_start = push(m.x0);
  if (!(at_start >= 0))
    return;  // (it leaves where the motion starts: startMotion() lifts it off there)
  const double x = bracketedRoot(push, [](double f) { return f >= 0 ? 1 : -1; }, m.x0, end, at_start, at_end);
  c.queueMotionEnd(i, x, MotionEnd::kTakeOff);
}

void resolveTakeOff(StepContext& c, const Event& event)
{
  const std::size_t i = event.i;
  const double x = event.x;
  // from where it is, on the floor (or on its surface just past the edge), with the
  // velocity and spin it has there
  const FloorFoot foot = c.ground_.floor()->project(c.positionAt(i, x), c.guessOf(i));
  if (!c.feet_.empty())
    c.guessOf(i) = foot.uv;
  const Vec3 p = c.ground_.floor()->ballCentre(foot, c.balls_[i].radius);
  const Vec3 v = c.onFloorVelocity(i, x, p, foot.normal);
  c.spin_->takeOff(c, i, x, foot.normal, v);
  liftOff(c, i, x);
  c.startMotion(i, x, p, v, false);
  c.countEvent(i);
  c.detect(i);
}

std::vector<Aabb> floorEdgeBoxes(const StepContext& c)
{
  // Each edge lies in the box of its control points (a Bezier curve keeps to their hull),
  // and where a wall holds them all (within round-off of its plane and inside it), the
  // edge is in the wall: a ball on the floor meets the wall before its foot passes there.
  std::vector<Aabb> boxes;
  if (!c.ground_.floor())
    return boxes;
  const FloorDef& def = c.ground_.floor()->def();
  std::vector<std::vector<Vec3>> edges;
  if (c.ground_.floor()->isPlane())
  {
    const Vec3 a = def.point, b = def.point + def.u, c = def.point + def.v, d = def.point + def.u + def.v;
    edges = {{a, b}, {c, d}, {a, c}, {b, d}};
  }
  else
  {
    const auto& q = def.control_points;
    for (int k : {0, 2})
    {
      edges.push_back({q[k][0], q[k][1], q[k][2]});
      edges.push_back({q[0][k], q[1][k], q[2][k]});
    }
  }
  constexpr double kInWall = 1e-9;  // [m] off its plane, and of its parameters past its sides
  const auto inWall = [&](const Wall& wall, const Vec3& p) {
    const Vec3 d = p - wall.def.point;
    const double s = d.dot(wall.dual_u), t = d.dot(wall.dual_v);
    return std::abs(d.dot(wall.normal)) <= kInWall && s >= -kInWall && s <= 1 + kInWall && t >= -kInWall &&
           t <= 1 + kInWall;
  };
  // (and the wall rises above the floor there: one that only hangs below the edge, as a
  // table's side, lets a ball roll off over it)
  const Vec3& up = c.ground_.up();
  const auto rises = [&](const Wall& wall, const std::vector<Vec3>& edge) {
    double top = -std::numeric_limits<double>::infinity(), highest = top;
    for (const Vec3& c : wall.corners)
      top = std::max(top, up.dot(c));
    for (const Vec3& p : edge)
      highest = std::max(highest, up.dot(p));
    return top > highest + kInWall;
  };
  for (const std::vector<Vec3>& edge : edges)
  {
    const bool walled = std::any_of(c.walls_.begin(), c.walls_.end(), [&](const Wall& wall) {
      return rises(wall, edge) &&
             std::all_of(edge.begin(), edge.end(), [&](const Vec3& p) { return inWall(wall, p); });
    });
    if (walled)
      continue;
    Aabb box{edge.front(), edge.front()};
    for (const Vec3& p : edge)
    {
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    }
    boxes.push_back(box);
  }
  return boxes;
}

double takeOffSpeedSquared(const StepContext& c)
{
  // (where even the floor's largest bend away from its normal, take_off_margin times what
  // its grid found, asks less than the least of gravity along its normal over the margin)
  const double margin = c.settings_.take_off_margin;
  if (!c.ground_.bends())
    return std::numeric_limits<double>::infinity();
  const double g_n = c.ground_.leastNormalGravity();
  if (!(g_n > 0))
    return 0.0;  // (somewhere gravity does not press a ball onto it: every motion is followed)
  if (!(c.ground_.floor()->awayCurvature() > 0))
    return std::numeric_limits<double>::infinity();  // (it bends toward its normal everywhere: a bowl)
  return g_n / (margin * margin * c.ground_.floor()->awayCurvature());
}

double edgeMarginOf(const Vec2& uv)
{
  return std::min({uv.x(), 1 - uv.x(), uv.y(), 1 - uv.y()});
}

double edgeMargin(const StepContext& c, std::size_t i, double x)
{
  const Floor& floor = *c.ground_.floor();
  const Vec3 p = c.positionAt(i, x);
  return edgeMarginOf(floor.isPlane() ? floor.planeParameters(p) : floor.project(p, c.guessOf(i)).uv);
}

void queueEdgeFall(StepContext& c, std::size_t i)
{
  const Motion& m = c.motions_[i];
  if (!c.ground_.floor() || c.balls_[i].flying() || m.frozen() || c.grouped(i))
    return;
  const double end = c.chordEnd(i);
  if (!(end > m.x0))
    return;
  const double at_end = edgeMargin(c, i, end);
  if (!(at_end < 0))
    return;
  const double at_start = edgeMargin(c, i, m.x0);
  if (!(at_start >= 0))
    return;  // (past the edge where the motion starts: an edit put it there, and it is lost)
  // the first double past the edge: where it flies from, off the floor
  const double lo = bracketedRoot([&](double x) { return edgeMargin(c, i, x); },
                                  [](double f) { return f >= 0 ? 1 : -1; }, m.x0, end, at_start, at_end);
  const double x = std::nextafter(lo, end);
  c.queueMotionEnd(i, x, MotionEnd::kTakeOff);
}
}  // namespace ball_collision_sim::core::step
