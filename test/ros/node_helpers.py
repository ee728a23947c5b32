"""Helpers for the node's Python rostests: service calls, topic collection, launching."""
import os
import signal
import subprocess
import threading
import time

import genpy
import rospy


def call(name, srv_type, timeout=20.0, **fields):
    """Calls service `name` with the request fields given (nested ones as dicts, as
    `rosservice call` takes them); returns the response."""
    rospy.wait_for_service(name, timeout=timeout)
    request = srv_type._request_class()
    genpy.message.fill_message_args(request, [fields])
    return rospy.ServiceProxy(name, srv_type)(request)


class Inbox:
    """Collects the messages of one topic."""

    def __init__(self, topic, msg_type):
        self.msgs = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._add, queue_size=1000)

    def _add(self, msg):
        with self.lock:
            self.msgs.append(msg)

    def take(self):
        with self.lock:
            out, self.msgs = self.msgs, []
        return out

    def wait_for(self, pred, timeout=10.0):
        """Waits until pred(all messages so far) holds; returns whether it did."""
        end = time.time() + timeout
        while time.time() < end:
            with self.lock:
                if pred(self.msgs):
                    return True
            time.sleep(0.01)
        return False

    def wait_connected(self, timeout=10.0):
        end = time.time() + timeout
        while self.sub.get_num_connections() == 0 and time.time() < end:
            time.sleep(0.01)
        time.sleep(0.2)

    def close(self):
        self.sub.unregister()


def roslaunch(*args):
    """Starts `roslaunch ball_collision_sim ARGS` on this test's master, headless."""
    env = dict(os.environ, ROSCONSOLE_STDOUT_LINE_BUFFERED="1")
    env.pop("DISPLAY", None)
    return subprocess.Popen(["roslaunch", "ball_collision_sim"] + list(args), env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)


def stop(process, timeout=20.0):
    """Stops a roslaunch as Ctrl-C does; returns its output."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
    try:
        out, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, _ = process.communicate()
    return out


def wait_gone(service, timeout=20.0):
    """Waits until `service` is no longer offered (its node has stopped)."""
    import rosservice
    end = time.time() + timeout
    while time.time() < end:
        try:
            if service not in rosservice.get_service_list():
                return True
        except Exception:  # the master is busy with the node's shutdown
            pass
        time.sleep(0.1)
    return False
