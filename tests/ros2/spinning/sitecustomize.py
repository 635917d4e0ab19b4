"""On PYTHONPATH, marks the moment an rclpy program first waits in its executor: it prints
SPINNING on standard error, once. tests/ros2/ctrl_c.py starts a lesson node with it and
presses Ctrl-C only after that line, when the node is in its loop taking messages, where the
Ctrl-C of a reader lands; an earlier one would end the imports, as Python's does.

With SW2SIM_CTRL_C_IN_TAKE=1 it also presses Ctrl-C itself, once it spins, at the worst
moment: while rclpy turns a /clock message it took into a Python object (the message's
constructor, which rclpy's converter calls). A KeyboardInterrupt raised there comes out of
rclpy 7.1 as `RuntimeError: Unable to convert call argument '0' to Python object`; a
reader meets it by chance, this meets it every time."""

import os
import signal
import sys

try:
    import rclpy.executors as _executors
except ImportError:        # not the ROS 2 environment: nothing to mark
    _executors = None

if _executors is not None:
    _wait = _executors.Executor._wait_for_ready_callbacks
    _state = {"spinning": False, "pressed": not os.environ.get("SW2SIM_CTRL_C_IN_TAKE")}

    def _marked(self, *args, **kwargs):
        if not _state["spinning"]:
            _state["spinning"] = True
            sys.stderr.write("SPINNING\n")
            sys.stderr.flush()
        return (yield from _wait(self, *args, **kwargs))

    _executors.Executor._wait_for_ready_callbacks = _marked

    if not _state["pressed"]:
        from rosgraph_msgs.msg import Clock

        _init = Clock.__init__

        def _init_and_press(self, *args, **kwargs):
            _init(self, *args, **kwargs)
            if _state["spinning"] and not _state["pressed"]:
                _state["pressed"] = True
                os.kill(os.getpid(), signal.SIGINT)   # handled before this returns

        Clock.__init__ = _init_and_press
