#include "ball_collision_sim/core/ground.hpp"

#include "ball_collision_sim/core/format.hpp"

#include "ball_collision_sim/core/response.hpp"

#include <cmath>

namespace ball_collision_sim::core
{
Ground::Ground(const std::optional<FloorDef>& floor, const Vec3& gravity, const StepSettings& settings)
    : gravity_(gravity)
{
  if (floor)
    floor_.emplace(*floor, gravity);
  const double g = gravity.norm();
  up_ = floor_ ? floor_->up() : g > 0 ? Vec3(-gravity / g) : Vec3(Vec3::UnitZ());
  plane_ = floor_ && floor_->isPlane();
  if (plane_)
  {
    plane_normal_ = floor_->planeNormal();
    plane_offset_ = floor_->planeOffset();
  }
  const Vec3 along = plane_ ? tangentPart(gravity, plane_normal_) : gravity;
  plane_gravity_along_ = plane_ ? along.norm() : 0.0;
  straight_ = !bends() && along.norm() <= settings.straight_gravity_ratio * g;
  if (bends() && floor_->maxCurvature() > 0)
  {
    longest_chord_ = settings.chord_turn / floor_->maxCurvature();
    sag_chord_squared_ = 8 * settings.chord_sag / floor_->maxCurvature();
  }
  if (floor_)
  {
    // (a plane's lowest point is a corner, which the grid holds)
    const int cells = plane_ ? 1 : settings.floor_grid_cells;
    lowest_ = least_normal_gravity_ = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= cells; ++a)
      for (int b = 0; b <= cells; ++b)
      {
        const Vec2 uv(double(a) / cells, double(b) / cells);
        lowest_ = std::min(lowest_, up_.dot(floor_->point(uv)));
        least_normal_gravity_ = std::min(least_normal_gravity_, -gravity.dot(floor_->normal(uv)));
      }
  }
}

Vec3 Ground::normalAt(const Vec3& p, const Vec2& guess) const
{
  if (plane_)
    return plane_normal_;
  if (!floor_)
    return up_;
  return floor_->project(p, guess).normal;
}

Vec3 Ground::normalUnder(const Vec2& foot) const
{
  if (plane_)
    return plane_normal_;
  if (!floor_)
    return up_;
  return floor_->normal(foot);
}

double Ground::gravityAlong(const Vec3& n) const
{
  return plane_ ? plane_gravity_along_ : along(gravity_, n).norm();
}

Vec3 Ground::pathAcceleration() const
{
  if (straight_ || bends())
    return Vec3::Zero();
  return plane_ ? tangentPart(gravity_, plane_normal_) : gravity_;
}

Vec3 Ground::withSpeedSquared(const Vec3& v, double target) const
{
  const double norm = v.norm();
  if (target <= 0 || norm == 0)
    return Vec3::Zero();
  return v * (std::sqrt(target) / norm);
}

Vec3 Ground::turned(const Vec3& before, const Vec3& after) const
{
  const double speed = after.norm();
  if (straight_ || !(speed > 0))
    return after;
  return after * (before.norm() / speed);
}

Vec3 Ground::landOnCurve(const Vec3& q, double radius, Vec2& guess) const
{
  const FloorFoot foot = floor_->project(q, guess);
  guess = foot.uv;
  return floor_->ballCentre(foot, radius);
}

Ground::End Ground::airEnd(const Vec3& p, const Vec2& guess) const
{
  if (plane_ || !floor_)
    return {p, flatNormal(), guess};
  const FloorFoot foot = floor_->project(p, guess);
  return {p, foot.normal, foot.uv};
}

double Ground::heightAbove(const Vec3& p, double radius, Vec2& guess) const
{
  if (!floor_)
    return std::numeric_limits<double>::infinity();
  if (plane_)
    return plane_normal_.dot(p) - floor_->planeOffset() - radius;
  const FloorFoot foot = floor_->project(p, guess);
  guess = foot.uv;
  return foot.normal.dot(p - foot.point) - radius;
}

std::string Ground::whyFallen(const Vec3& centre, double radius, const Bounds& walls) const
{
  if (!floor_)
    return whyOff(centre, radius, Vec2(0.5, 0.5), walls);
  const double below = lowest_ - radius - up_.dot(centre);
  if (!(below > 0))
    return "";
  return "left the floor (fell past its edge: its centre is " + formatNumber(below + radius) +
         " m below the floor's lowest point)";
}

Ground::End Ground::stillEnd(const Vec3& p, double radius, const Vec2& foot, bool with_normal) const
{
  if (plane_ || !floor_)
    return end(p, radius, foot);
  return {p, with_normal ? floor_->normal(foot) : Vec3::Zero(), foot};
}

std::string Ground::whyOff(const Vec3& centre, double radius, const Vec2& kept, const Bounds& walls) const
{
  if (floor_)
  {
    const Vec2 uv = plane_ ? floor_->planeParameters(centre) : kept;
    if (Floor::inside(uv))
      return "";
    return "left the floor (its foot point at u = " + formatNumber(uv.x()) + ", v = " + formatNumber(uv.y()) +
           " is outside [0, 1]^2)";
  }
  if (walls.any && ((centre.array() < walls.lo.array() - radius).any() || (centre.array() > walls.hi.array() + radius).any()))
    return "left the walls' bounds";
  return "";
}
}  // namespace ball_collision_sim::core
