"""display.launch as a reader runs it: `roslaunch` on the package's own file, with the
environment `sw2sim ros` gives (its stand-in packages on ROS_PACKAGE_PATH) and the old node
types adapted (sw2sim.ros.launch_fixes), on a virtual screen (Xvfb, one for the module).

For the lessons' five packages and the exporter's three examples: the sliders' window
(sw2sim.ros.sliders, standing in for joint_state_publisher_gui) is open on the screen,
/joint_states carries every movable joint of the URDF, robot_state_publisher sends their
frames on /tf, and no node of the launch stops (RViz included). RViz on Mesa's software
renderer crashes now and then on a busy machine (a segmentation fault in Ogre, about one
launch in a few hundred here): a launch whose RViz dies of a signal is said in a warning and
made once more.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
import sys
import time
import warnings
from pathlib import Path

import pytest
from lxml import etree

from course import rviz_picture
from packages import EXAMPLES
from sw2sim.ros import sliders
from sw2sim.ros.launch_fixes import adapt
from sw2sim.ros.run import environment, missing, stop

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tool" / "check"))
from exporter_packages import REAL_EXPORTS, write_export  # noqa: E402  (tests/tool/check)

PROBE = Path(__file__).with_name("display_probe.py")
LESSONS = [f"example_{n}" for n in range(1, 6)]
WINDOW_TIMEOUT = 40.0   # s for the sliders' window to show (RViz starts beside it)
MOVABLE = ("revolute", "continuous", "prismatic")

# The display.launch of the exporter's repository's oldest example, byte for byte
# (ros/solidworks_urdf_exporter 25da24a, examples/ORIGINAL_3_DOF_ARM/
# ORIGINAL_3_DOF_ARM_description/launch/display.launch): Unix line ends, no line end after
# the last tag, and robot_state_publisher's node under its name before ROS Noetic.
# exporter_packages.py writes the launch file of today's exporter for every export, so the
# example's own replaces it here.
ORIGINAL_DISPLAY_LAUNCH = (
    b'<launch>\n  <arg\n    name="model" />\n  <arg\n    name="gui"\n    default="False" />\n'
    b'  <param\n    name="robot_description"\n    textfile="$(find ORIGINAL_3_DOF_ARM_description)'
    b'/urdf/ORIGINAL_3_DOF_ARM_description.urdf" />\n  <param\n    name="use_gui"\n'
    b'    value="$(arg gui)" />\n  <node\n    name="joint_state_publisher_gui"\n'
    b'    pkg="joint_state_publisher_gui"\n    type="joint_state_publisher_gui" />\n  <node\n'
    b'    name="robot_state_publisher"\n    pkg="robot_state_publisher"\n'
    b'    type="state_publisher" />\n  <node\n    name="rviz"\n    pkg="rviz"\n    type="rviz"\n'
    b'    args="-d $(find ORIGINAL_3_DOF_ARM_description)/urdf.rviz" />\n</launch>')
RENAMED_NOTE = ("launch/display.launch:20: node type robot_state_publisher/state_publisher was "
                "renamed robot_state_publisher in ROS Noetic (robot_state_publisher 1.15.0); "
                "running that")


def screen_missing() -> str | None:
    """Why the window cannot be looked at here, or None."""
    absent = [deb for program, deb in (("Xvfb", "xvfb"), ("xwininfo", "x11-utils"))
              if not shutil.which(program)]
    if absent:
        return (f"not installed: {', '.join(absent)} (`make setup` installs them where Debian "
                "ships ROS 1)")
    try:
        import tkinter  # noqa: F401
    except ImportError:
        return "this Python has no tkinter (Debian: python3-tk; `make setup` installs it)"
    return None


@pytest.fixture(scope="module")
def screen():
    reason = screen_missing()
    if reason:
        pytest.skip(reason)
    with rviz_picture.xvfb() as started:
        yield started.display


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> dict[str, Path]:
    """The exporter's three examples as it writes them, in one folder (ROS_PACKAGE_PATH)."""
    folder = tmp_path_factory.mktemp("exports")
    roots = {name: write_export(export, folder) for name, export in REAL_EXPORTS.items()}
    (roots["ORIGINAL_3_DOF_ARM_description"] / "launch" / "display.launch").write_bytes(
        ORIGINAL_DISPLAY_LAUNCH)
    return roots


def movable(urdf: Path) -> dict[str, str]:
    """{movable joint: its child link} of a URDF."""
    return {j.get("name"): j.find("child").get("link")
            for j in etree.parse(str(urdf)).getroot().findall("joint") if j.get("type") in MOVABLE}


def shown(display: str, title: re.Pattern) -> list[str]:
    """The titles matching `title` of the windows the screen shows (mapped, and their
    parents too), as xwininfo reports them."""
    tree = subprocess.run(["xwininfo", "-display", display, "-root", "-tree"],
                          capture_output=True, text=True, timeout=10).stdout
    found = []
    for window, name in re.findall(r'^\s*(0x[0-9a-f]+) "(.*)":', tree, re.M):
        if title.fullmatch(name):
            report = subprocess.run(["xwininfo", "-display", display, "-id", window],
                                    capture_output=True, text=True, timeout=10).stdout
            if "Map State: IsViewable" in report:
                found.append(name)
    return found


# RViz dying of a signal (a segmentation fault, an abort), as roslaunch reports it
RVIZ_CRASH = re.compile(r"\[rviz-\d+\] process has died \[pid \d+, exit code -\d+")


def windows_shown(display: str, windows: dict[str, re.Pattern],
                  launched: subprocess.Popen) -> dict[str, list[str]]:
    """{kind: titles} of `windows` on the screen, once all show, after WINDOW_TIMEOUT, or
    when the launch has ended."""
    deadline, showing = time.monotonic() + WINDOW_TIMEOUT, {}
    while len(showing) < len(windows) and time.monotonic() < deadline and launched.poll() is None:
        time.sleep(0.25)
        showing = {k: found for k, title in windows.items() if (found := shown(display, title))}
    return showing


@pytest.mark.parametrize("package", [*LESSONS, *REAL_EXPORTS])
def test_display_launch_opens_the_sliders_and_places_every_joint(package, screen, exported, ros,
                                                                  tmp_path):
    if not shutil.which("rviz"):
        pytest.skip("not installed: rviz (`make setup` installs it where Debian ships ROS 1)")
    root = exported[package] if package in exported else EXAMPLES / package
    launch, notes = adapt(root / "launch" / "display.launch", tmp_path / "adapted")
    if package == "ORIGINAL_3_DOF_ARM_description":
        assert notes == [RENAMED_NOTE]
    else:
        assert (launch, notes) == (root / "launch" / "display.launch", [])
    home = tmp_path / "home"
    (home / "runtime").mkdir(parents=True)
    (home / "runtime").chmod(0o700)
    ours = {k: ros.env[k] for k in ("ROS_MASTER_URI", "ROS_IP", "ROS_HOSTNAME", "ROS_HOME",
                                   "ROS_LOG_DIR")}
    ros.env = {**environment(root, 1.0), **ours, "DISPLAY": screen, "HOME": str(home),
               "XDG_RUNTIME_DIR": str(home / "runtime")}
    joints = movable(root / "urdf" / f"{root.name}.urdf")
    assert joints, "every example has a joint to move"
    # The sliders' window, and RViz's ("urdf.rviz - RViz", or "RViz" without a config file)
    title = sliders.TITLE.format(node="/joint_state_publisher_gui")
    windows = {"sliders": re.compile(re.escape(title)), "RViz": re.compile(r"(.* - )?RViz\*?")}
    for attempt in (1, 2):
        suffix = "" if attempt == 1 else f"-{attempt}"
        launched = ros.start("roslaunch", "--wait", str(launch), name="roslaunch" + suffix)
        log = ros.logs / f"roslaunch{suffix}.log"
        # listening from the start: rospy's own start overlaps the launch's
        probe = ros.start(sys.executable, str(PROBE),
                          json.dumps({"joints": list(joints), "frames": list(joints.values())}),
                          name="probe" + suffix)
        showing = windows_shown(screen, windows, launched)
        if showing.keys() == windows.keys():
            heard = probe.wait(timeout=90)
        crash = RVIZ_CRASH.search(log.read_text(errors="replace"))
        if not crash or attempt == 2:
            break
        # RViz itself crashed (Ogre on Mesa's software renderer does so now and then on a
        # busy machine): said, and the launch made once more; a second crash fails.
        warnings.warn(f"{package}: RViz crashed on the virtual screen ({crash[0]}); "
                      "launching display.launch again")
        stop(launched, probe)
    assert showing.keys() == windows.keys(), \
        f"windows shown: {showing}\n{log.read_text(errors='replace')[-3000:]}"

    assert heard == 0
    report = (ros.logs / f"probe{suffix}.log").read_text(errors="replace")
    seen = json.loads(report.splitlines()[-1])
    assert set(seen["joints"]) == set(joints), seen["joints"]
    assert seen["publishers"] == ["/joint_state_publisher_gui"]
    placed = {child: node for child, node in seen["tf"].items() if child in joints.values()}
    assert placed == {child: "/robot_state_publisher" for child in joints.values()}, seen["tf"]
    # Every node still runs (RViz may stop badly once told to stop: not checked after that).
    text = log.read_text(errors="replace")
    assert "process has died" not in text and "cannot launch node" not in text, text[-3000:]
    ros.stop_all()


# --- the sliders' node, in this process -------------------------------------------------------

URDF = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/><link name="f"/>
  <joint name="turn" type="continuous"><parent link="a"/><child link="b"/></joint>
  <joint name="lift" type="prismatic"><parent link="b"/><child link="c"/>
    <limit lower="0.1" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="empty" type="revolute"><parent link="c"/><child link="d"/>
    <limit lower="0" upper="0" effort="0" velocity="0"/><safety_controller k_velocity="0"/></joint>
  <joint name="soft" type="revolute"><parent link="d"/><child link="e"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
    <safety_controller k_velocity="1" soft_lower_limit="-1" soft_upper_limit="1.5"/></joint>
  <joint name="twin" type="revolute"><parent link="e"/><child link="f"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
    <mimic joint="soft" multiplier="-2" offset="0.5"/></joint>
  <joint name="weld" type="fixed"><parent link="a"/><child link="f"/></joint>
</robot>"""


def test_the_sliders_span_each_joints_range_as_upstream_reads_it():
    found = {j.name: j for j in sliders.joints(URDF)}
    assert list(found) == ["turn", "lift", "empty", "soft", "twin"]
    assert (found["turn"].lower, found["turn"].upper) == (-math.pi, math.pi)
    assert (found["soft"].lower, found["soft"].upper) == (-1.0, 1.5)   # the soft limits
    assert found["lift"].zero == pytest.approx(0.2)   # 0 is out of range: the middle
    assert [j.name for j in found.values() if j.slides] == ["turn", "lift", "soft"]
    assert sliders.positions(list(found.values()), {"soft": 1.0, "lift": 0.25}) == \
        pytest.approx([0.0, 0.25, 0.0, 1.0, -1.5])
    wide = {j.name: j for j in sliders.joints(URDF, {"turn": 0.5}, smallest_limits=False)}
    assert (wide["soft"].lower, wide["soft"].upper, wide["turn"].zero) == (-2.0, 2.0, 0.5)


def test_a_description_that_is_not_a_urdf_is_named_so():
    with pytest.raises(sliders.DescriptionError, match="not a URDF: its root is <sdf>"):
        sliders.joints("<sdf/>")
    with pytest.raises(sliders.DescriptionError, match='joint j: limit upper="x" is not a number'):
        sliders.joints('<robot><joint name="j" type="revolute"><limit lower="0" upper="x"/>'
                       '</joint></robot>')


def test_randomize_stays_in_range_and_center_goes_back(screen):
    import tkinter
    root = tkinter.Tk(screenName=screen)
    try:
        found = sliders.joints(URDF)
        window = sliders.Window(root, "test", found, rows=2)
        root.update()
        assert set(window.chosen()) == {"turn", "lift", "soft"}
        for _ in range(20):
            window.randomize()
            for joint in found:
                if joint.slides:
                    assert joint.lower <= window.chosen()[joint.name] <= joint.upper
        window.center()
        assert window.chosen() == pytest.approx({"turn": 0.0, "lift": 0.2, "soft": 0.0})
    finally:
        root.destroy()


# --- old node types ---------------------------------------------------------------------------

def _package(folder: Path, launch: bytes) -> Path:
    root = folder / "ORIGINAL_3_DOF_ARM_description"
    (root / "launch").mkdir(parents=True)
    (root / "package.xml").write_text("<package>\n  <name>ORIGINAL_3_DOF_ARM_description</name>"
                                      "\n</package>")
    (root / "launch" / "display.launch").write_bytes(launch)
    return root


def test_state_publisher_runs_as_robot_state_publisher_in_a_copy(tmp_path):
    for newline in (b"\n", b"\r\n"):
        launch = ORIGINAL_DISPLAY_LAUNCH.replace(b"\n", newline)
        root = _package(tmp_path / repr(newline), launch)
        original = root / "launch" / "display.launch"
        adapted, notes = adapt(original, tmp_path / "adapted")
        assert notes == [RENAMED_NOTE]
        assert original.read_bytes() == launch, "the user's file is left as it is"
        assert adapted == tmp_path / "adapted" / root.name / "launch" / "display.launch"
        assert adapted.read_bytes() == launch.replace(b'type="state_publisher"',
                                                      b'type="robot_state_publisher"')
        # once adapted, nothing is left to change
        assert adapt(adapted, tmp_path / "again") == (adapted, [])


def test_a_launch_file_without_old_types_runs_as_it_is(tmp_path):
    launch = ORIGINAL_DISPLAY_LAUNCH.replace(b'"state_publisher"', b'"robot_state_publisher"')
    # in a comment, the old name is not a node
    launch = launch.replace(b"<launch>", b'<launch>\n<!-- <node pkg="robot_state_publisher" '
                                         b'type="state_publisher" /> -->')
    root = _package(tmp_path, launch)
    assert adapt(root / "launch" / "display.launch", tmp_path / "adapted") == \
        (root / "launch" / "display.launch", [])
    assert not (tmp_path / "adapted").exists()


def test_an_included_launch_file_of_the_package_is_adapted_too(tmp_path):
    if missing():
        pytest.skip(missing())
    root = _package(tmp_path / "src", ORIGINAL_DISPLAY_LAUNCH)
    (root / "urdf").mkdir()
    (root / "urdf" / f"{root.name}.urdf").write_text('<robot name="arm" />')
    main = root / "launch" / "main.launch"
    main.write_text('<launch>\n  <include file="$(find ORIGINAL_3_DOF_ARM_description)'
                    '/launch/display.launch" />\n  <include file="$(find rviz)/none.launch" '
                    'if="false" />\n</launch>\n')
    adapted, notes = adapt(main, tmp_path / "adapted")
    copy = tmp_path / "adapted" / root.name / "launch" / "display.launch"
    assert notes == [RENAMED_NOTE]
    assert adapted == tmp_path / "adapted" / root.name / "launch" / "main.launch"
    text = adapted.read_text()
    assert f'file="{copy}"' in text and 'file="$(find rviz)/none.launch"' in text
    # roslaunch reads the copies: the included one is the adapted display.launch
    env = {**environment(root, 1.0), "ROS_HOME": str(tmp_path / "ros")}
    files = subprocess.run(["roslaunch", "--files", str(adapted)], env=env, capture_output=True,
                           text=True, timeout=60)
    assert files.returncode == 0, files.stderr
    assert set(files.stdout.split()) == {str(adapted), str(copy)}
