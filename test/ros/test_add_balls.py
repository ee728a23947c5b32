#!/usr/bin/python3
"""Item: add_ball puts a ball on the floor under (x, y) whatever z is given. On
config/default.yaml's nine-point floor (a dip 0.1 m deep in the middle), a rospy client
adds 50 balls at z = 0.1: every one lands where asked, its centre one radius from the
curved surface, and a refusal is only ever an overlap. Then the 62 balls run 2 s with no
overlap, on the floor, inside the walls, with their energy kept."""
import random
import sys
import unittest

import numpy as np
import rospy
import rostest
from std_srvs.srv import SetBool

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.srv import AddBall, GetState, Step  # noqa: E402

PKG = "ball_collision_sim"
NS = "/ball_sim/"
# default.yaml's control points: the border on z = 0, the middle one at z = -0.4
CONTROL = np.array([[[-2.0, -2.0, 0.0], [-2.0, 0.0, 0.0], [-2.0, 2.0, 0.0]],
                    [[0.0, -2.0, 0.0], [0.0, 0.0, -0.4], [0.0, 2.0, 0.0]],
                    [[2.0, -2.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]])


def bernstein(t):
    return np.array([(1 - t) ** 2, 2 * t * (1 - t), t * t]), np.array([2 * t - 2, 2 - 4 * t, 2 * t])


def surface(u, v):
    """S(u, v) and its partial derivatives."""
    bu, du = bernstein(u)
    bv, dv = bernstein(v)
    s = np.einsum("i,j,ijk->k", bu, bv, CONTROL)
    su = np.einsum("i,j,ijk->k", du, bv, CONTROL)
    sv = np.einsum("i,j,ijk->k", bu, dv, CONTROL)
    return s, su, sv


def distance_to_floor(p):
    """Distance from p to the floor and the unit normal there, by Gauss-Newton on (u, v)."""
    u, v = (p[0] + 2) / 4, (p[1] + 2) / 4  # x and y are linear in u and v on this floor
    for _ in range(100):
        s, su, sv = surface(u, v)
        r = s - p
        jac = np.array([[su @ su, su @ sv], [su @ sv, sv @ sv]])
        du, dv = np.linalg.solve(jac, -np.array([r @ su, r @ sv]))
        u, v = u + du, v + dv
    s, su, sv = surface(u, v)
    n = np.cross(su, sv)
    return np.linalg.norm(p - s), n / np.linalg.norm(n), s


class AddBalls(unittest.TestCase):
    def test_fifty_balls_at_z_one_tenth_land_where_asked(self):
        self.assertTrue(nh.call(NS + "pause", SetBool, data=True).success)
        rng = random.Random(5)
        added, refused = [], []
        while len(added) < 50:
            x, y, r = rng.uniform(-1.8, 1.8), rng.uniform(-1.8, 1.8), rng.uniform(0.04, 0.1)
            res = nh.call(NS + "add_ball", AddBall, position={"x": x, "y": y, "z": 0.1},
                          velocity={"x": rng.uniform(-1, 1), "y": rng.uniform(-1, 1)}, radius=r, mass=1.0)
            (added if res.success else refused).append((res, x, y, r))
            self.assertLess(len(refused), 200)
        for res, _, _, _ in refused:
            self.assertTrue(res.message.startswith("position: overlaps "), res.message)
        state = nh.call(NS + "get_state", GetState)
        balls = {b.id: b for b in state.balls}
        self.assertEqual(len(balls), 62)
        for res, x, y, r in added:
            b = balls[res.id]
            p = np.array([b.pose.position.x, b.pose.position.y, b.pose.position.z])
            self.assertAlmostEqual(p[0], x, places=9)
            self.assertAlmostEqual(p[1], y, places=9)
            d, n, foot = distance_to_floor(p)
            self.assertAlmostEqual(d, r, places=9)
            self.assertGreater(p[2], foot[2])  # above the surface, not under it
            v = np.array([b.twist.linear.x, b.twist.linear.y, b.twist.linear.z])
            self.assertAlmostEqual(v @ n, 0.0, places=9)  # moving along the floor
        energy = sum(0.5 * b.mass * (b.twist.linear.x ** 2 + b.twist.linear.y ** 2 + b.twist.linear.z ** 2)
                     + 9.81 * b.mass * b.pose.position.z for b in state.balls)
        self.assertTrue(nh.call(NS + "step", Step, steps=200).success)
        after = nh.call(NS + "get_state", GetState).balls
        self.assertEqual(len(after), 62)
        for i, a in enumerate(after):
            p = np.array([a.pose.position.x, a.pose.position.y, a.pose.position.z])
            self.assertAlmostEqual(distance_to_floor(p)[0], a.radius, places=6)
            self.assertLess(max(abs(p[0]), abs(p[1])), 2 - a.radius + 1e-9)
            for b in after[i + 1:]:
                q = np.array([b.pose.position.x, b.pose.position.y, b.pose.position.z])
                self.assertGreater(np.linalg.norm(p - q), a.radius + b.radius - 1e-9)
        energy_after = sum(0.5 * b.mass * (b.twist.linear.x ** 2 + b.twist.linear.y ** 2 + b.twist.linear.z ** 2)
                           + 9.81 * b.mass * b.pose.position.z for b in after)
        self.assertAlmostEqual(energy_after, energy, delta=1e-6 * energy)


if __name__ == "__main__":
    rospy.init_node("add_balls_test")
    rostest.rosrun(PKG, "add_balls", AddBalls)
