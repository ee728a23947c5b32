#!/usr/bin/python3
"""Every launch starts from its own scene and settings only, and a bad scene fails it. Two
launches of simulator.launch run one after the other on this test's master: the first with
config/default.yaml (a nine-point floor), paused and with a status line; the second with
config/random_gas.yaml and nothing else. The second must be exactly its own: its floor,
its balls, running, no status line, and none of the first's keys left on the server. A
third, with a bad scene, exits non-zero before it starts anything."""
import subprocess
import sys
import time
import unittest

import rospy
import rostest
import yaml
from std_msgs.msg import String

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import node_helpers as nh  # noqa: E402
from ball_collision_sim.srv import GetState  # noqa: E402

PKG = "ball_collision_sim"


class CleanLaunch(unittest.TestCase):
    def test_second_launch_is_its_own(self):
        first = nh.roslaunch("simulator.launch", "start_paused:=true", "status_period:=0.5",
                             "ball_color:=id")
        try:
            state = nh.call("/ball_sim/get_state", GetState, timeout=60)
            self.assertTrue(state.paused)
            self.assertEqual(len(state.balls), 12)
            self.assertEqual(rospy.get_param("/ball_sim/floor/type"), "biquadratic")
            self.assertEqual(rospy.get_param("/ball_sim/ball_color"), "id")
            time.sleep(1.2)  # a status line or two
        finally:
            out = nh.stop(first)
        self.assertIn("collisions/s", out)  # its status lines
        self.assertTrue(nh.wait_gone("/ball_sim/get_state"))
        # what the first left on the master: its scene and every setting it used
        self.assertTrue(rospy.has_param("/ball_sim/floor/control_points"))

        random_gas = rospy.get_param("/clean_launch_test/random_gas")
        second = nh.roslaunch("simulator.launch", "scene:=" + random_gas)
        try:
            a = nh.call("/ball_sim/get_state", GetState, timeout=60)
            time.sleep(0.5)
            b = nh.call("/ball_sim/get_state", GetState)
            params = rospy.get_param("/ball_sim")
            scene_text = rospy.wait_for_message("/ball_sim/scene", String, timeout=10).data
        finally:
            out = nh.stop(second)
        # running (not paused), with random_gas's 200 balls on its plane floor
        self.assertFalse(a.paused)
        self.assertGreater(b.time, a.time)
        self.assertEqual(len(a.balls), 200)
        self.assertEqual(sorted(params["floor"].keys()), ["point", "type", "u", "v"])
        self.assertEqual(params["floor"]["type"], "plane")
        self.assertEqual(params["dt"], 0.005)
        # the first launch's settings are gone: these are the defaults
        self.assertFalse(params["start_paused"])
        self.assertEqual(params["status_period"], 0.0)
        self.assertEqual(params["ball_color"], "speed")
        self.assertNotIn("collisions/s", out)
        # the scene it publishes is random_gas.yaml, every key of it, and nothing else
        with open(random_gas) as f:
            wanted = yaml.safe_load(f)
        published = yaml.safe_load(scene_text)
        self.assertNotIn("control_points", scene_text)
        for key, value in wanted.items():
            self.assertEqual(published[key], value, key)
        self.assertEqual(published["start_paused"], False)

    def test_a_bad_scene_fails_the_launch_with_its_one_message(self):
        """roslaunch exits non-zero for a bad scene, before any node starts, and prints the
        scene's one message (the key and the reason) once."""
        bad = rospy.get_param("/clean_launch_test/bad_scene")
        launch = nh.roslaunch("simulator.launch", "scene:=" + bad, "name:=bad_sim")
        try:
            out, _ = launch.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            self.fail("roslaunch ran on with a bad scene:\n" + nh.stop(launch))
        self.assertNotEqual(launch.returncode, 0, out)
        self.assertEqual(out.count("balls[0].radius: must be > 0 (got -0.1)"), 1, out)
        self.assertIn(bad + ": balls[0].radius", out)  # (the file named with the key)
        self.assertNotIn("process[bad_sim", out)  # no node started
        self.assertFalse(rospy.has_param("/bad_sim"))


if __name__ == "__main__":
    rospy.init_node("clean_launch_test")
    rostest.rosrun(PKG, "clean_launch", CleanLaunch)
