"""`sw2sim plot`: topics' numeric fields over time, in rqt_plot's place (Debian ships no rqt)."""

from __future__ import annotations

import argparse
from pathlib import Path

from .options import no_display, say

HELP = """\
Plots numeric fields of ROS topics over ROS time, as rqt_plot does, under ROS 1 (rospy,
the master at ROS_MASTER_URI) or ROS 2 (rclpy), and takes rqt_plot's names, so that the
same line works in both tools:

  /joint_states/velocity[0]        a field of a topic's message, [N] into an array
  /example_3/middle_arm_controller/state/set_point   fields inside fields
  /joint_states/position[0]:velocity[0]   shorthand for two fields of one topic
  /a/data,/b/data                  several names in one argument
  /example_4/block_controller/state   a message: each of its numeric fields

The time axis is ROS time since the first sample: a message's header stamp where it has
one, else when it arrived; under a simulation's /clock (`sw2sim ros`, `sw2sim ros2`,
Gazebo) that is simulated time. With a display it draws in a live window showing the last
10 s, as rqt_plot scrolls (--window S for another span); without one, or with -o, it
draws into a PNG when it ends, and says where. It ends on Ctrl-C (the PNG and CSV are
still written), when the window is closed, or after --duration S: S seconds on the plot's
time axis (simulated seconds under /clock, however fast the simulation runs).

It uses ROS 1 where rospy imports and a master answers at ROS_MASTER_URI, else ROS 2
where rclpy imports (`--ros` chooses). Under ROS 2, give it the terminal's ROS_DOMAIN_ID;
it stays on this machine, as `sw2sim ros2` does. It waits up to 10 s for the topics to be
published, then for their first message.
Exit status: 0 done (also when ended by Ctrl-C), 2 it could not plot (the reason and the
fix are printed).

examples:
  sw2sim plot /joint_states/velocity[0]
  sw2sim plot /example_3/middle_arm_controller/state/set_point \\
      /example_3/middle_arm_controller/state/process_value --duration 20 -o arm.png
  sw2sim plot /example_4/block_controller/state/process_value --csv block.csv
  sw2sim plot /joint_states/position[0]:velocity[0] --window 30
"""


def seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"{value:g} s: give a time above 0")
    return value


def add_arguments(parser) -> None:
    parser.add_argument("names", metavar="TOPIC/FIELD", nargs="+",
                        help="what to plot, in rqt_plot's form (see above)")
    parser.add_argument("-o", "--output", metavar="FILE.png", type=Path,
                        help="draw into this PNG when it ends (no window)")
    parser.add_argument("--csv", metavar="FILE.csv", type=Path,
                        help="also write every sample: series, ros_time, time, value")
    parser.add_argument("--duration", metavar="S", type=seconds,
                        help="end after S seconds of the plot's time (simulated time "
                             "under /clock) from the first sample")
    parser.add_argument("--window", metavar="S", type=seconds,
                        help="show only the last S seconds (default: 10 in a window, as "
                             "rqt_plot; all of it in a PNG)")
    parser.add_argument("--ros", choices=("1", "2"),
                        help="which ROS (default: ROS 1 if its master answers, else ROS 2)")


def run(args) -> int:
    from ..plot.run import Options, run as run_plot
    if args.output is not None and args.output.suffix.lower() != ".png":
        say(f"sw2sim plot: -o {args.output}: give a file ending in .png")
        return 2
    options = Options(names=args.names, ros=args.ros, output=args.output, csv=args.csv,
                      duration=args.duration, window=args.window,
                      live=no_display() is None)
    return run_plot(options, say=say)
