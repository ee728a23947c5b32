// The world's state and the step's per-ball work space, out of the public header: the
// stages of the step (src/core/step/*.cpp) and the edits read and write it.
#pragma once

#include "step_state.hpp"

#include <cassert>
#include <functional>
#include <memory>
#include <unordered_map>

namespace ball_collision_sim::core
{
/// The world's state and the step's work space (StepState), with what reads and writes
/// them: the stages of the step, one file each under src/core/step/, and the helpers
/// World's edits share. Flight and take-off are functions over it (flight.hpp). World
/// (world.hpp) is its public API; nothing here is public beyond the core.
class StepContext : public StepState
{
public:
  // World (world.hpp) steps and resets it here; its queries and edits (src/core/world.cpp,
  // queries.cpp, edits.cpp, lost_balls.cpp) read and write StepState's members themselves.
  explicit StepContext(const Scene& scene, const StepSettings& settings = StepSettings());
  StepContext(const Scene& scene, SceneCheck checked, const StepSettings& settings = StepSettings());
  StepContext(const StepContext&);
  StepContext& operator=(const StepContext&);
  StepContext(StepContext&&) noexcept;
  StepContext& operator=(StepContext&&) noexcept;
  ~StepContext();

  void step();
  void reset();

  void load(PlacedBalls placed);
  /// After an edit: the next step visits the balls in id order and predicts afresh.
  void forgetOrder();
  /// The ball of `placed`, a definition already put on the floor.
  static Ball makeBall(int id, const BallDef& placed);
  /// The spin record of `placed`, whose foot point is `foot` (worlds with friction); in
  /// flight (`flying`) its spin is its own or none.
  BallSpin makeSpin(const BallDef& placed, const Vec2& foot, bool flying) const;
  /// Why `def` cannot stand in the world (ignoring ball `ignore_id`), or ""; else `def`
  /// is put on the floor as `landing` says, `foot` gets its foot point (u, v) and
  /// `flying` whether it is in flight there (Landing::kAsGiven).
  std::string place(BallDef& def, Landing landing, int ignore_id, Vec2& foot, bool& flying) const;
  /// Takes the balls whose slots in id order `gone` names out of the records (waking what
  /// leaned on them); the next step visits the rest in id order.
  void removeBalls(const std::function<bool(std::size_t)>& gone);
  /// The box the walls span, which a ball without a floor must not leave; empty without walls.
  Ground::Bounds wallBounds() const;
  /// Why the ball in slot s is out of the world (Ground::whyOff()), or "".
  std::string whyLost(std::size_t s, const Ground::Bounds& bounds) const;
  /// The record of the ball with this id in balls_, or balls_.size().
  std::size_t slotOf(int id) const;
  /// The ball with this id's place in id order (by_id_), or by_id_.size().
  std::size_t rankOf(int id) const;
  /// The records in id order again, as an edit leaves them (the next step visits them so).
  void sortById();
  /// Moves the records (balls_, feet_, spins_) so that slot k holds the one that was in
  /// slot from[k]; `from` is left as the identity.
  void permute(std::vector<std::uint32_t>& from);
  /// Ball i's foot point guess in this step (curved floors), or a value the ground does
  /// not read.
  const Vec2& guessOf(std::size_t i) const { return floor_uv_.empty() ? no_foot_ : floor_uv_[i]; }
  Vec2& guessOf(std::size_t i) { return floor_uv_.empty() ? no_foot_ : floor_uv_[i]; }
  /// The foot point of the record in slot s (curved floors), or a value the ground does not read.
  const Vec2& footOf(std::size_t s) const { return feet_.empty() ? no_foot_ : feet_[s]; }

  /// Calls run(begin, end) over runs of balls that together are each ball once, in
  /// order: on StepSettings::threads threads at once where there are
  /// StepSettings::parallel_min_balls or more, else on this one. run() may change only its
  /// own balls' records and work space; what they record for the step (noteTransition(),
  /// stop(), flights) reaches it in the balls' order, as on one thread.
  void forEachBall(const std::function<void(std::size_t, std::size_t)>& run);
  /// As forEachBall(), over [0, n) of another loop of a world of `balls` balls (as the
  /// grid's cells); the events run() finds (pushEvent()) reach the queue in that loop's
  /// order.
  void splitLoop(std::size_t n, std::size_t balls, const std::function<void(std::size_t, std::size_t)>& run);
  /// Queues an event found, in its run's tally while a loop is split.
  void pushEvent(const Event& event);
  /// Records a change of ball i's kind of motion at x (a transition), in its run's tally
  /// while forEachBall() splits a loop.
  void noteTransition(std::size_t i, double x, MotionKind from, MotionKind to);
  /// A flight starts (flights_), in its run's tally while forEachBall() splits a loop.
  void noteFlight();
  /// A ball's energy ran out (WorldStats::stopped_balls), in its run's tally likewise.
  void noteStopped();

  // What the stages of a step (stages.hpp) share, in their order.
  /// Ball i's free motion over the next step from its record, and its swept box; at the
  /// step's start (not at the last one's commit, which saw to it) a ball that the floor
  /// cannot hold on its bend leaves it.
  void predictMotion(std::size_t i, bool at_step_start = false);
  /// Ball i to the step's end, on the floor, with its velocity there (the normal kept in
  /// floor_normals_ when `settle`): its move over the step and the normal there.
  struct Committed
  {
    Vec3 moved;
    Vec3 normal;
  };
  Committed commitBall(std::size_t i, bool settle);
  /// Velocities across the step's resting contacts: out of blocked directions, bounced
  /// where gravity closed a pair fast enough, then no closing speed left at any contact
  /// (the contact solver), along the floor.
  void settleRestingVelocities();
  /// Turns ball i by its rolling over the step's move d (its angular velocity follows
  /// from its velocity when asked for: angularVelocity()).
  void roll(std::size_t i, const Vec3& floor_normal, const Vec3& d);

  /// Where ball i's chord from p at velocity v ends `span` seconds on, under `pull`
  /// (pullOf(i) where its phase pulls it), put back on the floor.
  Vec3 predictedEnd(std::size_t i, const Vec3& p, const Vec3& v, double span, const Vec3& pull);
  Vec3 predictedEnd(std::size_t i, const Vec3& p, const Vec3& v, double span)
  {
    return predictedEnd(i, p, v, span, pullOf(i));
  }
  /// On a curved floor: ball i's chord from p at x0 with velocity v to x1, as a
  /// displacement per unit of x. Where its motion has a flow law (SpinModel::flowLaw())
  /// the chord ends where its laws take it (FloorFlow), or where its phase ends on the way
  /// (then SpinMotion::x_end), and its state there is kept (flow_ends_); else its end is
  /// predictedEnd()'s. `on_kept_foot`: p is the centre over the foot point kept
  /// (guessOf(i)), as at the step's start.
  Vec3 chordOver(std::size_t i, const Vec3& p, const Vec3& v, double x0, double x1, bool on_kept_foot);
  /// Ball i's velocity at x where its chord ends as its flow took it (at `position`, the
  /// floor's normal there), into `v`; false where its chord is not a flow's or x is not
  /// its end.
  bool flowVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal, Vec3& v) const;
  /// Ball i's chord ends at x where its laws took it (flow_ends_).
  bool flowEndsAt(std::size_t i, double x) const { return !flow_ends_.empty() && flow_ends_[i].x == x; }
  Aabb currentBox(std::size_t i) const;
  /// Ball i's walls, pairs and motion ends queued anew; the pair with `done_with` left
  /// out (just found from that ball's side, with both motions as they are).
  void detect(std::size_t i, std::size_t done_with = kNoBall);
  void detectWalls(std::size_t i);
  void detectBall(std::size_t i, std::size_t j);
  /// detectBall() for the pairs other than two free lines (MotionType::kLine) of balls
  /// outside groups.
  void detectPairApart(std::size_t a, std::size_t b);
  /// The first impact of balls a < b on straight motions from xs on, as a part of the
  /// rest of the step (sphereSweep()), or none.
  std::optional<double> linesMeet(std::size_t a, std::size_t b, double xs) const;
  /// Queues the impact of balls a < b at x.
  void pushPairEvent(std::size_t a, std::size_t b, double x);
  /// Queues ball i's drop into the first pocket its motion's centre enters within the step
  /// (pockets.cpp).
  void queuePockets(std::size_t i);
  /// Ball i drops into the pocket at the event: its state there is recorded (pocketed_),
  /// and it is out of the step (MotionType::kPocketed), its group solved again without it.
  void resolvePocket(const Event& event);
  /// A contact of a ball that dropped into a pocket: no constraint any more.
  bool linkGone(const ContactLink& link) const;
  /// The step's pocketed balls out of the world, at its end.
  void removePocketed();
  /// The event as its kind, and a motion end as its end, says.
  void resolve(const Event& event);
  void resolveBallWall(const Event& event);
  void resolveBallBall(const Event& event);
  /// A ball-ball contact as resolveBallBall() works it out: visiting indices, the normal
  /// from i to j, the floor normals under them, the normal's parts along the floor, the
  /// directions of the impulse on each, and their inverse masses (0: immovable).
  struct PairContact
  {
    std::size_t i, j;
    Vec3 n, na, nb, along_a, along_b, ta, tb;
    double inv_a, inv_b;
  };
  /// Where ball i's chord ends: 1, or on a curved floor where it was cut (cutChord()).
  double chordEnd(std::size_t i) const { return chord_ends_.empty() ? 1.0 : chord_ends_[i]; }
  /// A chord of ball i (from `position` with start velocity v0) longer than the floor
  /// allows (Ground::longestChord()) is cut where it reaches that length, and ends there
  /// on the floor; the ball goes on from there by an event (queueCut(), resolveMotionEnd()).
  /// `start_foot`: the foot point under `position` where it is known (the step's start).
  void cutChord(std::size_t i, const Vec3& position, const Vec3& v0, const Vec2* start_foot);
  void queueCut(std::size_t i);
  /// Queues the end of ball i's motion at x, for why it ends (an EventKind::kMotionEnd
  /// under the motion's epoch).
  void queueMotionEnd(std::size_t i, double x, MotionEnd end);
  /// Queues what ends ball i's motion within the step, as its kind has it: a flight's
  /// landing; a friction phase's end; on a curved floor a chord's cut and take-off.
  void queueMotionEnds(std::size_t i);
  /// Some motion may end within the step: a friction phase (balls have them), a chord on
  /// a curved floor, a flight; on a level plane without friction only flights end there.
  bool motionsEnd() const { return !spin_motions_.empty() || !chord_ends_.empty() || flights_ > 0; }
  /// Ball i's motion ends within the step (EventKind::kMotionEnd): its friction phase's,
  /// made exact by FrictionLaw::finish(), or its chord at a cut; a new one starts there.
  void resolveMotionEnd(const Event& event);
  // Resting groups (src/core/step/resting_groups.cpp).
  /// The group of ball i (its union-find root), or kNone32.
  std::uint32_t groupOf(std::size_t i);
  /// The groups' per-ball data, made for the step at its first contact.
  void startGroups();
  /// Ball i is in a group (alone, if it was in none).
  void joinGroup(std::size_t i);
  /// The groups of balls i and j become one.
  void mergeGroups(std::size_t i, std::size_t j);
  /// Whether ball i is in a resting group this step.
  bool grouped(std::size_t i) const { return !group_parent_.empty() && group_parent_[i] != kNone32; }
  /// Whether ball i has a contact with `other` (a ball's visiting index, or kWallRow | w).
  bool linked(std::size_t i, std::uint32_t other) const;
  /// A resting contact between ball a and `other` (a ball, or kWallRow | w).
  void link(std::size_t a, std::uint32_t other);
  /// Ball i, on its group's motion, takes a change of velocity dv at x, where it is at
  /// `position` (its group is to be solved again).
  void takeImpulse(std::size_t i, double x, const Vec3& position, const Vec3& dv);
  /// Ball i's velocity at x on its group's motion: its velocity where the motion starts,
  /// plus the share so far of the impulses that its solve gave it over the rest of the
  /// step (gravity's and its contacts', spread evenly); the motion's own at the step's end.
  Vec3 groupVelocityAt(std::size_t i, double x) const;
  /// The kinetic energy an impulse at x that takes ball i's velocity from `before` to
  /// `after` (its chord's, as the impact sees it) gives it [J].
  double impulseEnergy(std::size_t i, double x, const Vec3& before, const Vec3& after) const;
  /// The motions of the group of ball i from x on: each member's free motion from where it
  /// is at x, with no contact of the group closing by more than its gap (the contact
  /// solver); each member gets the new motion, and mid-step (x > 0) is detected again.
  void solveGroup(std::size_t i, double x);
  /// The stages of formRestingGroups(): the resting contacts with walls, and between
  /// balls, within `reach` [m] at the step's start, linked; how near a contact closing at
  /// its resting speed, pulled along the floor at `pull`, must be to be linked [m].
  void linkRestingWalls(double reach);
  void linkRestingPairs(double reach);
  double speculativeReach(double rest_speed, double pull) const;
  /// The contacts of the group being solved (members_), exactly, from free_u_ over the
  /// rest of the step, `rest`: contact_group_'s u and impulses.
  void solveGroupContacts(ContactGroup& group, double span, double slack);
  /// Each member of the group solved gets its motion from x over `span` (and with
  /// friction, the spin of rolling with it).
  void finishGroup(double x, double span);
  /// The stages of solveGroup(): the members of ball i's group, in id order (members_);
  /// where they are at x, their velocities there and what gravity adds per unit of the
  /// step; the part of the rest of the step the solve spans; the rows of their contacts
  /// (contact_group_); their motions over the span, solved.
  void gatherGroup(std::size_t i);
  void startMembers(double x);
  double groupSpan(double x) const;
  void makeRows(double span);
  void solveRows(double span);
  /// With friction at the contacts (the `ball_ball` and `wall` coefficients): each
  /// member's spin at x and what an impulse turns it by, and each row's friction
  /// (contact_group_'s w, inv_inertia and friction; free_w_).
  void makeFrictionRows(double x);
  /// Ball i rolls in its group, under a floor of normal n: friction holds rolling there.
  bool rollsInGroup(std::size_t i, const Vec3& n) const;
  /// What an impulse along the floor moves ball i by, in a group: 1 / m, and where it
  /// rolls (rolls) 1 / ((1 + k) m) [1/kg].
  double groupInverseMass(std::size_t i, bool rolls) const;
  /// Ball i's motion starts anew at x from `position` with velocity v0 (its record, and
  /// where the step started it).
  void beginMotion(std::size_t i, double x, const Vec3& position, const Vec3& v0);
  /// The contacts of the step's groups that touch at its end, as the contact solver takes
  /// them, and the resting contacts that sleeping reads.
  ContactGroup& endGroup();
  /// The step's contacts in the order of their keys (linkKey()), made at the commit.
  const std::vector<std::uint32_t>& linksInKeyOrder();
  /// The key of a contact of ball a with `other` by ids, whatever the records' order.
  std::uint64_t linkKey(std::size_t a, std::uint32_t other) const;
  /// No contact of the step's groups overlaps at its end: the overlapping ones opened by
  /// moves along the floor, solved together (a few passes, each ball back on the floor
  /// after each).
  void separateAtEnd();
  /// separateAtEnd()'s rows (contact_group_): the step's contacts within touch_slack, each
  /// to close by no more than its gap along the floor; the deepest overlap [m].
  double separationRows();

  /// Each group ends the step with no more energy than its members had at its start plus
  /// what impacts gave them: where the time step gives more, its velocities are scaled down.
  void boundGroupEnergies();
  /// Ball i's energy [J], kinetic with velocity v at position p (and where friction
  /// grips, its spin's, the spin it has now: spinEnergy()), and potential; motionEnergyOf()
  /// leaves the spin's out.
  double motionEnergyOf(std::size_t i, const Vec3& p, const Vec3& v) const
  {
    return balls_[i].mass * (0.5 * v.squaredNorm() - gravity_.dot(p));
  }
  double energyOf(std::size_t i, const Vec3& p, const Vec3& v) const { return motionEnergyOf(i, p, v) + spinEnergy(i); }
  /// The kinetic energy of ball i's spin that counts as its own (SpinModel::spinEnergy()) [J].
  double spinEnergy(std::size_t i) const;
  /// After an impact: its balls' groups solved again from its time on, or the balls
  /// detected again.
  void goOnAfter(const Event& event);
  /// Ball i's velocity v after an impact's impulse at x, where it is at p on the floor
  /// with this normal (`before`: its velocity before): its new motion, or its group's
  /// free velocity; what the impulse gave it counts toward the energy its group may end
  /// with.
  void takeVelocity(std::size_t i, double x, const Vec3& p, const Vec3& normal, const Vec3& before, const Vec3& v);
  /// Whether the change dv of ball i's velocity at an impact lifts it off the floor with
  /// this normal: it points away from the floor enough to keep it off it for
  /// StepSettings::min_flight_time (the floor takes a push into it, never one out of it).
  bool liftedBy(std::size_t i, const Vec3& dv, const Vec3& floor_normal) const;
  /// The ball of i and j that an impact along n lifts off the floor, or kNoBall: only one
  /// in flight striking one on the floor below its centre lifts it, so at most one of
  /// the two. The lifted ball's direction (ta or tb) becomes n and the closing speed along
  /// them is found again.
  static constexpr std::size_t kNoBall = ~std::size_t(0);
  std::size_t pairLift(std::size_t i, std::size_t j, const Vec3& n, const Vec3& na, const Vec3& nb, const Vec3& va,
                const Vec3& vb, Vec3& ta, Vec3& tb, double& closing) const;
  /// Ball i's new motion from x on, from `position` with `velocity` (`impact`: an impact
  /// gave it, not a resting contact or a chord's or phase's end).
  void startMotion(std::size_t i, double x, const Vec3& position, const Vec3& velocity, bool impact);
  void countEvent(std::size_t i);
  /// Ball i has a new motion that no event of its own made (its group's): what was
  /// predicted for it is stale, and its box follows the motion.
  void renewMotion(std::size_t i);
  /// Ball i's energy has run out where its motion starts (a turning point): it has no
  /// motion and no speed from there (until an event gives it some); with friction its
  /// spin then follows its contacts (constrainSpin()).
  void stop(std::size_t i);
  /// An impact between balls i and j closing at `closing` along their normal wakes the
  /// group of the one asleep, where it is faster than the pair's resting speed.
  void wakeOnImpact(std::size_t i, std::size_t j, double closing, double rest_speed);
  /// Wakes sleeping ball i, and the sleeping balls that touch it, and those that touch
  /// them: the group it rests in. Their motions start at the next step.
  void wakeGroup(std::size_t i);
  /// After the step's resting contacts are settled: counts the balls that lean on
  /// something while all but still, and puts to sleep each group of them held together
  /// by resting contacts whose every ball has been so for sleep_steps steps.
  void sleepStillGroups();
  /// Every ball awake (an edit of the walls: what held a group may be gone).
  void wakeAll();
  /// Wakes the sleeping balls that touch a ball of `radius` at `position` (an edit there:
  /// what they lean on may have changed; the rest of their group wakes as they move).
  void wakeTouching(const Vec3& position, double radius);
  /// Whether a wall parts two balls that touch (they then lean on it, not on each other).
  bool wallBetween(const Ball& a, const Ball& b) const;
  void recordEvent(CollisionEvent::Kind kind, int ball, int other, const Vec3& point, const Vec3& normal,
                   double impulse, double closing, bool resting, const Event& event);
  Vec3 positionAt(std::size_t i, double x) const;
  /// Ball i's motion's rate of change at x, per unit of x [m], and its parabola term (zero for a chord).
  Vec3 rateAt(std::size_t i, double x) const;
  Vec3 parabolaOf(std::size_t i) const;
  /// The parabola term of ball i's free motion: the world's path_c_, or with friction its own.
  const Vec3& pathTerm(std::size_t i) const;

  // Friction (src/core/step/friction.cpp).
  /// Ball i's friction phase from x on, from its start velocity and spin_motions_[i].w0;
  /// a change of motion kind is recorded when `record`. A phase without friction force
  /// (a frictionless SpinPhase) is left for the caller to move as a frictionless ball,
  /// and on a curved floor every moving phase to move on its chord under
  /// SpinMotion::pull: returns whether the caller is to move it. On a curved floor a ball
  /// that was rolling, and not hit (`impact`), rolls on under the normal where it is now.
  bool startFriction(std::size_t i, double x, bool record, bool impact);
  /// Ball i has no motion for the rest of the step (frozen by the cap, or asleep): its
  /// spin stays as it is.
  void keepSpin(std::size_t i);
  /// Ball i's motion from its start on is not its phase's (its group's, or stopped where
  /// its energy ran out): its spin follows FrictionLaw::constrained().
  void constrainSpin(std::size_t i);
  /// ... or its group's, which moves it as a rolling mass: its spin rolls with it.
  void rollSpin(std::size_t i);
  /// Records a transition at x where ball i's kind is not the one last reported.
  void recordKind(std::size_t i, double x);
  Vec3 spinAt(std::size_t i, double x) const;
  /// Ball i's spin at an event at x where its velocity is v on the floor with this normal:
  /// spinAt(), and on a curved floor a rolling ball's rolling with v (never more energy).
  Vec3 spinAtEvent(std::size_t i, double x, const Vec3& normal, const Vec3& v) const;
  /// Queues the end of ball i's phase when it falls within the step.
  void queueTransition(std::size_t i);
  /// An impact with friction, the balls' spins at it in SpinMotion::w0: the tangential
  /// impulse (ball_ball and wall friction) across the contact's tangent plane opposing
  /// the slip of the touching points, at most mu times the normal impulse (0 for a
  /// resting contact), never more than stops the slip (tangentialImpulse()).
  void ballBallFriction(const PairContact& c, double normal_impulse, Vec3& va, Vec3& vb);
  /// The same at a wall; n is the contact normal toward the wall.
  void ballWallFriction(std::size_t i, const Vec3& n, const Vec3& floor_normal, double normal_impulse, Vec3& v);
  /// How an impulse in a contact's tangent plane (t1, t2) changes the slip of a ball's
  /// touching point: inv times its part along the floor (normal floor_normal), plus inv
  /// / k times itself.
  Mat2 slipResponse(const Vec3& t1, const Vec3& t2, const Vec3& floor_normal, double inv, double k) const;
  /// The friction laws under the floor's normal n (the plane's, or on a curved floor the
  /// local one).
  FrictionLaw frictionUnder(const Vec3& n) const;
  /// What pulls ball i's chord on a curved floor: gravity, and with friction the phase's
  /// friction force per unit mass [m/s^2].
  const Vec3& pullOf(std::size_t i) const;
  /// |v|^2 of ball i at x where its motion's chord is at p, from the energy: on a curved
  /// floor a sliding ball's is what gravity's work along the chord leaves after its spin's
  /// change and the slip's loss, mu_s g_n (|u0| t - rate t^2 / 2); elsewhere |v0|^2 +
  /// 2 <pull, p - p0> [m^2/s^2].
  double speedSquaredAt(std::size_t i, double x, const Vec3& p) const;
  /// |v0|^2 + 2 <pull, p - p0>: ball i's speed squared at p where its pull does all the
  /// work [m^2/s^2].
  double pulledSpeedSquared(std::size_t i, const Vec3& p) const;
  /// |v|^2 where ball i's chord b ends, `rest` of the step on, with its pull's work along
  /// the chord (linear in b).
  double linearChordSpeedSquared(std::size_t i, double rest, const Vec3& b) const
  {
    return startVelocity(i).squaredNorm() + 2 * rest * pullOf(i).dot(b);
  }
  /// Turns ball i by the rotation vector `angle` [rad].
  void turn(std::size_t i, const Vec3& angle);
  /// The spin of a ball defined by `def` on the floor with normal n: its own, or rolling's.
  static Vec3 spinOf(const BallDef& def, const Vec3& n);
  /// Ball i's inverse mass in the step's responses: 0 while frozen (it does not give way).
  double inverseMass(std::size_t i) const;  // (step_types.hpp)
  /// While the step runs, a ball's position and velocity are those at the start of its
  /// motion (Motion::x0); where the step started it, step_starts_ keeps once it moved on.
  Vec3& startPosition(std::size_t i) { return balls_[i].position; }
  const Vec3& startPosition(std::size_t i) const { return balls_[i].position; }
  Vec3& startVelocity(std::size_t i) { return balls_[i].velocity; }
  const Vec3& startVelocity(std::size_t i) const { return balls_[i].velocity; }
  Vec3 floorNormalAt(std::size_t i, const Vec3& position) const;
  /// Where the ball i centred at q is put back on the floor (q itself without a floor).
  Vec3 onFloor(std::size_t i, const Vec3& q) const;
  /// The speed ball i's motion would end with, from its energy at the motion's start.
  struct EnergyCheck
  {
    const StepContext* world;
    std::size_t i;
    double rest;  ///< the part of the step the motion runs for
    /// |v|^2 at the step's end with the displacement b per unit of x, put on the floor
    double speedSquaredWith(const Vec3& b) const;
    /// ... with the motion cut to the fraction s of its chord
    double speedSquared(double s) const;
    /// ... where the chord itself ends: a motion kept out of its blocked directions can
    /// end off the floor, higher than the floor under its end
    double chordSpeedSquared(const Vec3& b) const;
  };
  Vec3 onFloorVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const;
  /// onFloorVelocity() of the motions other than a free line or path (its switch).
  Vec3 motionVelocity(std::size_t i, double x, const Vec3& position, const Vec3& normal) const;
  /// The contact solver's exact stage as settings_ ask (step_types.hpp).
  step::ExactSettings exactSettings() const;
  /// The direction a wall pushes a ball along, n the unit normal from the ball toward it:
  /// n's part along the floor with this normal, or n itself where the floor all but faces
  /// the wall (a wall parallel to the floor is met in space).
  Vec3 wallPush(const Vec3& n, const Vec3& floor_normal) const;
  /// The closing speed at or below which an impact at restitution e is a resting contact.
  /// (At a ball of this radius centred at `position`: the round-off of positions there.)
  double restingSpeed(const Vec3& floor_normal, double restitution, const Vec3& position, double radius) const;
  /// The resting speed of a contact between two balls at the scene's restitution: the
  /// larger of the two balls' (whichever floor is which).
  double pairRestingSpeed(const Vec3& na, const Vec3& pa, double ra, const Vec3& nb, const Vec3& pb, double rb) const;
  /// A ball slower than this is all but still: gravity along the floor gives it as much
  /// in resting_steps steps [m/s].
  double stillSpeed(const Vec3& floor_normal) const;

};
}  // namespace ball_collision_sim::core
