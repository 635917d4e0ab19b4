"""Practice 5: drive the car from the keyboard in MuJoCo's viewer (needs a display).

    Up / Down      faster / slower (backwards below 0), in steps of 0.1 m/s
    Left / Right   turn the centre steering joint 5° to the left / right
    Space          stop and straighten the wheels

The viewer keeps its own keys (mouse to look around, Tab for the panels); the
arrow keys and Space are free. Run it from the repository root:
    python examples/example_5/scripts/drive.py
"""

import math
import sys
import time
from dataclasses import dataclass, replace

sys.path.insert(0, "examples/example_5/scripts")   # run from the repository root
from ackermann import Car  # noqa: E402  (the script next to this one)

# GLFW's key codes, which the viewer passes to key_callback
KEY_RIGHT, KEY_LEFT, KEY_DOWN, KEY_UP, KEY_SPACE = 262, 263, 264, 265, 32
SPEED_STEP = 0.1                    # m/s per key press
STEER_STEP = math.radians(5.0)      # rad per key press
TOP_SPEED = 1.5                     # m/s, either way


@dataclass(frozen=True)
class Command:
    speed: float = 0.0      # m/s, of the rear axle's centre
    steering: float = 0.0   # rad, of the centre steering joint; positive to the left


def on_key(command, key, steer_limit):
    """The command after one key press; other keys leave it as it was."""
    if key == KEY_UP:
        return replace(command, speed=min(command.speed + SPEED_STEP, TOP_SPEED))
    if key == KEY_DOWN:
        return replace(command, speed=max(command.speed - SPEED_STEP, -TOP_SPEED))
    if key == KEY_LEFT:
        return replace(command, steering=min(command.steering + STEER_STEP, steer_limit))
    if key == KEY_RIGHT:
        return replace(command, steering=max(command.steering - STEER_STEP, -steer_limit))
    if key == KEY_SPACE:
        return Command()
    return command


def main():
    import mujoco.viewer

    car = Car()
    limit = float(car.model.jnt_range[car.model.joint("steering_joint").id][1])
    state = {"command": Command()}

    def key_callback(key):
        state["command"] = on_key(state["command"], key, limit)

    with mujoco.viewer.launch_passive(car.model, car.data, key_callback=key_callback) as viewer:
        viewer.cam.type = mujoco.mjtCamera.mjCAMERA_TRACKING
        viewer.cam.trackbodyid = car.model.body("base_link").id
        viewer.cam.distance = 2.5
        while viewer.is_running():
            start = time.perf_counter()
            command = state["command"]
            car.command(speed=command.speed, steering=command.steering)
            with viewer.lock():
                car.step()
            viewer.sync()
            period = car.steps_per_control * car.model.opt.timestep
            time.sleep(max(0.0, period - (time.perf_counter() - start)))


if __name__ == "__main__":
    main()
