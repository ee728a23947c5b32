#pragma once

#include "ball_collision_sim/core/floor.hpp"
#include "ball_collision_sim/core/response.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/step_settings.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace ball_collision_sim::core
{
/// What the balls move on: nothing, a plane, or a curved ("nine point") floor. The one
/// place that knows which: the step asks it where a ball goes back onto the floor, the
/// normal under it, what of a vector lies along the floor and how hard gravity pulls along
/// it. On a curved floor a ball's foot point (u, v) is kept by the caller between calls,
/// as Newton's first guess; elsewhere the guess is not used.
class Ground
{
public:
  Ground(const std::optional<FloorDef>& floor, const Vec3& gravity, const StepSettings& settings);

  const std::optional<Floor>& floor() const { return floor_; }
  /// Unit vector against gravity (the floor's normal side).
  const Vec3& up() const { return up_; }
  /// Gravity has no part along the floor (a plane square to it, or no floor and no
  /// gravity): balls move in straight lines between impacts, at the speed they have.
  bool straight() const { return straight_; }
  /// A chord between two points of the floor leaves it (a curved floor): a motion
  /// corrected after an impact is put back on the floor, and balls keep foot points.
  bool bends() const { return floor_ && !plane_; }
  /// Balls move along "up" as freely as across it (no floor holds them): the broad phase
  /// tells them apart by height as well.
  bool spreadsAlongUp() const { return !floor_; }

  /// The plane's normal, or up where there is no floor (a curved floor's varies) [unit].
  const Vec3& flatNormal() const { return plane_ ? plane_normal_ : up_; }

  /// The longest chord a ball of this radius may take on the floor before it is cut:
  /// StepSettings::chord_turn over the floor's largest curvature, and no longer than one
  /// that strays StepSettings::chord_sag of the radius from the floor; infinite where
  /// paths do not bend [m].
  double longestChord(double radius) const
  {
    return std::min(longest_chord_, std::sqrt(sag_chord_squared_ * radius));
  }

  /// The centre of a ball of radius r put back on the floor from q (q without a floor).
  Vec3 land(const Vec3& q, double radius, const Vec2& guess) const
  {
    if (plane_)
      return q + (radius + plane_offset_ - plane_normal_.dot(q)) * plane_normal_;
    if (!floor_)
      return q;
    return floor_->ballCentre(floor_->project(q, guess), radius);
  }
  /// The same, with the foot point found written back into `guess` (curved floors).
  Vec3 landKeepingFoot(const Vec3& q, double radius, Vec2& guess) const
  {
    return bends() ? landOnCurve(q, radius, guess) : land(q, radius, guess);
  }
  /// The floor's unit normal under a ball centred at p (up without a floor).
  Vec3 normalAt(const Vec3& p, const Vec2& guess) const;
  /// The normal under a ball whose foot point is `foot` (curved floors; the plane's
  /// normal, or up, elsewhere).
  Vec3 normalUnder(const Vec2& foot) const;
  /// w less its part along the floor's normal n; w itself without a floor.
  Vec3 along(const Vec3& w, const Vec3& n) const { return floor_ ? tangentPart(w, n) : w; }
  /// A ball's motion or velocity w kept on a plane floor: less its part along the
  /// plane's normal (a ball on a plane moves in it); w itself elsewhere, where a chord
  /// is put back on the floor at its end.
  Vec3 inPlane(const Vec3& w) const { return plane_ ? Vec3(w - w.dot(plane_normal_) * plane_normal_) : w; }
  /// |gravity along the floor| where its normal is n [m/s^2].
  double gravityAlong(const Vec3& n) const;

  /// The acceleration of a free ball's path between events where that path is a parabola
  /// that the step follows exactly: gravity along a sloped plane, or gravity itself
  /// without a floor. Zero where balls move in straight lines (straight()) and on a curved
  /// floor, where a ball's motion in a step is the chord across its path [m/s^2].
  Vec3 pathAcceleration() const;

  /// A ball's velocity at p, on the floor with normal n there, `elapsed` seconds into a
  /// motion that started at p0 with velocity v0: gravity's along the floor added, and
  /// where gravity pulls along the floor, the speed its energy gives at p.
  Vec3 velocityAt(const Vec3& v0, double elapsed, const Vec3& p0, const Vec3& p, const Vec3& n) const
  {
    return velocityAt(v0, elapsed, p0, p, n, gravity_);
  }
  /// The same under `pull` [m/s^2] in gravity's place: gravity and a friction force (whose
  /// work <f, p - p0> per unit mass comes off the energy too).
  Vec3 velocityAt(const Vec3& v0, double elapsed, const Vec3& p0, const Vec3& p, const Vec3& n,
                  const Vec3& pull) const
  {
    const Vec3 v = along(v0 + elapsed * pull, n);
    if (straight_)
      return v;  // no force along the floor: the motion is the chord itself
    // Under a force along the floor the ball's path is a curve and its motion in the step
    // the chord across it, which runs off the curve; so where an impact stops the chord,
    // the velocity the force gave by then does not go with the height the chord reached.
    // Keep the frictionless ball's |v|^2 = |v0|^2 + 2 <g, p - p0> (the course code's
    // correction on its curved floor).
    return withSpeedSquared(v, v0.squaredNorm() + 2 * pull.dot(p - p0));
  }
  /// v scaled to the speed sqrt(target); zero where target <= 0.
  Vec3 withSpeedSquared(const Vec3& v, double target) const;
  /// A velocity `before` turned to the direction of `after` by something frictionless
  /// (a resting contact, the floor): where gravity pulls along the floor a ball's speed
  /// is its energy's, and the turn keeps it; elsewhere `after` as it is.
  Vec3 turned(const Vec3& before, const Vec3& after) const;

  /// Where a ball's motion ends the step: its centre (on a plane put on it; on a curved
  /// floor its chord already ends there), the normal there, and the foot point.
  struct End
  {
    Vec3 centre;
    Vec3 normal;
    Vec2 foot;
  };
  End end(const Vec3& p, double radius, const Vec2& guess) const
  {
    if (plane_)
      return {land(p, radius, guess), plane_normal_, guess};
    if (!floor_)
      return {p, up_, guess};
    // The chord ends on the floor except where a ball was stopped by the event cap, was
    // held, or its constraints did not settle: then it stays at its chord's end, clear of
    // everything, a little off the floor until the next step puts it back.
    return airEnd(p, guess);
  }
  /// The same for a ball in flight: where it is, the normal and foot point under it.
  End airEnd(const Vec3& p, const Vec2& guess) const;
  /// How far a ball of this radius centred at p is above the floor [m] (below: < 0),
  /// `guess` its foot point's first guess, and then its foot point (curved floors).
  double heightAbove(const Vec3& p, double radius, Vec2& guess) const;
  /// The same for a ball that has not moved since its foot point was found (asleep):
  /// where it is, with that foot point, and no search for it; on a curved floor the
  /// normal only `with_normal` (else zero: a ball that does not move turns by nothing).
  /// The same as end() where `foot` is what end() found there (its search then stops at
  /// once), that is where it converged.
  End stillEnd(const Vec3& p, double radius, const Vec2& foot, bool with_normal) const;

  /// A box [m]; `any` false: none.
  struct Bounds
  {
    bool any = false;
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  };
  /// Why a ball of radius r centred at `centre` has left what it moves on, or "" where it
  /// has not: with a floor, its foot point (from its centre on a plane, the kept one on a
  /// curved floor) is off the floor; without one, it is beyond `walls`, the box the walls
  /// span (nothing, where there are none).
  std::string whyOff(const Vec3& centre, double radius, const Vec2& kept, const Bounds& walls) const;
  /// The same for a ball in flight: with a floor, its centre is more than its radius below
  /// the floor's lowest point (it fell past the edge, and nothing brings it back); without
  /// one, as whyOff().
  std::string whyFallen(const Vec3& centre, double radius, const Bounds& walls) const;
  /// Whether a ball can leave at all: there is a floor, or walls to bound it.
  bool bounded(const Bounds& walls) const { return floor_.has_value() || walls.any; }

private:
  /// landKeepingFoot() on a curved floor.
  Vec3 landOnCurve(const Vec3& q, double radius, Vec2& guess) const;

  std::optional<Floor> floor_;
  Vec3 up_ = Vec3::UnitZ();
  bool plane_ = false;
  Vec3 plane_normal_ = Vec3::UnitZ();
  double plane_offset_ = 0.0;
  double plane_gravity_along_ = 0.0;  ///< |gravity along the plane| [m/s^2]
  Vec3 gravity_;
  bool straight_ = true;
  double longest_chord_ = std::numeric_limits<double>::infinity();
  double sag_chord_squared_ = std::numeric_limits<double>::infinity();  ///< 8 chord_sag / k [m]
  /// The floor's lowest point's height along up_ [m] (a curved floor's lowest of a 65 x 65
  /// grid of its points, corners and edges included).
  double lowest_ = 0.0;
  /// The least of gravity's part into the floor, -g.n, over the same grid [m/s^2].
  double least_normal_gravity_ = 0.0;

public:
  /// The floor's lowest point's height along up() [m].
  double lowest() const { return lowest_; }
  /// The least of gravity's part into the floor, -g.n, over its grid of points [m/s^2].
  double leastNormalGravity() const { return least_normal_gravity_; }
};
}  // namespace ball_collision_sim::core
