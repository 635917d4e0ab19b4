"""The stand-in's gzserver, as roslaunch starts it: the simulation node (sw2sim.ros.world)
with MuJoCo's drawing turned off, unless it shows a window (`sw2sim ros --view`), so that
MuJoCo loads no OpenGL library (a tenth of a second less at every start).

    python -m sw2sim.ros.gzserver [-u]
"""

import os
import sys

from .. import gl

if os.environ.get("SW2SIM_VIEW") != "1":
    gl.without_drawing()

from .world import main  # noqa: E402  (after the choice above: MuJoCo reads it once)

if __name__ == "__main__":
    sys.exit(main())
