#pragma once

#include <cstddef>
#include <cstdint>

namespace ball_collision_sim::core
{
/// The most threads a step takes (StepSettings::threads): more than any machine here has
/// cores [threads].
constexpr unsigned kMaxThreads = 1024;

/// Every threshold and tunable of the step, with its unit and the reason for its value.
/// The defaults are what the tests and benchmarks are measured with; a World takes them
/// at construction.
struct StepSettings
{
  // ---- resting contacts ---------------------------------------------------------------
  /// An impact whose bounces to follow (each e times the last, gravity along the floor
  /// bringing the ball back) would all be over within this many steps is a resting
  /// contact: their sum, the motion stopped along the normal, is taken at once, so that
  /// a ball leaning on a wall neither jitters nor makes endless events. At e = 1 they
  /// never end: no resting contact [steps].
  double resting_steps = 4.0;
  /// ... and a closing speed below this always: round-off of speeds, where an impact
  /// would be found again at once [m/s]. (Plus sqrt(2 a d): what a ball pulled along the
  /// floor at a reaches falling through a gap d of roundoff_epsilons of the positions.)
  double resting_speed_floor = 1e-9;
  /// A ball with more events than this in one step is stopped for the rest of the step
  /// and acts as immovable: a guard against endless chatter in jammed piles; at most 4094
  /// (a ball's count is kept in 12 bits) [events].
  std::uint32_t max_events_per_ball_step = 256;
  /// Sweeps of the contact solver over a group's contacts (projected Gauss-Seidel) before
  /// it stops with closing left (counted: WorldStats::unsettled_contacts); each sweep
  /// takes a jam's closing down by a steady factor, and piles of hundreds settle in tens
  /// [sweeps].
  int contact_sweeps = 100;
  /// ... and a solve is done once no sweep changes a closing speed, nor leaves one, by
  /// more than this part of the largest it started with (or resting_speed_floor): the
  /// usual relative tolerance of an iterative solver [ratio].
  double contact_tolerance = 1e-6;
  /// Passes over a step's resting contacts at its end that open those its groups' solves
  /// left overlapping (their residual: each pass solves them together, then puts the
  /// balls back on the floor, which the next pass corrects) [passes] ...
  int position_sweeps = 8;
  /// ... where a contact's normal has less than this of it (squared) along the floor, the
  /// move that opens it is along the normal itself (along the floor it would be long) [1].
  double separation_min_share = 0.01;
  /// Resting groups look for contacts to link no farther than a step at the resting speed
  /// of the most dissipative restitution in the scene, plus this, for the round-off of
  /// speeds [m/s] ...
  double reach_speed_margin = 1e-3;
  /// ... taking a restitution below this as this (at e = 0 every closing rests, and the
  /// reach would have no bound) [1].
  double reach_least_restitution = 1e-3;
  /// A group's solve starts from each contact's last impulse (the last step's, or what is
  /// left of this step's last solve): a pile at rest then needs next to no sweeps. Off,
  /// from none (for comparison) [on/off].
  bool warm_start = true;
  /// Sweeps of projected Gauss-Seidel over a group's contacts before the exact stage: a
  /// guess of which contacts push, which the exact stage corrects [sweeps].
  int group_sweeps = 20;
  /// ... and where the exact stage finds no answer from that guess, this many more before
  /// it tries once again [sweeps].
  int group_retry_sweeps = 160;
  /// Solves of a group on a curved floor, each with its contacts' linearization corrected
  /// where the last one's ends landed on the floor (Newton's method on their distances);
  /// what the last leaves is opened at the step's end (position_sweeps) [solves].
  int group_passes = 4;
  /// Direct solves the contact solver's exact stage may take, changing which contacts push
  /// between them (step::solveContactsExactly()); a group of hundreds needs a few, a jam
  /// whose contacts say the same about one per pushing contact (taken one at a time):
  /// hundreds for a hundred balls packed tight, and more than this past about 140
  /// (then the sweeps' answer stays, counted in WorldStats::unsettled_contacts) [solves].
  int exact_solves = 1024;
  /// The exact stage factorizes its matrix with the diagonal this much larger: contacts
  /// that say the same (a jam's, a ball on three others and a wall) leave it singular,
  /// and this makes them share their push equally [ratio] ...
  double exact_regularization = 1e-10;
  /// ... and refines the solution this many times against the matrix itself, each taking
  /// its error down by about that factor, to round-off [refinements].
  int exact_refinements = 2;
  /// Rounds in which every wrong contact changes side together (block principal pivoting)
  /// may go without making fewer wrong, before the interior-point method and then the
  /// primal active-set method, which end, take over [rounds].
  int exact_pivot_tries = 3;
  /// Iterations of the interior-point method, which finds which contacts push in a jam
  /// whose contacts say the same (each one sparse factorization on one pattern; a square
  /// jam of 204 balls takes about 30) before the active-set method finishes from there,
  /// in a solve or a few [iterations].
  int exact_interior_iterations = 100;
  /// With friction at resting contacts (the `ball_ball` and `wall` coefficients), where the
  /// sweeps over a group's contacts and their friction do not converge: solves of its
  /// contacts exactly with friction held, each followed by friction again under the
  /// contacts' impulses found, until friction stops changing (staggered projections;
  /// step::solveFrictionally()) [solves].
  int friction_passes = 8;
  /// Sweeps of the contact solver over a group with rolling resistance, each followed by
  /// the members' resistance, before its contacts are solved exactly with the resistance
  /// found (what is left is a resistance a little off its cap) [sweeps].
  int resistance_sweeps = 100;
  /// Positions are known to this many machine epsilons of their magnitude: gaps and
  /// corrections below it are round-off [epsilons].
  double roundoff_epsilons = 16;
  /// A wall whose normal's part along the floor is shorter than this (squared) is
  /// parallel to the floor: a ball meets it in space, not along the floor [1].
  double wall_along_floor_squared = 1e-12;

  /// Two touching objects are closing only when the motion left in the step would take
  /// them deeper than this part of the contact distance; less is round-off (of a resting
  /// contact's removed approach), not an impact [ratio].
  double closing_slop = 1e-12;

  // ---- sleeping ----------------------------------------------------------------------
  /// A ball slower than this while it leans on something is all but still: a millimetre
  /// a second, well below what a viewer sees move, and what piles settle to in seconds
  /// [m/s].
  double sleep_speed = 1e-3;
  /// A group of balls held together by resting contacts sleeps once every one of them
  /// has been all but still this long [s] (at least one step).
  double sleep_time = 0.5;
  /// Balls this close count as touching when an impact wakes a sleeping group [m].
  double touch_slack = 1e-6;

  // ---- keeping a motion within its energy (curved floors) -----------------------------
  /// Root finding on the chord for where the speed runs out: at most this many steps,
  /// and until the bracket is this narrow [steps], [fraction of the step].
  int energy_root_iterations = 50;
  double energy_root_width = 1e-15;
  /// Sliding downhill from an impact point above the floor: the shortest reach tried,
  /// as a part of the radius, the longest as a part of it, and how many doublings lie
  /// between [ratio], [ratio], [doublings].
  double slide_first_reach = 1e-12;
  double slide_longest_reach = 0.5;
  int slide_doublings = 64;

  // ---- fast balls on curved floors ---------------------------------------------------
  /// A chord on a curved floor turns through at most this angle of the floor (its length
  /// times the floor's largest curvature): a chord of length L strays up to L^2 k / 8 from
  /// the surface, and a fast ball's, across much of the floor in one step, may leave it.
  /// A longer one is cut where it reaches this length, and the ball goes on from the cut,
  /// on the floor, with the speed its energy gives there (an event) [rad].
  double chord_turn = 0.25;
  /// ... and strays at most about this part of the ball's radius from the surface (L^2 k /
  /// 8, for the floor's curvature k; the centre's surface, r further out, curves by up to
  /// R / (R - r) more in a hollow of radius R): a ball stopped part way along its chord
  /// (where its energy runs out) ends the step there, off the floor by the sag, and a small ball's long chord
  /// would leave it floating several radii above it. A small fast ball's step is then cut
  /// into v dt / sqrt(8 chord_sag r / k) chords, each an event that counts toward
  /// max_events_per_ball_step [ratio].
  double chord_sag = 0.01;
  /// A chord's end on a curved floor is where the ball's laws take it, integrated
  /// (FloorFlow, fourth order) in substeps that each turn its path, or gravity's swing
  /// sqrt(g k), by at most this; a free ball after 1 s at dt = 0.01 s is then within about
  /// 1e-9 m of the exact motion on the test floors (test_floor_flow) [rad].
  double flow_turn = 0.05;
  /// ... and in steps that each turn a sliding ball's slip (or a rolling one's velocity
  /// under rolling resistance) by at most this where friction's drag on it is g, where
  /// friction's direction turns with it, fastest near the slip's end; by this times
  /// (g / drag)^(1/3) under another drag (the step's error goes as the drag times the turn
  /// cubed: a rolling ball's resistance of 0.01 g turns 4.6 times as far), and without
  /// one, freely. The slip's end is then found within about 1e-9 s (2e-6 s at 0.05, 1e-9
  /// s at 0.005 for the slip's drag of 0.2 g (1 + 1/k) on the test floors) [rad].
  double slip_turn = 0.0035;
  /// ... in at most this many steps a chord: a ball all but at rest in a pile, whose tiny
  /// velocity or slip the pull and its contacts turn about, would take ever shorter ones;
  /// past the cap its flow goes on in the substeps flow_turn gives. A single ball's slip
  /// ends on the test floors within 1e-9 s under it (test_floor_flow); piles with
  /// friction that settle in a bowl take 1.5 to 3.7 times as long as with the first-order
  /// chords (test_long_runs) [steps].
  int flow_step_cap = 512;

  // ---- friction ----------------------------------------------------------------------
  /// A slip of the contact point smaller than this part of the ball's speeds (|v| plus
  /// r times its spin along the floor) is round-off, of a transition or of the input: the
  /// ball rolls, and the sticking impulse that takes the slip away costs at most this
  /// part squared of its energy [ratio].
  double slip_tolerance = 1e-12;

  // ---- the floor's kind ---------------------------------------------------------------
  /// Gravity along a plane floor shorter than this part of gravity is none: balls move
  /// in straight lines between impacts there [ratio].
  double straight_gravity_ratio = 1e-12;

  // ---- broad phase --------------------------------------------------------------------
  /// A swept box wider than this many times the mean is left out of the cell's width
  /// and listed apart: one fast or large ball must not make every cell huge [ratio].
  double grid_outlier_ratio = 4.0;
  /// A cell is wider than the widest box it is sized by, by this part of it (round-off of
  /// the boxes' bounds) [ratio], and by this, so that it is not zero where every box is a
  /// point [m].
  double grid_cell_margin = 1e-9;
  double grid_cell_floor = 1e-12;
  /// The grid's cells are one dense array while there are at most this many per item
  /// plus grid_dense_extra_cells (then the scan reads the items in cell order), else
  /// hashed buckets: balls spread thin over a large floor must not cost a table of empty
  /// cells [cells per item], [cells].
  double grid_dense_cells_per_item = 4.0;
  double grid_dense_extra_cells = 1024.0;

  // ---- flight -------------------------------------------------------------------------
  /// A ball that leaves the floor slower along its normal than would keep it in flight
  /// this long stays on the floor: a bounce at e < 1 is followed by endless ones, e
  /// times as long each, whose flights sum to the series' limit; cut where the next would
  /// be shorter than this, the ball lands for good at most min_flight_time / (1 - e)
  /// early, its hops by then g min_flight_time^2 / 8 high (1e-11 m) [s]. The same holds
  /// for the round-off of a velocity along the floor's normal after an impact or an
  /// edit.
  double min_flight_time = 1e-6;
  /// A flight over a curved floor is looked at in this many samples of its height over
  /// the rest of the step; the first more than round-off below the floor closes the
  /// landing's bracket, refined to neighbouring doubles. A graze on a bump narrower than
  /// the step's flight over this many is not seen (16: 2.5 cm at 4 m/s and dt = 0.01 s,
  /// where the nine-point floor's bumps span the patch) [samples].
  int landing_samples = 16;
  /// Take-off is looked for only where this many times the floor's largest bend away from
  /// its normal sampled on a grid (Floor::awayCurvature(); none on a bowl), times |v|^2, reaches what gravity gives along the floor's normal
  /// (its least over the ground's grid, floor_grid_cells, over this again): the
  /// curvature and the normal between the grids' points differ from theirs, and 2 takes
  /// a biquadratic's changes between neighbouring points with room [ratio].
  double take_off_margin = 2.0;

  // ---- the ground ---------------------------------------------------------------------
  /// The curved floor's lowest point and least normal gravity are taken on a grid of
  /// this many cells a side (a ball in flight below the lowest less its radius has fallen
  /// past the edge and is lost; take_off_margin covers what lies between points) [cells].
  int floor_grid_cells = 64;

  // ---- memory order -------------------------------------------------------------------
  /// The balls' records are put in the grid's cell order (the step's visiting order)
  /// anew every this many steps: balls move less than a cell in a step [steps].
  std::uint32_t reorder_steps = 8;

  // ---- threads ------------------------------------------------------------------------
  /// The threads the step's per-ball stages (predict, commit) run on: 1, the caller's
  /// alone; 0, as many as the machine has cores. Every count gives the same bits: each
  /// thread takes a contiguous run of balls, and what they record for the step is put
  /// together in the balls' order [threads].
  unsigned threads = 1;  ///< at most kMaxThreads
  /// ... where the world has at least this many balls: handing a loop to the other
  /// threads and waiting for them costs some microseconds, what the commit of a few
  /// hundred balls costs [balls].
  std::size_t parallel_min_balls = 2048;
  /// Between a step's loops, and while the caller waits for them, a thread looks for
  /// work this long before it sleeps: woken from sleep, a thread of a virtual machine can
  /// take longer to run again than a loop of 10^4 balls takes [us].
  std::uint32_t thread_spin_us = 2000;
};
}  // namespace ball_collision_sim::core
