"""What scripts/plot_run needs of a scene (its YAML, as on /ball_sim/scene or in a scene
file): gravity, the floor, the walls, checked with errors that name the key; and the
lowest level a ball's centre can rest at on the floor, above which potential energy is
measured."""

import math

# The defaults of the scene schema (README, "Scenes").
DEFAULT_GRAVITY = [0.0, 0.0, -9.81]
DEFAULT_PLANE = {"point": [-2.0, -2.0, 0.0], "u": [4.0, 0.0, 0.0], "v": [0.0, 4.0, 0.0]}
# The biquadratic floor's lowest resting level: a grid of this many points a side, then
# a pattern search from its lowest point down to steps of MIN_STEP in (u, v).
GRID = 33
MIN_STEP = 1e-12


class SceneError(Exception):
    """A key of the scene that plot_run cannot use, with the reason."""


def vector(value, key, default=None):
    """A list of 3 finite numbers at `key`, or `default` where the key is missing."""
    if value is None:
        if default is None:
            raise SceneError("%s: missing" % key)
        return [float(x) for x in default]
    if not isinstance(value, list) or len(value) != 3 or not all(
            isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in value):
        raise SceneError("%s: must be a list of 3 finite numbers (got %r)" % (key, value))
    return [float(x) for x in value]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def add(a, b, s=1.0):
    return [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]


class Scene:
    """Gravity [m/s^2], the floor (None, or ("plane", point, u, v), or ("biquadratic",
    3 x 3 control points)) and the walls' (point, u, v) [m] of a scene's YAML mapping."""

    def __init__(self, data):
        if data is None:
            data = {}
        if not isinstance(data, dict):
            raise SceneError("the scene: must be a mapping of keys (got %s)" % type(data).__name__)
        self.gravity = vector(data.get("gravity"), "gravity", DEFAULT_GRAVITY)
        self.g = math.sqrt(dot(self.gravity, self.gravity))
        self.up = [-x / self.g for x in self.gravity] if self.g > 0 else [0.0, 0.0, 1.0]
        self.friction = data.get("friction") is not None
        self.floor = self._floor(data.get("floor"))
        walls = data.get("walls") or []
        if not isinstance(walls, list):
            raise SceneError("walls: must be a list (got %r)" % (walls,))
        self.walls = []
        for k, w in enumerate(walls):
            if not isinstance(w, dict):
                raise SceneError("walls[%d]: must be a mapping (got %r)" % (k, w))
            self.walls.append(tuple(vector(w.get(key), "walls[%d].%s" % (k, key)) for key in ("point", "u", "v")))
        self._rest = {}

    def _floor(self, floor):
        if floor is None:
            return None
        if not isinstance(floor, dict):
            raise SceneError("floor: must be a mapping (got %r)" % (floor,))
        kind = floor.get("type", "plane")
        if kind == "plane":
            point, u, v = (vector(floor.get(key), "floor." + key, DEFAULT_PLANE[key]) for key in ("point", "u", "v"))
            if dot(cross(u, v), cross(u, v)) == 0:
                raise SceneError("floor.u, floor.v: must not be parallel (got %r, %r)" % (u, v))
            return ("plane", point, u, v)
        if kind == "biquadratic":
            rows = floor.get("control_points")
            if not isinstance(rows, list) or len(rows) != 3 or not all(
                    isinstance(r, list) and len(r) == 3 for r in rows):
                raise SceneError("floor.control_points: must be 3 rows of 3 points (got %r)" % (rows,))
            return ("biquadratic", [[vector(rows[i][j], "floor.control_points[%d][%d]" % (i, j)) for j in range(3)]
                                    for i in range(3)])
        raise SceneError("floor.type: must be plane or biquadratic (got %r)" % (kind,))

    def height(self, p):
        """Height [m] of a point against gravity (along z without gravity)."""
        return dot(self.up, p)

    def rest_height(self, radius):
        """The lowest height [m] the centre of a ball of this radius can have on the floor:
        at the floor's lowest point, the centre at S + r n (n the unit normal facing
        against gravity). 0 without a floor: heights are then measured from the origin."""
        if self.floor is None:
            return 0.0
        if radius not in self._rest:
            self._rest[radius] = (self._plane_rest if self.floor[0] == "plane" else self._curved_rest)(radius)
        return self._rest[radius]

    def _oriented(self, n):
        length = math.sqrt(dot(n, n))
        if length == 0:
            return None
        n = [x / length for x in n]
        return n if dot(n, self.up) >= 0 else [-x for x in n]

    def _plane_rest(self, radius):
        _, point, u, v = self.floor
        corners = [point, add(point, u), add(point, v), add(add(point, u), v)]
        return min(self.height(c) for c in corners) + radius * self.height(self._oriented(cross(u, v)))

    def _surface(self, u, v):
        """S(u, v) and its unit normal facing against gravity (None where degenerate)."""
        bu = [(1 - u) ** 2, 2 * u * (1 - u), u * u]
        bv = [(1 - v) ** 2, 2 * v * (1 - v), v * v]
        du = [-2 * (1 - u), 2 - 4 * u, 2 * u]
        dv = [-2 * (1 - v), 2 - 4 * v, 2 * v]
        s, su, sv = [0.0] * 3, [0.0] * 3, [0.0] * 3
        points = self.floor[1]
        for i in range(3):
            for j in range(3):
                s = add(s, points[i][j], bu[i] * bv[j])
                su = add(su, points[i][j], du[i] * bv[j])
                sv = add(sv, points[i][j], bu[i] * dv[j])
        return s, self._oriented(cross(su, sv))

    def _centre_height(self, radius, u, v):
        s, n = self._surface(u, v)
        return math.inf if n is None else self.height(s) + radius * self.height(n)

    def _curved_rest(self, radius):
        # The lowest point of a grid over [0, 1]^2, then a pattern search from there: steps
        # to the lowest of the eight neighbours (kept on the floor), halved when none is lower.
        best, u, v = min((self._centre_height(radius, a / (GRID - 1), b / (GRID - 1)), a / (GRID - 1), b / (GRID - 1))
                         for a in range(GRID) for b in range(GRID))
        step = 1.0 / (GRID - 1)
        while step > MIN_STEP:
            moves = [(min(1.0, max(0.0, u + du * step)), min(1.0, max(0.0, v + dv * step)))
                     for du in (-1, 0, 1) for dv in (-1, 0, 1) if du or dv]
            lowest = min((self._centre_height(radius, a, b), a, b) for a, b in moves)
            if lowest[0] < best:
                best, u, v = lowest
            else:
                step /= 2
        return best
