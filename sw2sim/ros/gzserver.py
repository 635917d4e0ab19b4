"""The stand-in's gzserver, as roslaunch starts it: the simulation node (sw2sim.ros.world)
with MuJoCo's drawing turned off, unless it shows a window (`sw2sim ros --view`), so that
MuJoCo loads no OpenGL library (a tenth of a second less at every start).

    python -m sw2sim.ros.gzserver [-u]
"""

import os
import sys
import time

from .. import gl

if os.environ.get("SW2SIM_VIEW") != "1":
    gl.without_drawing()

from .world import World  # noqa: E402  (after the choice above: MuJoCo reads it once)


def main(argv: list[str] | None = None) -> int:
    """The node: the world, its services, then steps kept to the real-time factor."""
    from . import messages
    messages.ensure()
    import rospy
    argv = sys.argv[1:] if argv is None else argv
    rospy.init_node("gazebo", disable_signals=True)
    world = World(rospy)
    world.services()
    world.paused = "-u" in argv   # gzserver's flag: start paused
    realtime = float(os.environ.get("SW2SIM_REALTIME", "1") or 0)
    window = None
    if os.environ.get("SW2SIM_VIEW") == "1":
        from .viewer import Window
        window = Window(world)
    try:
        while not rospy.is_shutdown():
            if window is not None:
                window.update()
            if world.model is None or world.paused:
                time.sleep(0.01)
                continue
            world.step()
            if realtime > 0:
                world.keep_pace(realtime)
    except KeyboardInterrupt:
        pass
    if window is not None:
        window.close()
    rospy.signal_shutdown("stopped")
    return 0


if __name__ == "__main__":
    sys.exit(main())
