"""MuJoCo's viewer on the stand-in's simulation, for `sw2sim ros --view`.

The window shows the world the simulation node steps, at most FPS times a second. It
opens once the model is spawned and again whenever the node recompiles the model (a
controller adds its actuator). Closing the window leaves the simulation running; a
display that cannot open a window is reported once, and the simulation goes on without.
"""

from __future__ import annotations

import sys
import time

FPS = 60.0


class Window:
    """The viewer window of one World (sw2sim.ros.world)."""

    def __init__(self, world):
        self.world = world
        self.handle = None
        self.model = None
        self.closed = False
        self.next = 0.0

    def update(self) -> None:
        """Show the world's current state; cheap when called more often than FPS."""
        now = time.monotonic()
        if self.closed or now < self.next:
            return
        self.next = now + 1.0 / FPS
        with self.world.lock:
            model, data = self.world.model, self.world.data
            if model is None:
                return
            if model is not self.model:
                self._open(model, data)
                if self.closed:
                    return
            if not self.handle.is_running():
                self.closed = True
                return
            self.handle.sync()

    def _open(self, model, data) -> None:
        self.close()
        try:
            import mujoco.viewer
            self.handle = mujoco.viewer.launch_passive(model, data)
            self.model = model
        except Exception as exc:  # noqa: BLE001  (GLFW and the display fail in many ways)
            print(f"sw2sim ros: the viewer could not open a window ({type(exc).__name__}: "
                  f"{exc}); the simulation goes on without it", file=sys.stderr, flush=True)
            self.closed = True

    def close(self) -> None:
        if self.handle is not None:
            self.handle.close()
            self.handle = None
