#!/usr/bin/python3
"""The node's state in and out, live settings and safe requests, through its real
interfaces (test/data/node_scene.yaml, paused): get_state, set_ball_state,
apply_impulse, load_scene, dynamic_reconfigure, empty requests, lost balls, the scene
as YAML, and what a late or paused client sees."""
import math
import os
import re
import subprocess
import sys
import time
import unittest

import rospkg
import rospy
import rostest
import tf2_ros
import yaml
from dynamic_reconfigure import DynamicReconfigureCallbackException
from dynamic_reconfigure.client import Client
from rosgraph_msgs.msg import Log
from std_msgs.msg import String
from std_srvs.srv import SetBool, Trigger

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.msg import BallState, BallStateArray, LostBall, MotionTransition  # noqa: E402
from ball_collision_sim.srv import (AddBall, ApplyImpulse, GetState, LoadScene, RemoveObject,  # noqa: E402
                                    SetBallState, Step, Strike)

PKG = "ball_collision_sim"
NS = "/ball_sim/"
DT = 0.01
# node_scene.yaml: a flat floor [-2, 2] x [-1, 1], four walls 0.3 m high; ball 1 (r 0.125,
# 1 kg) at (-0.763, 0) at 1.5 m/s, ball 2 (r 0.125, 3 kg) at (0.5, 0) at -0.5 m/s.


def get():
    return nh.call(NS + "get_state", GetState)


def step(n):
    return nh.call(NS + "step", Step, steps=n)


def fresh():
    assert nh.call(NS + "pause", SetBool, data=True).success
    assert nh.call(NS + "reset", Trigger).success


def vec(x=0.0, y=0.0, z=0.0):
    return {"x": x, "y": y, "z": z}


class NodeApi(unittest.TestCase):
    def assertUnchanged(self, before):
        after = get()
        self.assertEqual(after.balls, before.balls)
        self.assertEqual(after.walls, before.walls)
        self.assertEqual(after.time, before.time)

    def test_get_state_paused_and_running(self):
        fresh()
        s = get()
        self.assertTrue(s.success)
        self.assertTrue(s.paused)
        self.assertEqual(s.time, 0.0)
        self.assertEqual(s.frame_id, "world")
        self.assertEqual([b.id for b in s.balls], [1, 2])
        self.assertEqual([w.id for w in s.walls], [1, 2, 3, 4])
        self.assertEqual((s.balls[0].radius, s.balls[0].mass, s.balls[1].mass), (0.125, 1.0, 3.0))
        self.assertEqual(s.balls[0].pose.position.x, -0.763)
        self.assertEqual(s.balls[0].twist.linear.x, 1.5)
        # rolling: w = n x v / r = (0, 0, 1) x (1.5, 0, 0) / 0.125 = (0, 12, 0)
        self.assertAlmostEqual(s.balls[0].twist.angular.y, 12.0, places=12)
        self.assertEqual(s.walls[3].point.x, 2.0)
        self.assertEqual(s.walls[0].restitution, 1.0)
        self.assertAlmostEqual(step(7).time, 0.07, places=12)
        self.assertAlmostEqual(get().time, 0.07, places=12)
        self.assertTrue(nh.call(NS + "pause", SetBool, data=False).success)
        time.sleep(0.3)
        running = get()
        self.assertFalse(running.paused)
        self.assertGreater(running.time, 0.2)
        fresh()

    def test_a_late_client_sees_the_present_while_paused(self):
        fresh()
        step(13)
        states = nh.Inbox(NS + "ball_states", BallStateArray)
        self.assertTrue(states.wait_for(lambda all: len(all) >= 1))
        msg = states.take()[0]
        self.assertAlmostEqual(msg.header.stamp.to_sec(), 0.13, places=9)
        self.assertEqual(msg.balls, get().balls)
        states.close()
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer)  # noqa: F841
        tf = buffer.lookup_transform("world", "ball_2", rospy.Time(0), rospy.Duration(10))
        self.assertAlmostEqual(tf.header.stamp.to_sec(), 0.13, places=9)
        self.assertEqual(tf.transform.translation.x, get().balls[1].pose.position.x)

    def test_set_ball_state_keeps_the_id_and_publishes_once(self):
        fresh()
        states = nh.Inbox(NS + "ball_states", BallStateArray)
        states.wait_connected()
        states.wait_for(lambda all: len(all) >= 1)
        states.take()
        # any height: the centre lands on the floor under (x, y)
        r = nh.call(NS + "set_ball_state", SetBallState, id=2, position=vec(1.2, 0.5, 3.0), set_position=True,
                    velocity=vec(-0.4, 0.2, 1.0), set_velocity=True)
        self.assertTrue(r.success, r.message)
        self.assertEqual(r.state.id, 2)
        s = get()
        ball = s.balls[1]
        self.assertEqual((ball.id, ball.radius, ball.mass), (2, 0.125, 3.0))
        self.assertEqual((ball.pose.position.x, ball.pose.position.y, ball.pose.position.z), (1.2, 0.5, 0.125))
        self.assertEqual((ball.twist.linear.x, ball.twist.linear.y, ball.twist.linear.z), (-0.4, 0.2, 0.0))
        self.assertTrue(states.wait_for(lambda all: len(all) >= 1))
        time.sleep(0.3)
        sent = states.take()
        self.assertEqual(len(sent), 1)  # once per edit
        self.assertEqual(sent[0].balls, s.balls)
        # it runs on from there: 10 steps later
        step(10)
        moved = get().balls[1].pose.position
        self.assertAlmostEqual(moved.x, 1.2 - 0.4 * 0.1, places=12)
        self.assertAlmostEqual(moved.y, 0.5 + 0.2 * 0.1, places=12)
        states.close()

    def test_bad_set_and_push_change_nothing(self):
        fresh()
        before = get()
        cases = [
            ("set_ball_state", SetBallState, {}, "id"),  # empty
            ("set_ball_state", SetBallState, {"id": 9, "position": vec(1.2, 0.5), "set_position": True}, "id"),
            ("set_ball_state", SetBallState, {"id": 1, "position": vec(0.55, 0.05), "set_position": True},
             "position"),  # onto ball 2
            ("set_ball_state", SetBallState, {"id": 1, "position": vec(1.95, 0.0), "set_position": True},
             "position"),  # into wall 4
            ("set_ball_state", SetBallState, {"id": 1, "position": vec(2.6, 0.0), "set_position": True},
             "position"),  # off the floor
            ("set_ball_state", SetBallState, {"id": 1, "position": vec(float("nan"), 0.0), "set_position": True},
             "position"),
            ("set_ball_state", SetBallState, {"id": 1, "velocity": vec(1e9), "set_velocity": True}, "velocity"),
            # a value given without its flag is refused, never dropped; so is a request that sets nothing
            ("set_ball_state", SetBallState, {"id": 1, "position": vec(1.2, 0.5)}, "position"),
            ("set_ball_state", SetBallState, {"id": 1, "velocity": vec(0.5), "set_velocity": True,
                                              "angular_velocity": vec(0.0, 5.0)}, "angular_velocity"),
            ("set_ball_state", SetBallState, {"id": 1},
             "set_position, set_velocity, set_angular_velocity, inertia"),
            ("apply_impulse", ApplyImpulse, {"id": 1}, "impulse"),
            ("apply_impulse", ApplyImpulse, {}, "id"),
            ("apply_impulse", ApplyImpulse, {"id": 3, "impulse": vec(1.0)}, "id"),
            ("apply_impulse", ApplyImpulse, {"id": 1, "impulse": vec(float("inf"))}, "impulse"),
            ("remove_ball", RemoveObject, {}, "id"),
            ("remove_wall", RemoveObject, {}, "id"),
            ("load_scene", LoadScene, {}, "path"),
        ]
        for service, srv_type, fields, field in cases:
            r = nh.call(NS + service, srv_type, **fields)
            self.assertFalse(r.success, (service, fields))
            self.assertTrue(r.message.startswith(field + ": "), (service, fields, r.message))
            self.assertUnchanged(before)

    def test_apply_impulse_adds_impulse_over_mass(self):
        fresh()
        # ball 2 has 3 kg: J = (0.9, 0.6, 0) N s gives dv = (0.3, 0.2, 0), along the floor
        r = nh.call(NS + "apply_impulse", ApplyImpulse, id=2, impulse=vec(0.9, 0.6, 0.0))
        self.assertTrue(r.success, r.message)
        v = get().balls[1].twist.linear
        self.assertAlmostEqual(v.x, -0.5 + 0.3, places=15)
        self.assertAlmostEqual(v.y, 0.2, places=15)
        self.assertEqual(v.z, 0.0)
        self.assertEqual(r.state.twist.linear, v)
        self.assertEqual(r.state.motion, BallState.ROLLING)
        # pressed into the floor at 5 / 3 m/s, it comes back off it at the floor's
        # restitution (the scene's, 1) and flies
        r = nh.call(NS + "apply_impulse", ApplyImpulse, id=2, impulse=vec(0.0, 0.0, -5.0))
        self.assertTrue(r.success, r.message)
        self.assertAlmostEqual(r.state.twist.linear.z, 5.0 / 3.0, places=15)
        self.assertEqual(r.state.motion, BallState.FLYING)
        self.assertEqual(get().balls[1].motion, BallState.FLYING)

    def test_settings_change_live_and_are_written_back(self):
        fresh()
        # written back at start: every setting the node uses, defaults included
        self.assertEqual(rospy.get_param(NS + "tf_max_balls"), 500)
        self.assertEqual(rospy.get_param(NS + "restitution"), 1.0)
        self.assertEqual(rospy.get_param(NS + "frame_prefix"), "")
        self.assertTrue(rospy.get_param(NS + "publish_clock"))
        client = Client("/ball_sim", timeout=20)
        client.update_configuration({"marker_rate": 5.0})
        self.assertEqual(rospy.get_param(NS + "marker_rate"), 5.0)
        # real_time_factor: simulated time runs 4 times as fast as wall time, at once
        for factor in (4.0, 1.0):
            client.update_configuration({"real_time_factor": factor})
            self.assertTrue(nh.call(NS + "pause", SetBool, data=False).success)
            time.sleep(0.3)
            t0, w0 = get().time, time.time()
            time.sleep(1.5)
            t1, w1 = get().time, time.time()
            self.assertTrue(nh.call(NS + "pause", SetBool, data=True).success)
            self.assertAlmostEqual((t1 - t0) / (w1 - w0), factor, delta=0.25 * factor)
        client.update_configuration({"marker_rate": 30.0})
        fresh()

    def test_settings_out_of_range_are_refused_and_the_caller_told(self):
        """A value outside its range in cfg/Simulator.cfg, not finite, or a ball colour
        that is not speed, id or motion: the set_parameters call fails with the reason
        (dynparam exits non-zero and prints it), and nothing changes."""
        fresh()
        client = Client("/ball_sim", timeout=20)
        before = rospy.get_param(NS[:-1])
        bad = [({"ball_color": "red"}, 'ball_color: expected speed, id or motion, got "red"'),
               ({"real_time_factor": -1.0}, "real_time_factor: must be >= 0 (got -1)"),
               ({"marker_rate": float("nan")}, "marker_rate: must be finite"),
               ({"max_balls": 0}, "max_balls: must be >= 1 (got 0)"),
               ({"marker_rate": 5.0, "tf_rate": 2e6}, "tf_rate: must be <= 1e+06 (got 2e+06)")]
        for changes, reason in bad:
            with self.assertRaises(DynamicReconfigureCallbackException, msg=changes) as refused:
                client.update_configuration(changes)
            self.assertIn(reason, str(refused.exception.__context__))
            self.assertEqual(rospy.get_param(NS[:-1]), before)
            self.assertEqual(client.get_configuration(timeout=5)["marker_rate"], before["marker_rate"])
        env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
        for args, reason in [(["ball_color", "purple"], 'ball_color: expected speed, id or motion, got "purple"'),
                             (["real_time_factor", "-2"], "real_time_factor: must be >= 0 (got -2)"),
                             (["click_radius", "0"], "click_radius: must be >= 1e-06 (got 0)")]:
            run = subprocess.run(["rosrun", "dynamic_reconfigure", "dynparam", "set", "/ball_sim"] + args, env=env,
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
            out = run.stdout.decode()
            self.assertNotEqual(run.returncode, 0, out)
            self.assertIn(reason, out)
            self.assertEqual(rospy.get_param(NS[:-1]), before)
        # the same command with a good value is taken (exit 0)
        run = subprocess.run(["rosrun", "dynamic_reconfigure", "dynparam", "set", "/ball_sim", "ball_color", "id"],
                             env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
        self.assertEqual(run.returncode, 0, run.stdout.decode())
        self.assertEqual(rospy.get_param(NS + "ball_color"), "id")
        client.update_configuration({"ball_color": before["ball_color"]})

    def test_scene_is_yaml_with_the_shortest_numbers(self):
        text = rospy.wait_for_message(NS + "scene", String, timeout=10).data
        scene = yaml.safe_load(text)
        self.assertEqual(scene["balls"][0]["position"], [-0.763, 0.0, 0.125])
        self.assertEqual(scene["dt"], 0.01)
        self.assertEqual(scene["max_balls"], 3)
        self.assertIsNone(re.search(r"\d{15}", text), text)  # no 0.14999999999999999

    def test_load_scene_replaces_the_world_or_refuses_and_keeps_it(self):
        fresh()
        before = get()
        buffer = tf2_ros.Buffer()  # listening before the load: it sends the new frames once
        listener = tf2_ros.TransformListener(buffer)  # noqa: F841
        bad = [({"path": "/nonexistent/scene.yaml"}, "path: /nonexistent/scene.yaml: cannot open file"),
               ({"yaml": "balls:\n  - {position: [0, 0, 0.1], radius: -1}\n"}, "balls[0].radius: must be > 0"),
               ({"yaml": "dtt: 0.1\n"}, "dtt: unknown key"),
               ({"path": "package://no_such_package/x.yaml"}, "path: no package named"),
               ({"path": "a.yaml", "yaml": "dt: 0.1"}, "yaml: give either path or yaml")]
        for fields, message in bad:
            r = nh.call(NS + "load_scene", LoadScene, **fields)
            self.assertFalse(r.success, fields)
            self.assertIn(message, r.message)
            self.assertUnchanged(before)
        text = ("floor: {type: plane, point: [-1, -1, 0], u: [2, 0, 0], v: [0, 2, 0]}\n"
                "balls:\n  - {position: [0, 0, 0.2], velocity: [0.5, 0, 0], radius: 0.2, mass: 2}\n"
                "marker_rate: 10\nframe_prefix: sim/\n")
        r = nh.call(NS + "load_scene", LoadScene, yaml=text)
        self.assertTrue(r.success, r.message)
        s = get()
        self.assertEqual([(b.id, b.radius, b.mass) for b in s.balls], [(1, 0.2, 2.0)])
        self.assertEqual(s.walls, [])
        self.assertEqual(s.time, 0.0)
        self.assertTrue(s.paused)  # the scene does not say start_paused: the pause is kept
        self.assertEqual(rospy.get_param(NS + "marker_rate"), 10.0)  # a key it sets
        self.assertEqual(rospy.get_param(NS + "max_balls"), 3)  # a key it leaves out
        self.assertEqual(rospy.get_param(NS + "floor/u"), [2.0, 0.0, 0.0])
        self.assertEqual(s.frame_prefix, "sim/")
        buffer.lookup_transform("world", "sim/ball_1", rospy.Time(0), rospy.Duration(10))
        step(20)
        self.assertTrue(nh.call(NS + "reset", Trigger).success)  # back to the loaded scene
        self.assertEqual(get().balls, s.balls)
        r = nh.call(NS + "load_scene", LoadScene, path="package://ball_collision_sim/test/data/node_scene.yaml")
        self.assertTrue(r.success, r.message)
        self.assertEqual(get().balls, before.balls)
        self.assertEqual(get().frame_prefix, "sim/")  # a key the file leaves out keeps its value
        with open(rospkg.RosPack().get_path(PKG) + "/test/data/node_scene.yaml") as f:
            r = nh.call(NS + "load_scene", LoadScene, yaml=f.read() + "frame_prefix: ''\n")
        self.assertTrue(r.success, r.message)
        self.assertEqual(get().frame_prefix, "")
        self.assertEqual(rospy.get_param(NS + "marker_rate"), 30.0)

    def test_friction_spin_strike_and_transitions(self):
        """A scene with friction: add_ball and set_ball_state take spin and inertia,
        strike gives dv = J / m and dw = offset x J / (k m r^2), bad requests change
        nothing, and the slide-to-roll transition comes on its topic at its exact time."""
        fresh()
        text = ("floor: {type: plane, point: [-2, -1, 0], u: [6, 0, 0], v: [0, 2, 0]}\n"
                "friction: {sliding: 0.2, rolling: 0.01, spinning: 0.044}\n"
                "balls:\n  - {position: [-1.5, 0, 0.1], radius: 0.1, mass: 2}\n")
        try:
            r = nh.call(NS + "load_scene", LoadScene, yaml=text)
            self.assertTrue(r.success, r.message)
            r = nh.call(NS + "add_ball", AddBall, position=vec(0.5, 0.5), velocity=vec(1.0), radius=0.1, mass=1.0,
                        angular_velocity=vec(0.0, 0.0, 3.0), set_angular_velocity=True, inertia=2.0 / 3)
            self.assertTrue(r.success, r.message)
            added = get().balls[1]
            self.assertEqual((added.twist.angular.x, added.twist.angular.z), (0.0, 3.0))
            self.assertEqual(added.inertia, 2.0 / 3)
            self.assertEqual(added.motion, BallState.SLIDING)  # no spin about y: its foot slips
            self.assertEqual(get().balls[0].motion, BallState.STATIONARY)
            before = get()
            bad = [("strike", Strike, {}, "id"),
                   ("strike", Strike, {"id": 1, "impulse": vec(1.0), "offset": vec(0.0, 0.0, 0.15)}, "offset"),
                   ("strike", Strike, {"id": 1, "impulse": vec(float("nan"))}, "impulse"),
                   ("strike", Strike, {"id": 7, "impulse": vec(1.0)}, "id"),
                   ("add_ball", AddBall, {"position": vec(1.0), "radius": 0.1, "mass": 1.0, "inertia": 1.5},
                    "inertia"),
                   ("set_ball_state", SetBallState, {"id": 1, "position": vec(-1.0), "set_position": True,
                                                     "angular_velocity": vec(float("inf")),
                                                     "set_angular_velocity": True}, "angular_velocity")]
            for service, srv_type, fields, field in bad:
                r = nh.call(NS + service, srv_type, **fields)
                self.assertFalse(r.success, (service, fields))
                self.assertTrue(r.message.startswith(field + ": "), (service, fields, r.message))
                self.assertUnchanged(before)
            # struck 0.06 m above its centre (follow): J = 1 N s along x on 2 kg
            r = nh.call(NS + "strike", Strike, id=1, impulse=vec(1.0), offset=vec(0.0, 0.0, 0.06))
            self.assertTrue(r.success, r.message)
            v0 = 0.5
            w0 = 0.06 * 1.0 / (0.4 * 2.0 * 0.1 ** 2)  # (0, 0, 0.06) x (1, 0, 0) = (0, 0.06, 0)
            self.assertEqual(r.state.twist.linear.x, v0)
            self.assertAlmostEqual(r.state.twist.angular.y, w0, places=12)
            self.assertEqual(r.state.motion, BallState.SLIDING)
            transitions = nh.Inbox(NS + "motion_transitions", MotionTransition)
            transitions.wait_connected()
            # slip u = v0 - r w0 < 0 (more topspin than rolling): friction pushes it on until
            # |u| k / ((1 + k) mu_s g) has passed
            u = v0 - 0.1 * w0
            t1 = abs(u) * 0.4 / (1.4 * 0.2 * 9.81)
            step(int(t1 / DT) + 2)
            self.assertTrue(transitions.wait_for(lambda all: any(m.ball == 1 for m in all)))
            first = [m for m in transitions.take() if m.ball == 1][0]
            self.assertEqual((first.before, first.after), (BallState.SLIDING, BallState.ROLLING))
            self.assertAlmostEqual(first.header.stamp.to_sec(), t1, places=8)
            rolled = get().balls[0]
            self.assertEqual(rolled.motion, BallState.ROLLING)
            self.assertAlmostEqual(rolled.twist.angular.y, rolled.twist.linear.x / 0.1, places=12)
        finally:
            r = nh.call(NS + "load_scene", LoadScene, path="package://ball_collision_sim/test/data/node_scene.yaml")
            self.assertTrue(r.success, r.message)

    def test_a_ball_that_leaves_is_reported_once_and_removed(self):
        fresh()
        lost = nh.Inbox(NS + "lost_balls", LostBall)
        log = nh.Inbox("/rosout", Log)
        lost.wait_connected()
        log.wait_connected()
        self.assertTrue(nh.call(NS + "remove_wall", RemoveObject, id=4).success)  # the east wall
        r = nh.call(NS + "set_ball_state", SetBallState, id=2, position=vec(1.5, 0.5), set_position=True,
                    velocity=vec(2.0), set_velocity=True)
        self.assertTrue(r.success, r.message)
        # its foot passes x = 2 at t = 0.25 s and it falls off the floor: its centre is r below
        # the floor sqrt(4 r / g) = 0.2258 s later, found at the end of the step at 0.48 s
        step(60)
        self.assertTrue(lost.wait_for(lambda all: len(all) >= 1))
        time.sleep(0.3)
        gone = lost.take()
        self.assertEqual(len(gone), 1)
        self.assertEqual(gone[0].ball.id, 2)
        self.assertIn("fell past its edge", gone[0].reason)
        self.assertEqual(gone[0].ball.motion, BallState.FLYING)
        self.assertAlmostEqual(gone[0].header.stamp.to_sec(), 0.48, places=9)
        self.assertEqual([b.id for b in get().balls], [1])
        self.assertTrue(log.wait_for(lambda all: any(m.level == Log.WARN and "ball 2 left the floor" in m.msg
                                                     for m in all)))
        fresh()
        self.assertEqual([b.id for b in get().balls], [1, 2])


if __name__ == "__main__":
    rospy.init_node("node_api_test")
    rostest.rosrun(PKG, "node_api", NodeApi)
