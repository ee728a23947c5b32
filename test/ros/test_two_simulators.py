#!/usr/bin/python3
"""Item: several simulators side by side on one master, no crosstalk. The
launch/two_simulators.launch (README, docs/ros-interface.md) runs config/default.yaml in /a and config/billiards.yaml in
/b, both paused. Each answers for its own world only: its topics, services, rviz clicks
and tf frames are its own, and only /a publishes /clock."""
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import PointStamped
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.msg import BallStateArray  # noqa: E402
from ball_collision_sim.srv import AddBall, GetState, Step  # noqa: E402

PKG = "ball_collision_sim"


def state(ns):
    return nh.call("/%s/ball_sim/get_state" % ns, GetState, timeout=60)


class TwoSimulators(unittest.TestCase):
    def test_each_world_is_its_own(self):
        a, b = state("a"), state("b")
        self.assertEqual(len(a.balls), 12)  # default.yaml
        self.assertNotEqual(len(b.balls), len(a.balls))  # billiards.yaml
        self.assertEqual(a.frame_prefix, "a/")
        self.assertEqual(b.frame_prefix, "b/")
        self.assertTrue(a.paused and b.paused)

        # one /clock publisher: /a/ball_sim
        publishers = dict(rosgraph.Master("/two_simulators_test").getSystemState()[0])
        self.assertEqual(publishers.get("/clock"), ["/a/ball_sim"])

        # tf: every frame of each is under its own prefix, with its own world's balls
        tf = nh.Inbox("/tf", TFMessage)
        tf.wait_connected()
        self.assertTrue(tf.wait_for(lambda all: len({t.child_frame_id for m in all for t in m.transforms})
                                    >= len(a.balls) + len(b.balls)))
        frames = {}
        for m in tf.take():
            for t in m.transforms:
                frames[t.child_frame_id] = t.transform.translation
        want = {"a/ball_%d" % s.id: s.pose.position for s in a.balls}
        want.update({"b/ball_%d" % s.id: s.pose.position for s in b.balls})
        self.assertEqual(set(frames), set(want))
        for name, p in want.items():
            self.assertEqual((frames[name].x, frames[name].y, frames[name].z), (p.x, p.y, p.z), name)

        # stepping a moves a's time and a's clock, not b's
        clock = nh.Inbox("/clock", Clock)
        states_b = nh.Inbox("/b/ball_sim/ball_states", BallStateArray)
        clock.wait_connected()
        states_b.wait_connected()
        self.assertTrue(states_b.wait_for(lambda all: len(all) >= 1))  # b's present, at once
        states_b.take()
        self.assertTrue(nh.call("/a/ball_sim/step", Step, steps=25).success)
        self.assertAlmostEqual(state("a").time, 0.25, places=12)
        self.assertEqual(state("b").time, 0.0)
        self.assertTrue(clock.wait_for(lambda all: any(abs(c.clock.to_sec() - 0.25) < 1e-9 for c in all)))
        time.sleep(0.3)
        self.assertEqual(states_b.take(), [])  # b said nothing: nothing changed there

        # a click in /a's rviz adds a ball to a only
        click = rospy.Publisher("/a/clicked_point", PointStamped, queue_size=1)
        end = time.time() + 10
        while click.get_num_connections() == 0 and time.time() < end:
            time.sleep(0.01)
        point = PointStamped()
        point.header.frame_id = "world"
        point.point.x, point.point.y = 0.3, 0.3
        click.publish(point)
        end = time.time() + 10
        while len(state("a").balls) == 12 and time.time() < end:
            time.sleep(0.05)
        self.assertEqual(len(state("a").balls), 13)
        self.assertEqual(len(state("b").balls), len(b.balls))
        # and the services are each world's own
        added = nh.call("/b/ball_sim/add_ball", AddBall, radius=0.02, mass=0.1)
        self.assertEqual(len(state("a").balls), 13)
        self.assertEqual(len(state("b").balls), len(b.balls) + (1 if added.success else 0))


if __name__ == "__main__":
    rospy.init_node("two_simulators_test")
    rostest.rosrun(PKG, "two_simulators", TwoSimulators)
