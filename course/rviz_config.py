"""The RViz configuration an example package ships as `urdf.rviz`.

The exporter's launch/display.launch starts RViz with `-d $(find NAME)/urdf.rviz` but
writes no such file, so RViz opens with its own defaults: fixed frame `map`, which the
robot's transforms never reach, and no RobotModel display. The course adds the file:
the fixed frame is the robot's root link, a Grid on the floor, the RobotModel read from
`robot_description`, a TF display to switch on, and an orbit camera framing the robot
as it stands with every joint at zero (what joint_state_publisher_gui starts from).
"""

from __future__ import annotations

import math
import struct

import numpy as np

# The RViz window: the 3D view's background, where the window opens and its size, and the
# docks around the 3D view: the Displays on the left, the Views on the right, the Time below
# (widths and height in pixels). The 3D view gets what is left, about 640 x 640.
BACKGROUND = (48, 48, 48)
WINDOW = {"X": 0, "Y": 0, "Width": 1280, "Height": 800}
DOCKS = {"left": ("Displays", 330), "right": ("Views", 250), "bottom": ("Time", 60)}
MENU_AND_TOOLS, STATUS = 62, 29
FIELD_OF_VIEW = math.pi / 4      # rad: RViz's camera, vertically
YAW, PITCH = 0.9, 0.45           # rad: the orbit camera, from the front left, a little above
# A robot several times longer than wide (Practice 4's bar) is seen more from its right
# side, x to the right, where it spans the view instead of running away from the camera.
LONG, LONG_YAW, LONG_PITCH = 4.0, -1.3, 0.35


def _rotation(rpy) -> np.ndarray:
    """URDF's roll-pitch-yaw: about fixed x, then y, then z."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def root_link(robot) -> str:
    """The link no joint has as its child: the frame everything else hangs from."""
    joints = [*robot.added_joints, *robot.joints]
    children = {j.child for j in joints}
    roots = [link.name for link in [*robot.added_links, *robot.links] if link.name not in children]
    if len(roots) != 1:
        raise ValueError(f"{robot.name}: expected one root link, found {roots}")
    return roots[0]


def bounds(robot) -> np.ndarray:
    """(2, 3): the lowest and highest corner of the robot's meshes in its root link's frame,
    with every joint at zero."""
    joints = {j.child: j for j in [*robot.added_joints, *robot.joints]}
    poses: dict[str, np.ndarray] = {}

    def pose(link: str) -> np.ndarray:
        if link not in poses:
            local = np.eye(4)
            if link in joints:
                j = joints[link]
                local[:3, :3], local[:3, 3] = _rotation(j.rpy), j.xyz
                local = pose(j.parent) @ local
            poses[link] = local
        return poses[link]

    corners = []
    for link in robot.links:
        vertices = np.asarray(link.part.mesh.vertices)
        placed = vertices @ pose(link.name)[:3, :3].T + pose(link.name)[:3, 3]
        corners += [placed.min(axis=0), placed.max(axis=0)]
    return np.array([np.min(corners, axis=0), np.max(corners, axis=0)])


def _grid_cell(size: float) -> float:
    """A round cell size (1, 2 or 5 times a power of ten) of about a fifth of the robot."""
    step = 10 ** math.floor(math.log10(size / 5))
    return next(step * k for k in (1, 2, 5, 10) if step * k >= size / 5)


def view_size() -> tuple[int, int]:
    """The 3D view's width and height in pixels, in a window of WINDOW's size: what the
    docks, the buttons that fold them, the menu, the toolbar and the status bar leave
    (as RViz 1.14 lays them out)."""
    return (WINDOW["Width"] - DOCKS["left"][1] - DOCKS["right"][1] - 62,
            WINDOW["Height"] - MENU_AND_TOOLS - STATUS - DOCKS["bottom"][1] - 6)


def window_state() -> str:
    """The docks' layout as Qt's QMainWindow::saveState writes it, in hex (RViz's
    "QMainWindow State"). Without it RViz stacks every panel on the left and the 3D view
    is squeezed to nothing.

    The format: int 0xff and a version; a dock marker (0xfd) and the number of dock areas;
    for each, its index (left 0, right 1, top 2, bottom 3), its size and a sequence (marker
    0xfc, orientation 1 across or 2 down, count) of widgets (marker 0xfb, the panel's name
    as UTF-16, 1 for visible, then position, size, minimum and maximum along the sequence);
    then the central widget's size and which area owns each corner; then the toolbars."""
    def name(text: str) -> bytes:
        raw = text.encode("utf-16-be")
        return struct.pack(">i", len(raw)) + raw

    width, height = WINDOW["Width"], WINDOW["Height"]
    middle = height - MENU_AND_TOOLS - STATUS - DOCKS["bottom"][1]
    areas = [(0, DOCKS["left"], (DOCKS["left"][1], middle), 2),
             (1, DOCKS["right"], (DOCKS["right"][1], middle), 2),
             (3, DOCKS["bottom"], (width, DOCKS["bottom"][1]), 1)]
    out = struct.pack(">iiBi", 0xFF, 0, 0xFD, len(areas))
    for index, (panel, _), (w, h), orientation in areas:
        along = h if orientation == 2 else w
        out += struct.pack(">iii", index, w, h) + struct.pack(">BBi", 0xFC, orientation, 1)
        out += b"\xfb" + name(panel) + struct.pack(">Biiii", 1, 0, along, 0, 16777215)
    # The top corners belong to the side docks, the bottom ones to the bottom dock.
    out += struct.pack(">ii", *view_size()) + struct.pack(">iiii", 1, 2, 8, 8)
    # The toolbars (marker 0xfc, number of lines): one line on top (2) with one toolbar,
    # RViz's "Tools", shown, first in the line, at its own size (-1), not floating.
    out += struct.pack(">Biii", 0xFC, 1, 2, 1) + name("Tools") + struct.pack(">BiiII", 1, 0, -1, 0, 0)
    return out.hex()


def _num(v: float) -> str:
    return f"{v:.4g}" if abs(v) >= 1e-9 else "0"


def angles(low: np.ndarray, high: np.ndarray) -> tuple[float, float]:
    """The orbit camera's yaw and pitch for a robot in the box (low, high)."""
    length, width = high[:2] - low[:2]
    return (LONG_YAW, LONG_PITCH) if length > LONG * width else (YAW, PITCH)


def framing(low: np.ndarray, high: np.ndarray, aspect: float, fill: float = 0.85) -> float:
    """The orbit camera's distance from the middle of the box (low, high) at which every
    corner of the box is in the view, the box filling `fill` of the view's width or height."""
    centre = (low + high) / 2
    yaw, pitch = angles(low, high)
    back = np.array([math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw),
                     math.sin(pitch)])                   # from the focal point to the camera
    right = np.cross(-back, [0, 0, 1])
    right /= np.linalg.norm(right)
    up = np.cross(right, -back)
    tan_v = math.tan(FIELD_OF_VIEW / 2) * fill
    tan_h = tan_v * aspect
    distance = 0.0
    for corner in np.array(np.meshgrid(*zip(low, high))).T.reshape(-1, 3) - centre:
        # the corner is in the view while its offsets across are within the view's
        # half-angles at its depth, which is distance - corner . back
        distance = max(distance, corner @ back + abs(corner @ right) / tan_h,
                       corner @ back + abs(corner @ up) / tan_v)
    return distance


def rviz_text(robot) -> str:
    """urdf.rviz for `robot`, an `exporter_format.Robot` (not imported here: that module
    imports this one)."""
    root = root_link(robot)
    width, height = view_size()
    aspect = width / height
    low, high = bounds(robot)
    centre = (low + high) / 2
    distance = framing(low, high, aspect)
    yaw, pitch = angles(low, high)
    cell = _grid_cell(float(max(high - low)))
    cells = 2 * math.ceil(1.5 * float(max(high - low)) / cell)
    # A root frame without a body (the lessons' `world`) is the floor; a robot with a body
    # at its root stands on the floor, at the bottom of its meshes.
    root_has_body = any(link.name == root and link.part is not None for link in robot.links)
    floor = float(low[2]) if root_has_body else 0.0
    background = "; ".join(str(c) for c in BACKGROUND)
    window = "".join(f"  {k}: {v}\n" for k, v in WINDOW.items())
    return f"""Panels:
  - Class: rviz/Displays
    Help Height: 78
    Name: Displays
    Property Tree Widget:
      Expanded:
        - /Global Options1
        - /RobotModel1
      Splitter Ratio: 0.5
    Tree Height: 560
  - Class: rviz/Views
    Expanded:
      - /Current View1
    Name: Views
    Splitter Ratio: 0.5
  - Class: rviz/Time
    Name: Time
    SyncMode: 0
    SyncSource: ""
Preferences:
  PromptSaveOnExit: false
Visualization Manager:
  Class: ""
  Displays:
    - Alpha: 0.5
      Cell Size: {_num(cell)}
      Class: rviz/Grid
      Color: 160; 160; 164
      Enabled: true
      Line Style:
        Line Width: 0.03
        Value: Lines
      Name: Grid
      Normal Cell Count: 0
      Offset:
        X: 0
        Y: 0
        Z: {_num(floor)}
      Plane: XY
      Plane Cell Count: {cells}
      Reference Frame: <Fixed Frame>
      Value: true
    - Alpha: 1
      Class: rviz/RobotModel
      Collision Enabled: false
      Enabled: true
      Links:
        All Links Enabled: true
        Expand Joint Details: false
        Expand Link Details: false
        Expand Tree: false
        Link Tree Style: Links in Alphabetic Order
      Name: RobotModel
      Robot Description: robot_description
      TF Prefix: ""
      Update Interval: 0
      Value: true
      Visual Enabled: true
    - Class: rviz/TF
      Enabled: false
      Frame Timeout: 15
      Frames:
        All Enabled: true
      Marker Alpha: 1
      Marker Scale: {_num(cell)}
      Name: TF
      Show Arrows: true
      Show Axes: true
      Show Names: true
      Tree:
        {{}}
      Update Interval: 0
      Value: false
  Enabled: true
  Global Options:
    Background Color: {background}
    Default Light: true
    Fixed Frame: {root}
    Frame Rate: 30
  Name: root
  Tools:
    - Class: rviz/Interact
      Hide Inactive Objects: true
    - Class: rviz/MoveCamera
    - Class: rviz/Select
    - Class: rviz/FocusCamera
    - Class: rviz/Measure
  Value: true
  Views:
    Current:
      Class: rviz/Orbit
      Distance: {_num(distance)}
      Enable Stereo Rendering:
        Stereo Eye Separation: 0.06
        Stereo Focal Distance: 1
        Swap Stereo Eyes: false
        Value: false
      Field of View: {_num(FIELD_OF_VIEW)}
      Focal Point:
        X: {_num(centre[0])}
        Y: {_num(centre[1])}
        Z: {_num(centre[2])}
      Focal Shape Fixed Size: true
      Focal Shape Size: 0.05
      Invert Z Axis: false
      Name: Current View
      Near Clip Distance: 0.01
      Pitch: {_num(pitch)}
      Target Frame: <Fixed Frame>
      Yaw: {_num(yaw)}
    Saved: ~
Window Geometry:
  Displays:
    collapsed: false
{window}  Hide Left Dock: false
  Hide Right Dock: false
  QMainWindow State: {window_state()}
  Time:
    collapsed: false
  Views:
    collapsed: false
"""
