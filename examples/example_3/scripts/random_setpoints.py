"""Practice 3, MuJoCo version of the movement script: random set points every 5 s.

Each setpoint is drawn between the joint's limits (±0.7854 rad) and held for
PERIOD seconds, a rate of 1 / 5 s = 0.2 Hz. Run it from the repository root:
    python examples/example_3/scripts/random_setpoints.py
"""

import sys

import numpy as np

sys.path.insert(0, "examples/example_3/scripts")   # run from the repository root
from arm_controller import Arm  # noqa: E402  (the script next to this one)

PERIOD = 5.0   # s between two new setpoints


def random_setpoints(arm, seconds, seed=None):
    """Drive `arm` for `seconds`, sending new random setpoints every PERIOD s."""
    rng = np.random.default_rng(seed)
    for _ in range(round(seconds / PERIOD)):
        arm.command(**{name: rng.uniform(c.limits.lower, c.limits.upper)
                       for name, c in arm.controllers.items()})
        arm.run(PERIOD)


if __name__ == "__main__":
    arm = Arm()
    random_setpoints(arm, seconds=30, seed=1)
    t = arm.times()
    for name in arm.controllers:
        error = np.abs(arm.states(name, "error"))
        settled = error[(t + 1e-6) % PERIOD > 2.0]   # the last 3 s of each 5 s hold
        print(f"{name:22} {len(t)} samples at {arm.state_rate} Hz, "
              f"largest error once settled {settled.max():.4f} rad")
