"""The figures of scripts/plot_run, and what each shows as data (`describe`): titles,
axis labels, tick values, the balls' lines and their colours, the ball ids written on it."""

import math

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.patheffects as effects  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

# Every PNG at this many pixels per inch of its figure size.
DPI = 100
# With this many balls or fewer, a legend names them; with this many or fewer, each
# ball's id is written at the end of its line.
MAX_LEGEND = 10
MAX_IDS = 60
# BallState.motion: name and colour of each state
STATES = [("sliding", "tab:red"), ("rolling", "tab:blue"), ("spinning", "tab:orange"), ("stationary", "tab:gray"),
          ("flying", "tab:green")]


def ball_colours(ids):
    """A colour for each ball, all different: tab10 up to 10 balls, tab20 (its 10 strong
    colours, then their light ones) up to 20, else evenly over turbo (256 colours)."""
    n = len(ids)
    if n <= 10:
        table = plt.get_cmap("tab10").colors[:n]
    elif n <= 20:
        tab20 = plt.get_cmap("tab20").colors
        table = (tab20[0::2] + tab20[1::2])[:n]
    else:
        turbo = plt.get_cmap("turbo")
        table = [turbo(k / (n - 1)) for k in range(n)]
    return {i: to_hex(c) for i, c in zip(ids, table)}


def label_balls(ax, ends, colours):
    """Each ball's id beside the end of its line (`ends`: id -> (x, y)), in its colour, up
    to MAX_IDS balls; a legend too up to MAX_LEGEND."""
    if len(ends) <= MAX_IDS:
        for i, (x, y) in ends.items():
            ax.annotate(str(i), (x, y), xytext=(3, 3), textcoords="offset points", fontsize=8, color=colours[i],
                        fontweight="bold", gid="id:%d" % i,
                        path_effects=[effects.withStroke(linewidth=2, foreground="white")])
    if len(ends) <= MAX_LEGEND:
        ax.legend(loc="upper right", fontsize=8)


def integer_ticks(axis):
    axis.set_major_locator(MaxNLocator(integer=True))


def save(fig, out):
    """Writes the figure to `out` as PNG and returns what it shows (`describe`)."""
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    shown = describe(fig)
    plt.close(fig)
    return shown


def describe(fig):
    """The figure as data: its size in pixels and, for each of its axes, title, labels,
    the tick values within the view, how many balls' lines it draws and their different
    colours, and the ball ids written on it (in text or the legend)."""
    axes = []
    for ax in fig.axes:
        def ticks(values, limits):
            low, high = min(limits), max(limits)
            return [float(t) for t in values if low - 1e-9 * abs(high - low) <= t <= high + 1e-9 * abs(high - low)]
        lines = [line for line in ax.get_lines() if str(line.get_gid()).startswith("ball:")]
        ids = {int(t.get_gid()[3:]) for t in ax.texts if str(t.get_gid()).startswith("id:")}
        if ax.get_legend():
            ids |= {int(t.get_text()[5:]) for t in ax.get_legend().get_texts() if t.get_text().startswith("ball ")}
        axes.append({"title": ax.get_title(), "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
                     "xticks": ticks(ax.get_xticks(), ax.get_xlim()), "yticks": ticks(ax.get_yticks(), ax.get_ylim()),
                     "shares_x": len(ax.get_shared_x_axes().get_siblings(ax)) > 1, "ball_lines": len(lines),
                     "ball_colours": sorted({to_hex(line.get_color()) for line in lines}), "ids_shown": sorted(ids)})
    width, height = fig.get_size_inches() * DPI
    return {"size": [int(round(width)), int(round(height))], "axes": axes}


def plot_energy(times, kinetic, potential, floor):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    total = [k + p for k, p in zip(kinetic, potential)]
    ax.plot(times, total, label="kinetic + potential", color="black")
    ax.plot(times, kinetic, label="kinetic", alpha=0.7)
    ax.plot(times, potential, label="potential", alpha=0.7)
    ax.set_xlabel("simulated time [s]")
    ax.set_ylabel("energy [J]")
    ax.set_title("Energy (potential above each ball's lowest resting level)" if floor else
                 "Energy (potential above height 0: the scene has no floor)")
    ax.legend()
    ax.grid(alpha=0.3)
    return fig


def plot_momentum(times, samples):
    px, py, pz = [], [], []
    for s in samples:
        px.append(sum(b.mass * b.twist.linear.x for b in s.balls))
        py.append(sum(b.mass * b.twist.linear.y for b in s.balls))
        pz.append(sum(b.mass * b.twist.linear.z for b in s.balls))
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(times, px, label="p_x")
    ax.plot(times, py, label="p_y")
    ax.plot(times, pz, label="p_z")
    ax.plot(times, [math.sqrt(a * a + b * b + c * c) for a, b, c in zip(px, py, pz)], label="|p|", color="black")
    ax.set_xlabel("simulated time [s]")
    ax.set_ylabel("total momentum [kg m/s]")
    ax.set_title("Total momentum (walls exchange momentum; without walls it is kept)")
    ax.legend()
    ax.grid(alpha=0.3)
    return fig


def plot_collisions(collisions, t0, t1):
    """The collisions counted in bins of 1 s (of a tenth of the run when shorter than 10 s)."""
    span = max(t1 - t0, 1e-9)
    width = 1.0 if span >= 10 else span / 10
    bins = max(1, int(math.ceil(span / width)))
    counts = [0] * bins
    for t in collisions:
        counts[min(bins - 1, max(0, int((t - t0) / width)))] += 1
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.bar([t0 + (k + 0.5) * width for k in range(bins)], counts, width=width * 0.9)
    ax.set_ylim(0, max(1, max(counts)) * 1.05)
    if not collisions:
        ax.text(0.5, 0.5, "no collisions in this run", transform=ax.transAxes, ha="center", va="center")
    ax.set_xlabel("simulated time [s]")
    ax.set_ylabel("collisions in %.3g s [count]" % width)
    ax.set_title("Collisions, %d in all, in bins of %.3g s" % (len(collisions), width))
    integer_ticks(ax.yaxis)
    ax.grid(alpha=0.3, axis="y")
    return fig


def paths(samples, ids, coordinates):
    """id -> (list of the first coordinate, list of the second) over the samples."""
    result = {i: ([], []) for i in ids}
    for s in samples:
        for b in s.balls:
            if b.id in result:
                a, c = coordinates(s, b)
                result[b.id][0].append(a)
                result[b.id][1].append(c)
    return result


def plot_trajectories(samples, ids, walls):
    """Top view: each ball's path in its own colour from a ring (its start) to a dot (its
    end), with its id there; the walls in grey. The figure is 9 inches wide and as high as
    the drawing's proportions need (4 to 9 inches)."""
    xy = paths(samples, ids, lambda s, b: (b.pose.position.x, b.pose.position.y))
    outlines = []
    for p, u, v in walls:
        corners = [p, [p[k] + u[k] for k in range(3)], [p[k] + u[k] + v[k] for k in range(3)],
                   [p[k] + v[k] for k in range(3)], p]
        outlines.append(([c[0] for c in corners], [c[1] for c in corners]))
    xs = [x for xs, _ in list(xy.values()) + outlines for x in xs]
    ys = [y for _, ys in list(xy.values()) + outlines for y in ys]
    aspect = (max(ys) - min(ys)) / max(max(xs) - min(xs), 1e-9) if xs else 1.0
    fig, ax = plt.subplots(figsize=(9, min(9.0, max(4.0, 1.0 + 8.0 * aspect))))
    for xs, ys in outlines:
        ax.plot(xs, ys, color="gray", linewidth=2)
    colours = ball_colours(ids)
    for i in ids:
        xs, ys = xy[i]
        ax.plot(xs, ys, linewidth=0.9, color=colours[i], gid="ball:%d" % i, label="ball %d" % i)
        ax.plot(xs[:1], ys[:1], "o", markersize=5, markerfacecolor="none", color=colours[i])
        ax.plot(xs[-1:], ys[-1:], "o", markersize=4, color=colours[i])
    label_balls(ax, {i: (xy[i][0][-1], xy[i][1][-1]) for i in ids if xy[i][0]}, colours)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("Trajectories of %d balls seen from above (ring: start; %s: end)" % (
        len(ids), "dot and id" if len(ids) <= MAX_IDS else "dot"))
    return fig


def plot_heights(samples, ids):
    """The height z of each ball's centre over time, a colour and an id for each ball."""
    tz = paths(samples, ids, lambda s, b: (s.header.stamp.to_sec(), b.pose.position.z))
    fig, ax = plt.subplots(figsize=(8, 4.5))
    colours = ball_colours(ids)
    for i in ids:
        ax.plot(tz[i][0], tz[i][1], linewidth=0.9, color=colours[i], gid="ball:%d" % i, label="ball %d" % i)
    label_balls(ax, {i: (tz[i][0][-1], tz[i][1][-1]) for i in ids if tz[i][0]}, colours)
    ax.set_xlabel("simulated time [s]")
    ax.set_ylabel("height of the centre z [m]")
    ax.set_title("Heights of %d balls over time" % len(ids))
    ax.grid(alpha=0.3)
    return fig


def plot_states(samples, transitions):
    """How many balls are in each motion state at each sample (stacked), and below, each
    transition as a dot at its exact time on its ball's row, coloured by the new state."""
    times = [s.header.stamp.to_sec() for s in samples]
    counts = [[sum(1 for b in s.balls if b.motion == k) for s in samples] for k in range(len(STATES))]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True, gridspec_kw={"height_ratios": [1, 1.4]})
    top.stackplot(times, counts, labels=[name for name, _ in STATES], colors=[c for _, c in STATES], alpha=0.8)
    top.set_ylabel("balls [count]")
    top.set_title("Motion states of %d balls over time" % max(len(s.balls) for s in samples))
    top.legend(loc="upper right")
    integer_ticks(top.yaxis)
    for k, (name, colour) in enumerate(STATES):
        hits = [m for m in transitions if m.after == k]
        bottom.plot([m.header.stamp.to_sec() for m in hits], [m.ball for m in hits], "o", markersize=3, color=colour,
                    label="to %s (%d)" % (name, len(hits)))
    bottom.set_xlabel("simulated time [s]")
    bottom.set_ylabel("ball [id]")
    bottom.set_title("Transitions at their exact times (%d in all)" % len(transitions))
    bottom.legend(loc="upper right", fontsize=8)
    integer_ticks(bottom.yaxis)
    bottom.grid(alpha=0.3)
    return fig


def plot_speeds(samples):
    """Speeds over the second half of the run against the 2D Maxwell-Boltzmann density
    f(v) = <(m v / kT) exp(-m v^2 / (2 kT))> over the balls, with kT = mean kinetic
    energy per ball (two degrees of freedom)."""
    late = samples[len(samples) // 2:]
    speeds, kinetic = [], 0.0
    for s in late:
        for b in s.balls:
            v = b.twist.linear
            speed2 = v.x * v.x + v.y * v.y + v.z * v.z
            speeds.append(math.sqrt(speed2))
            kinetic += 0.5 * b.mass * speed2
    kT = kinetic / len(speeds)
    masses = [b.mass for b in samples[-1].balls]
    top = max(speeds) * 1.05 if speeds else 1.0
    grid = [top * k / 200 for k in range(201)]
    density = [sum((m * v / kT) * math.exp(-m * v * v / (2 * kT)) for m in masses) / len(masses) if kT > 0 else 0
               for v in grid]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.hist(speeds, bins=40, range=(0, top), density=True, alpha=0.6, label="simulated (second half)")
    ax.plot(grid, density, color="black", label="2D Maxwell-Boltzmann, kT = %.3g J" % kT)
    ax.set_xlabel("speed [m/s]")
    ax.set_ylabel("probability density [s/m]")
    ax.set_title("Speeds of %d balls" % len(masses))
    ax.legend()
    return fig
