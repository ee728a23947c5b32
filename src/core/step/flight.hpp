// Flight and take-off as functions over the step's context (flight.cpp, take_off.cpp):
// a ball off the floor on the parabola of gravity (MotionType::kFlight), where it lands,
// and where a ball on the floor leaves it.
#pragma once

#include "step_types.hpp"

#include <optional>
#include <vector>

namespace ball_collision_sim::core::step
{
using Event = StepState::Event;
using Motion = StepState::Motion;
using SpinMotion = StepState::SpinMotion;

/// Ball i's motion from its start is a flight: the parabola of gravity (flight_c_),
/// its spin kept.
void startFlight(StepContext& c, std::size_t i);
/// Ball i's velocity at x in flight [m/s].
Vec3 flightVelocity(const StepContext& c, std::size_t i, double x);
/// Queues where ball i's flight reaches the floor within the step, if it does there
/// over the floor.
void queueLanding(StepContext& c, std::size_t i);
/// Where ball i's flight first reaches the floor after its motion's start, as a part of
/// the rest of the step (at most `rest`), or none.
std::optional<double> landingIn(const StepContext& c, std::size_t i, double rest);
/// ... over a plane: the root of a quadratic.
std::optional<double> landingOverPlane(const StepContext& c, std::size_t i, double rest);
/// ... over a curved floor: a bracket from samples of the height, refined.
std::optional<double> landingOverCurve(const StepContext& c, std::size_t i, double rest);
/// Ball i's flight meets the floor (StepEvent::end kLanding): it bounces at the floor's
/// restitution, with friction's impulse against the slip of its contact point; a
/// bounce too low to fly for StepSettings::min_flight_time puts it on the floor.
void resolveLanding(StepContext& c, const Event& event);
/// A ball on a curved floor at `position` with velocity v leaves it: the floor would
/// have to pull it to keep it on its bend (the normal force m (kappa |v|^2 + g_n) below
/// zero, kappa the curvature of the centre's path along v).
bool leavesCurvedFloor(const StepContext& c, std::size_t i, const Vec3& position, const Vec3& v);
inline bool leavesFloor(const StepContext& c, std::size_t i, const Vec3& position, const Vec3& v)
{
  return c.ground_.bends() && leavesCurvedFloor(c, i, position, v);  // (a plane holds whatever moves along it)
}
/// The normal force per unit mass the floor gives ball i with foot point uv, normal n
/// there and velocity v, kappa |v|^2 + g_n [m/s^2]: below zero it would have to pull.
double floorPush(const StepContext& c, std::size_t i, const Vec2& uv, const Vec3& n, const Vec3& v);
/// Queues the exact time at which ball i's motion on a curved floor reaches where the
/// floor's push on it falls to zero, if that is within the motion.
void queueTakeOff(StepContext& c, std::size_t i);
/// ... past the check of its speed: the floor's push followed along the motion.
void searchTakeOff(StepContext& c, std::size_t i);
/// Ball i takes off (StepEvent::end kTakeOff): it flies from where it is on the floor,
/// with its velocity there.
void resolveTakeOff(StepContext& c, const Event& event);
/// Queues where ball i's foot point passes the floor's edge within its motion, the
/// first double past it, as a take-off: past the edge no floor holds it.
void queueEdgeFall(StepContext& c, std::size_t i);
/// How far the foot point uv lies inside the floor's patch [0, 1]^2 (below zero past
/// its edge; Floor::inside() takes up to kInsideTolerance past it for round-off).
double edgeMarginOf(const Vec2& uv);
/// ... that of ball i's foot point at x.
double edgeMargin(const StepContext& c, std::size_t i, double x);
/// The boxes of the floor's edges that no wall covers (none without a floor): obstacles
/// of the grid, so that only the balls near such an edge look for passing it. (Made
/// again as walls come and go.)
std::vector<Aabb> floorEdgeBoxes(const StepContext& c);
/// The speed squared below which no ball takes off from the floor's bend: where even
/// take_off_margin times its largest curvature asks less of it than the least of
/// gravity along the floor's normal over the margin [m^2/s^2].
double takeOffSpeedSquared(const StepContext& c);
/// Ball i leaves the floor at x: in flight from there, its kind recorded.
void liftOff(StepContext& c, std::size_t i, double x);
/// Records ball i's change of kind at x where no friction phase reports it (a world
/// without friction: its take-offs and landings).
void recordFlightChange(StepContext& c, std::size_t i, double x, MotionKind from, MotionKind to);
/// The restitution of impacts on the floor: the floor's own, else the scene's.
double floorRestitution(const StepContext& c);
inline void queueTakeOff(StepContext& c, std::size_t i)
{
  const Motion& m = c.motions_[i];
  // (the fastest it can go within the motion, its start speed and all gravity can add,
  // against the least speed that can take off anywhere: (a + b)^2 <= 2 a^2 + 2 b^2)
  const double span = (c.chordEnd(i) - m.x0) * c.dt_;
  if (2 * (c.startVelocity(i).squaredNorm() + span * span * c.gravity_.squaredNorm()) <= c.take_off_speed2_)
    return;
  searchTakeOff(c, i);
}
}  // namespace ball_collision_sim::core::step
