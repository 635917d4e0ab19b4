"""`sw2sim render` frames the whole robot as it stands on the floor, whatever the base.

The robot's pixels are found by rendering the same picture twice, once with the robot's
geoms hidden: what differs is the robot. Its bounding box must stay clear of the picture's
edges and fill a good part of it.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from PIL import Image

from sw2sim.cli import main
from sw2sim.loader import load_package, world_fixed
from sw2sim.render import render, robot_view
from packages import copy_example, edit, urdf_of
from repository import ROOT, practice_numbers


def robot_box(image: np.ndarray, without: np.ndarray) -> tuple[int, int, int, int]:
    """(left, top, right, bottom) of the pixels where the robot changes the picture."""
    rows, cols = np.nonzero(np.abs(image.astype(int) - without.astype(int)).sum(axis=2) > 24)
    assert len(rows), "the robot is not in the picture"
    return cols.min(), rows.min(), cols.max(), rows.max()


def pictures(package, width, height, azimuth=135.0, elevation=-25.0, frame=True):
    """The picture `sw2sim render` makes, and the same with the robot hidden."""
    spec = load_package(package, fixed_base=world_fixed(package))
    spec.visual.global_.offwidth, spec.visual.global_.offheight = width, height
    model = spec.compile()
    data = mujoco.MjData(model)
    view = dict(width=width, height=height, azimuth=azimuth, elevation=elevation,
                shadows=False)
    if frame:
        lookat, distance = robot_view(model, data, azimuth, elevation, width, height)
    else:   # how render aimed before: the model's centre, from 1.6 times its extent
        lookat, distance = model.stat.center.copy(), 1.6 * model.stat.extent
    shown = render(model, data, lookat=lookat, distance=distance, **view)
    robot = model.geom_bodyid != 0
    model.geom_rgba[robot, 3] = 0.0
    hidden = render(model, data, lookat=lookat, distance=distance, **view)
    return shown, hidden


def assert_framed(box, width, height):
    left, top, right, bottom = box
    assert left >= 1 and top >= 1 and right <= width - 2 and bottom <= height - 2, box
    assert (right - left) >= 0.5 * width or (bottom - top) >= 0.5 * height, box


def raised(tmp_path, height=2.5):
    """Practice 5's vehicle (a free base) placed `height` m above a new root link at the
    origin: its meshes sit far from where the model's frame is, as in many real exports.
    Below the origin (height < 0), the loader lifts the whole robot onto the floor."""
    package = copy_example(5, tmp_path)
    edit(urdf_of(package), "</robot>", """  <link name="origin_link">
    <inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>
  </link>
  <joint name="origin_joint" type="fixed">
    <origin xyz="0 0 {height}" rpy="0 0 0"/>
    <parent link="origin_link"/>
    <child link="base_link"/>
  </joint>
</robot>""".format(height=height))
    return package


@pytest.mark.parametrize("n", practice_numbers())
def test_render_frames_each_practice_robot(tmp_path, n):
    package = copy_example(n, tmp_path)
    out = tmp_path / "picture.png"
    assert main(["render", str(package), "-o", str(out), "--width", "320",
                 "--height", "240"]) == 0
    assert Image.open(out).size == (320, 240)
    shown, hidden = pictures(package, 320, 240)
    assert np.array_equal(shown, np.asarray(Image.open(out).convert("RGB")))
    assert_framed(robot_box(shown, hidden), 320, 240)


@pytest.mark.parametrize("lift, width, height, azimuth, elevation", [
    (2.5, 320, 240, 135, -25), (2.5, 240, 320, 30, -60), (2.5, 320, 180, 270, -5),
    (-0.5, 320, 240, 135, -25)])
def test_render_frames_a_robot_far_from_its_origin(tmp_path, lift, width, height, azimuth,
                                                   elevation):
    package = raised(tmp_path, lift)
    shown, hidden = pictures(package, width, height, azimuth, elevation)
    assert_framed(robot_box(shown, hidden), width, height)


@pytest.mark.parametrize("lift", [2.5, -0.5])
def test_the_old_aim_cut_that_robot_off(tmp_path, lift):
    """What the test above guards against: aimed at the model's centre, part of the robot
    falls outside the picture (or it is a speck). The robot lifted onto the floor is cut
    at the top edge, since that centre was taken before the lift."""
    shown, hidden = pictures(raised(tmp_path, lift), 320, 240, frame=False)
    box = robot_box(shown, hidden)
    with pytest.raises(AssertionError):
        assert_framed(box, 320, 240)
    if lift < 0:
        assert box[1] == 0, box


def test_a_picture_larger_than_the_model_s_offscreen_buffer_grows_the_buffer():
    """render() is asked for more pixels than the model's <global offwidth offheight>
    allow (MuJoCo's Renderer refuses that): the buffer grows to the picture, which comes
    out at the size asked, with the robot in it."""
    spec = load_package(ROOT / "examples" / "example_3")
    spec.visual.global_.offwidth, spec.visual.global_.offheight = 320, 240
    model = spec.compile()
    data = mujoco.MjData(model)
    image = render(model, data, width=640, height=400, shadows=False)
    assert image.shape == (400, 640, 3)
    assert (model.vis.global_.offwidth, model.vis.global_.offheight) == (640, 400)
    assert image.std() > 5, "a picture, not a blank buffer"
