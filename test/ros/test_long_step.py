#!/usr/bin/python3
"""Item: a long step does not freeze the node. On config/random_gas.yaml (200 balls),
`step 100000` runs while get_state answers within 0.2 s and shows the time moving, and
a second step call is refused at once; `step 1000000` is cancelled with ~cancel_step.
The same through the step action: feedback as it goes, cancel, and a short goal that
ends at the exact time."""
import os
import sys
import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from std_srvs.srv import SetBool, Trigger

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.msg import StepAction, StepGoal  # noqa: E402
from ball_collision_sim.srv import GetState, Step  # noqa: E402

PKG = "ball_collision_sim"
NS = "/ball_sim/"
DT = 0.005  # random_gas.yaml
# [s] the longest another service may take to answer during a run; a build with the
# sanitizers (BCS_SLOWDOWN, set by `make sanitize`) runs its code several times slower
LIMIT = 0.2 * float(os.environ.get("BCS_SLOWDOWN", "1"))


def watch(seconds):
    """get_state as often as it answers for `seconds`: (latencies, times). One connection
    for all the calls, so that what is timed is the node's answer (a new connection per
    call also asks the master where the service is, every time)."""
    get = rospy.ServiceProxy(NS + "get_state", GetState, persistent=True)
    latencies, times = [], []
    end = time.time() + seconds
    while time.time() < end:
        start = time.time()
        times.append(get().time)
        latencies.append(time.time() - start)
    return latencies, times


class LongStep(unittest.TestCase):
    def setUp(self):
        self.assertTrue(nh.call(NS + "pause", SetBool, data=True, timeout=60).success)
        self.assertTrue(nh.call(NS + "reset", Trigger).success)

    def test_service_step_leaves_the_node_answering(self):
        result = {}
        runner = threading.Thread(target=lambda: result.update(r=nh.call(NS + "step", Step, steps=100000)))
        runner.start()
        latencies, times = watch(0.5)
        second = nh.call(NS + "step", Step, steps=10)  # one run at a time: refused, at once
        self.assertFalse(second.success)
        self.assertIn("another run of steps is going", second.message)
        while runner.is_alive():
            more, later = watch(0.2)
            latencies += more
            times += later
        self.assertGreater(len(latencies), 20)
        self.assertLess(max(latencies), LIMIT, sorted(latencies)[-5:])
        self.assertGreater(len(set(times)), 3)  # progress shows: the time moves as it runs
        r = result["r"]
        self.assertTrue(r.success, r.message)
        self.assertAlmostEqual(r.time, 100000 * DT, places=6)

    def test_service_step_is_cancelled(self):
        result = {}
        runner = threading.Thread(target=lambda: result.update(r=nh.call(NS + "step", Step, steps=1000000)))
        runner.start()
        watch(0.5)
        cancel = nh.call(NS + "cancel_step", Trigger)
        runner.join(20)
        self.assertFalse(runner.is_alive())
        self.assertTrue(cancel.success, cancel.message)
        r = result["r"]
        self.assertFalse(r.success)
        self.assertIn("cancelled after", r.message)
        self.assertLess(round(r.time / DT), 1000000)
        self.assertAlmostEqual(nh.call(NS + "get_state", GetState).time, r.time, places=12)
        self.assertFalse(nh.call(NS + "cancel_step", Trigger).success)  # nothing left to cancel

    def test_action_gives_feedback_and_is_cancelled(self):
        client = actionlib.SimpleActionClient(NS + "step", StepAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(20)))
        feedback = []
        client.send_goal(StepGoal(steps=100000), feedback_cb=lambda f: feedback.append(f.steps_done))
        latencies, _ = watch(1.5)
        client.cancel_goal()
        self.assertTrue(client.wait_for_result(rospy.Duration(20)))
        self.assertEqual(client.get_state(), GoalStatus.PREEMPTED)
        result = client.get_result()
        self.assertFalse(result.success)
        self.assertLess(result.steps_done, 100000)
        self.assertGreater(len(feedback), 3)
        self.assertEqual(feedback, sorted(feedback))
        self.assertLess(max(latencies), LIMIT, sorted(latencies)[-5:])
        self.assertAlmostEqual(result.time, nh.call(NS + "get_state", GetState).time, places=12)
        # a short goal runs to its end: exactly 500 steps later
        t0 = result.time
        client.send_goal(StepGoal(steps=500))
        self.assertTrue(client.wait_for_result(rospy.Duration(60)))
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED)
        self.assertEqual(client.get_result().steps_done, 500)
        self.assertAlmostEqual(client.get_result().time, t0 + 500 * DT, places=9)


if __name__ == "__main__":
    rospy.init_node("long_step_test")
    rostest.rosrun(PKG, "long_step", LongStep)
