#!/usr/bin/python3
"""A ball that drops into a pocket (test/data/pocket_scene.yaml): reported once on
~pocketed, stamped with the exact time its centre crossed the circle, with its state
there and the pocket's index; it is then out of get_state, and a reset brings it back."""
import sys
import time
import unittest

import rospy
import rostest
from std_srvs.srv import SetBool, Trigger

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.msg import PocketedBall  # noqa: E402
from ball_collision_sim.srv import GetState, Step  # noqa: E402

PKG = "ball_collision_sim"
NS = "/ball_sim/"


class Pocketed(unittest.TestCase):
    def test_a_ball_that_drops_into_a_pocket_is_reported_once_at_its_time(self):
        pocketed = nh.Inbox(NS + "pocketed", PocketedBall)
        pocketed.wait_connected()
        self.assertTrue(nh.call(NS + "pause", SetBool, data=True).success)
        self.assertTrue(nh.call(NS + "reset", Trigger).success)
        self.assertTrue(nh.call(NS + "step", Step, steps=80).success)
        self.assertTrue(pocketed.wait_for(lambda all: len(all) >= 1))
        time.sleep(0.3)
        dropped = pocketed.take()
        self.assertEqual(len(dropped), 1)
        self.assertEqual(dropped[0].ball.id, 1)
        self.assertEqual(dropped[0].pocket, 1)
        self.assertAlmostEqual(dropped[0].header.stamp.to_sec(), 0.55, places=9)
        self.assertAlmostEqual(dropped[0].ball.pose.position.x, 0.3, places=12)
        self.assertEqual(dropped[0].ball.twist.linear.x, 2.0)
        self.assertEqual([b.id for b in nh.call(NS + "get_state", GetState).balls], [2])
        self.assertTrue(nh.call(NS + "reset", Trigger).success)
        self.assertEqual([b.id for b in nh.call(NS + "get_state", GetState).balls], [1, 2])


if __name__ == "__main__":
    rospy.init_node("pocketed_test")
    rostest.rosrun(PKG, "pocketed", Pocketed)
