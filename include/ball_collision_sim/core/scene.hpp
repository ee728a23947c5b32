#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/types.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ball_collision_sim::core
{
/// The floor the balls move on: a parametric surface S(u, v), (u, v) in [0, 1]^2.
struct FloorDef
{
  enum class Type
  {
    kPlane,        ///< S = point + u U + v V
    kBiquadratic,  ///< tensor-product Bezier surface of 3x3 control points
  };
  Type type = Type::kPlane;
  /// normal restitution of ball-floor impacts (landings), 0..1; unset: the scene's default
  std::optional<double> restitution;
  Vec3 point = Vec3(-2.0, -2.0, 0.0);  ///< plane corner [m]
  Vec3 u = Vec3(4.0, 0.0, 0.0);        ///< plane edge vector [m]
  Vec3 v = Vec3(0.0, 4.0, 0.0);        ///< plane edge vector [m]
  /// biquadratic control points [m]: control_points[i][j] weighs B_i(u) B_j(v).
  std::array<std::array<Vec3, 3>, 3> control_points = [] {
    std::array<std::array<Vec3, 3>, 3> grid;
    for (auto& row : grid)
      row.fill(Vec3::Zero());
    return grid;
  }();
};

/// A finite two-sided wall: the parallelogram point + s u + t v, s, t in [0, 1].
struct WallDef
{
  Vec3 point = Vec3::Zero();  ///< [m]
  Vec3 u = Vec3::Zero();      ///< edge vector [m]
  Vec3 v = Vec3::Zero();      ///< edge vector [m]
  /// restitution of contacts with this wall, 0..1; unset: the scene's default
  std::optional<double> restitution;
};

/// A ball's moment of inertia is k m r^2: a solid ball k = 2/5, a hollow one 2/3.
constexpr double kSolidInertia = 2.0 / 5;
constexpr double kHollowInertia = 2.0 / 3;
/// The least k a ball may have: below a sphere's any real k (all its mass at the centre
/// gives 0), and far enough from 0 that k m r^2 stays a normal number for every ball
/// (k = 2.2e-308 on a 0.17 kg ball of 5 cm makes it a denormal, 1 / I infinite, and
/// friction's first step its spin NaN).
constexpr double kMinInertia = 0.01;

/// How a ball of a scene or an edit meets the floor.
enum class BallPlacement : std::uint8_t
{
  /// put on the floor: the centre one radius above the surface point nearest it (scene
  /// files) or under it along gravity (services), the velocity along the floor
  kOnFloor,
  /// the centre exactly at `position` and the velocity whole: more than
  /// kContactTolerance above the floor it flies; touching it, it is on the floor and takes
  /// off at once where its velocity points away; below the surface it is refused
  kAsGiven,
};
/// "on_floor", "as_given"
const char* placementName(BallPlacement placement);

struct BallDef
{
  Vec3 position = Vec3::Zero();  ///< centre [m]; put on the floor when there is one
  Vec3 velocity = Vec3::Zero();  ///< [m/s]; its part normal to the floor is dropped
  double radius = 0.1;           ///< [m]
  double mass = 1.0;             ///< [kg]
  /// [rad/s]; unset: rolling without slip on the floor under it, n x v / r (the part
  /// about the floor's normal 0). Only a world with friction keeps a ball's own spin.
  std::optional<Vec3> angular_velocity;
  double inertia = kSolidInertia;  ///< k in I = k m r^2, in [kMinInertia, 1]
  BallPlacement placement = BallPlacement::kOnFloor;
};

/// Friction coefficients (Lakså and Bang 2005; pooltool's motion states). All >= 0.
struct FrictionDef
{
  double sliding = 0.0;    ///< mu_s, Coulomb ball-floor
  double rolling = 0.0;    ///< mu_r, rolling resistance
  double spinning = 0.0;   ///< mu_sp, spin about the floor's normal
  double ball_ball = 0.0;  ///< Coulomb at ball-ball impacts
  double wall = 0.0;       ///< Coulomb at ball-wall impacts
};

struct Range
{
  double min = 0.0;
  double max = 0.0;
};

/// Balls placed at random on the floor, clear of walls and of each other.
struct RandomBallsDef
{
  int count = 0;
  std::uint64_t seed = 1;
  Range radius{0.05, 0.1};  ///< uniform [m]
  Range mass{1.0, 1.0};     ///< uniform [kg]
  Range speed{0.0, 2.0};    ///< uniform [m/s]; direction uniform in the tangent plane
  double inertia = kSolidInertia;  ///< k of every ball, as BallDef::inertia
  struct Region
  {
    Vec2 min = Vec2::Zero();  ///< [m], x and y
    Vec2 max = Vec2::Zero();  ///< [m], x and y
  };
  std::optional<Region> region;
};

/// A pocket in the floor: a ball whose centre crosses its circle (in x and y) while on the
/// floor drops into it at that time and leaves the world (World::lastPocketed()). A ball in
/// flight passes over it, and drops where it lands inside the circle.
struct PocketDef
{
  Vec2 position = Vec2::Zero();  ///< the circle's centre, x and y [m]; over the floor
  double radius = 0.06;          ///< [m], > 0
};

/// Everything a simulation starts from. Defaults are the documented YAML defaults.
struct Scene
{
  std::string frame_id = "world";
  double dt = 0.01;                          ///< physics step [s]
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);      ///< [m/s^2]
  double restitution = 1.0;                  ///< default for every contact, 0..1
  std::optional<FloorDef> floor;             ///< balls move on it when present
  /// Balls have their own spin and the floor's friction acts on them; absent: balls slide
  /// without friction, their spin that of rolling (the same bits as ever).
  std::optional<FrictionDef> friction;
  std::vector<WallDef> walls;
  std::vector<BallDef> balls;
  std::optional<RandomBallsDef> random_balls;
  std::vector<PocketDef> pockets;
};

/// One problem found in a scene: the key it concerns and why.
struct SceneIssue
{
  std::string key;     ///< e.g. "balls[3].radius"
  std::string reason;  ///< e.g. "must be > 0"
  std::string str() const { return key + ": " + reason; }
};

/// The balls as a scene starts them, explicit ones first, then random ones: each put on
/// the floor, as the record a World keeps (centre, velocity, radius, mass; the World gives
/// the ids), with its foot point (u, v) there. A World takes the records over as they
/// are. Their spins come from the scene: an explicit ball's own, a random ball's from
/// random_balls.inertia.
struct PlacedBalls
{
  std::vector<Ball> balls;
  std::vector<Vec2> feet;
  std::size_t size() const { return balls.size(); }
  bool empty() const { return balls.empty(); }
};

/// What checking a scene finds: every problem, in key order; or, when there is none,
/// every ball (the explicit ones, then the random ones) put on the floor, ready for a
/// World. Each ball is placed once, here.
struct SceneCheck
{
  std::vector<SceneIssue> issues;
  PlacedBalls balls;
};

/// Checks the scene and places its balls. Pure: it reads the scene and nothing else.
SceneCheck check(const Scene& scene);

/// check(scene).issues: empty when the scene can be simulated.
std::vector<SceneIssue> validate(const Scene& scene);

/// The balls of a scene that passed check(), placed as check() places them (a World's
/// reset places them again from its scene).
PlacedBalls placeBalls(const Scene& scene);

/// Problems of one ball's own fields (finite, radius and mass > 0, sizes in range).
/// Keys are `prefix` + field name, e.g. prefix "balls[3]." gives "balls[3].radius".
std::vector<SceneIssue> validateBall(const BallDef& ball, const std::string& prefix);

/// Problems of one wall's own fields (finite, non-zero and non-parallel edges).
std::vector<SceneIssue> validateWall(const WallDef& wall, const std::string& prefix);

/// The issues joined into one line, "a: why; b: why".
std::string joinIssues(const std::vector<SceneIssue>& issues);

/// The balls of `random_balls`, placed as the scene says (deterministic in its seed).
/// Fewer than `count` come back when there is no room; validate() reports that.
std::vector<BallDef> placeRandomBalls(const Scene& scene);
/// ... as the records a World keeps, with room kept ahead of them for the scene's own
/// balls, so that check() puts all on the floor in one list, in place.
std::vector<Ball> placeRandomBallRecords(const Scene& scene);
/// The record of a ball with this definition (its id 0: the World gives it one).
Ball ballRecord(const BallDef& def);
/// The definition of a random ball with this record: its fields, no spin of its own, and
/// random_balls.inertia.
BallDef randomBallDef(const Scene& scene, const Ball& ball);

/// The scene's explicit balls followed by its random ones.
std::vector<BallDef> allBalls(const Scene& scene);
}  // namespace ball_collision_sim::core
