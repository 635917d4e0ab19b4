"""The SolidWorks-to-URDF exporter's windows, as its source lays them out: the data the
schematics of course/dialog_schematics.py are drawn from.

Nothing here is typed from a screenshot. `ASSEMBLY_FORM` holds every control of the
assembly export window (steps 2 and 3 of an export) with the position, size and text
SW2URDF/UI/AssemblyExportForm.Designer.cs gives it, and the line that sets the text.
`PROPERTY_MANAGER` holds the panel of step 1 in the order
SW2URDF/URDFExport/ExportPropertyManager.cs adds its controls, with each caption and
tooltip and its line. Both were read from ros/solidworks_urdf_exporter at `COMMIT`.

The exporter's source is not part of this repository. With a copy of it,
`python -m course.exporter_dialogs PATH` (PATH: a bare clone or a work tree) prints
`ASSEMBLY_FORM` afresh from Designer.cs, and tests/course/test_reference_exporter_dialogs.py
checks both lists against it.
"""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

REPOSITORY = "ros/solidworks_urdf_exporter"
# The source's HEAD when these were read (after release 1.6.1).
COMMIT = "25da24a2095bd3279b3c5c7efe14303333b986f6"
DESIGNER = "SW2URDF/UI/AssemblyExportForm.Designer.cs"
PROPERTY_MANAGER_SOURCE = "SW2URDF/URDFExport/ExportPropertyManager.cs"
MIRROR = Path("/work/.mirror/ros+solidworks_urdf_exporter/repo")   # where a copy may be


@dataclass(frozen=True)
class Control:
    """One Windows Forms control of the assembly export window, in the window's pixels."""

    name: str            # the field's name in Designer.cs
    kind: str            # Label, TextBox, ComboBox, Button, GroupBox, RadioButton, ...
    parent: str          # "form" or the panel or group box it sits in
    x: int
    y: int
    w: int
    h: int
    text: str = ""       # its Text as the Designer sets it ("" when none)
    line: int = 0        # the line of Designer.cs that sets the text
    hidden: bool = False  # Visible = false: shown only later (the mimic fields)
    bold: bool = False
    checked: bool = False


@dataclass(frozen=True)
class PanelControl:
    """One control of the property manager panel (step 1), in the order the source adds it."""

    kind: str            # Label, Textbox, Combobox, Selectionbox, Numberbox, Button, Checkbox, Tree
    caption: str         # the caption the source passes ("" when none)
    tip: str             # its tooltip ("" when none)
    line: int            # the line of ExportPropertyManager.cs that sets the caption (the
                         # tooltip is set in the same block, a few lines on)
    # "always"; "root" with the root link selected; "child" with any other link;
    # "loaded" after Load Configuration... has read a CSV file
    shown: str
    added: bool = True   # False: the source sets the caption but never adds the control


# --- step 1: the panel beside the feature tree (ExportPropertyManager.cs, SetupPropertyManagerPage)
# Since release 1.6.0 (#106) the labels "Parent Link", "Link Name", "Link Components" and
# "Number of child links" are no longer added to the panel: their captions are still set, and
# the boxes under them carry the same words as tooltips.
PROPERTY_MANAGER_TITLE = ("URDF Exporter", 149)
PROPERTY_MANAGER = [
    PanelControl("Group", "Configure and Organize Links", "", 703, "always"),
    PanelControl("Label", "Parent Link", "", 710, "always", added=False),
    PanelControl("Label", "", "", 717, "always"),    # the parent's name, filled in by the panel
    PanelControl("Label", "Link Name", "Enter the name of the link", 725, "always", added=False),
    PanelControl("Textbox", "base_link", "Enter the name of the link", 733, "always"),
    PanelControl("Label", "Joint Name", "Enter the name of the joint", 743, "child"),
    PanelControl("Textbox", "", "Enter the name of the joint", 752, "child"),
    PanelControl("Label", "Global Origin Coordinate System",
                 "Select the reference coordinate system for the global origin", 761, "root"),
    PanelControl("Combobox", "Global Origin Coordinate System Name",
                 "Select the reference coordinate system for the global origin", 770, "root"),
    PanelControl("Label", "Reference Coordinate System",
                 "Select the reference coordinate system for the joint origin", 781, "child"),
    PanelControl("Combobox", "Reference Coordinate System Name",
                 "Select the reference coordinate system for the joint origin", 790, "child"),
    PanelControl("Label", "Reference Axis", "Select the reference axis for the joint", 801, "child"),
    PanelControl("Combobox", "Reference Axis Name", "Select the reference axis for the joint", 810, "child"),
    PanelControl("Label", "Joint Type", "Select the joint type", 821, "child"),
    PanelControl("Combobox", "Joint type", "Select the joint type", 830, "child"),
    PanelControl("Label", "Link Components", "Select components associated with this link", 843, "always",
                 added=False),
    PanelControl("Selectionbox", "Link Components", "Select components associated with this link", 851, "always"),
    PanelControl("Label", "Number of child links",
                 "Enter the number of child links and they will be automatically added", 872, "always",
                 added=False),
    PanelControl("Numberbox", "", "Enter the number of child links and they will be automatically added",
                 880, "always"),
    PanelControl("Button", "Load Configuration...", "Import values from a CSV file", 893, "always"),
    PanelControl("Label", "Imported File: ", "", 904, "loaded"),
    PanelControl("Checkbox", "Compute Mass and Inertia", "", 913, "loaded"),
    PanelControl("Checkbox", "Compute Visual and Collision", "", 922, "loaded"),
    PanelControl("Checkbox", "Compute Joint Kinematics", "", 931, "loaded"),
    PanelControl("Checkbox", "Compute Joint Limits", "", 940, "loaded"),
    PanelControl("Button", "Preview and Export...", "Preview the generated URDF and export to a URDF package",
                 952, "always"),
    PanelControl("Tree", "Link Tree", "", 956, "always"),
]
# The choices of the joint type box (line 839) and the tree's right-click menu (lines 982, 985).
JOINT_TYPES = (["Automatically Detect", "continuous", "revolute", "prismatic", "fixed"], 839)
TREE_MENU = [("Add Child Link", 982), ("Remove", 985)]


def property_manager_strings() -> dict[str, int]:
    """Every text of the panel the source holds: caption or tooltip -> the line of the block
    that sets it."""
    out = {PROPERTY_MANAGER_TITLE[0]: PROPERTY_MANAGER_TITLE[1]}
    for c in PROPERTY_MANAGER:
        for text in (c.caption, c.tip):
            if text:
                out.setdefault(text, c.line)
    for choice in JOINT_TYPES[0]:
        out[choice] = JOINT_TYPES[1]
    out.update(TREE_MENU)
    return out


# --- steps 2 and 3: the assembly export window (AssemblyExportForm.Designer.cs) ---------------

FORM_TITLE = ("SolidWorks Assembly to URDF Exporter", 1707)   # the window's title bar

_NEW = re.compile(r"this\.(\w+) = new System\.Windows\.Forms\.(\w+)\(\);")
_ADD = re.compile(r"this\.(?:(\w+)\.)?Controls\.Add\(this\.(\w+)\);")
_AT = re.compile(r"this\.(\w+)\.Location = new System\.Drawing\.Point\((-?\d+), (-?\d+)\);")
_SIZE = re.compile(r"this\.(\w+)\.Size = new System\.Drawing\.Size\((\d+), (\d+)\);")
_TEXT = re.compile(r'this\.(\w+)\.Text = "(.*)";$')
_FLAG = re.compile(r"this\.(\w+)\.(Visible = false|Checked = true|Font = .*FontStyle\.Bold)")


def read_designer(text: str) -> list[Control]:
    """The controls a Designer.cs file sets up, in the order it creates them."""
    kinds, parents, fields, order = {}, {}, {}, []
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if m := _NEW.match(s):
            kinds[m[1]] = m[2]
            order.append(m[1])
            fields[m[1]] = {}
        elif m := _ADD.match(s):
            parents[m[2]] = m[1] or "form"
        elif m := _AT.match(s):
            fields[m[1]].update(x=int(m[2]), y=int(m[3]))
        elif m := _SIZE.match(s):
            fields[m[1]].update(w=int(m[2]), h=int(m[3]))
        elif m := _TEXT.match(s):
            fields[m[1]].update(text=m[2].replace("\\'", "'").replace('\\"', '"'), line=n)
        elif m := _FLAG.match(s):
            flag = m[2].split()[0]
            key = {"Visible": "hidden", "Checked": "checked", "Font": "bold"}[flag]
            fields[m[1]][key] = True
    return [Control(name, kinds[name], parents.get(name, ""), **fields[name])
            for name in order if "x" in fields[name] and name in parents]


def read_source(path: Path, file: str) -> str:
    """A file of the exporter's source from a work tree, or from a bare clone's HEAD."""
    if (path / file).is_file():
        return (path / file).read_text(encoding="utf-8-sig")
    out = subprocess.run(["git", "-C", str(path), "show", f"HEAD:{file}"], check=True,
                         capture_output=True)
    return out.stdout.decode("utf-8-sig")


def children(parent: str) -> list[Control]:
    return [c for c in ASSEMBLY_FORM if c.parent == parent]


def main(argv: list[str]) -> int:
    path = Path(argv[0]) if argv else MIRROR
    print("ASSEMBLY_FORM = [")
    for c in read_designer(read_source(path, DESIGNER)):
        extra = "".join(f", {k}={getattr(c, k)!r}" for k in ("text", "line", "hidden", "bold", "checked")
                        if getattr(c, k) != Control.__dataclass_fields__[k].default)
        print(f"    Control({c.name!r}, {c.kind!r}, {c.parent!r}, {c.x}, {c.y}, {c.w}, {c.h}{extra}),")
    print("]")
    return 0


# Generated by `python -m course.exporter_dialogs` from Designer.cs at COMMIT.
ASSEMBLY_FORM = [
    Control('panelLinkProperties', 'Panel', 'form', 0, 0, 1073, 634, hidden=True),
    Control('buttonLinksExportUrdfOnly', 'Button', 'panelLinkProperties', 759, 603, 150, 21, text='Export URDF Only...', line=218),
    Control('label2', 'Label', 'panelLinkProperties', 22, 31, 308, 12, text="Use this page to make any changes to the links' properties", line=229),
    Control('label5', 'Label', 'panelLinkProperties', 12, 8, 193, 17, text='Configure Link Properties', line=239, bold=True),
    Control('buttonLinksFinish', 'Button', 'panelLinkProperties', 914, 603, 150, 21, text='Export URDF and Meshes...', line=248),
    Control('buttonLinksPrevious', 'Button', 'panelLinkProperties', 509, 603, 75, 21, text='Previous', line=259),
    Control('buttonLinksCancel', 'Button', 'panelLinkProperties', 12, 603, 75, 21, text='Cancel', line=270),
    Control('groupBox5', 'GroupBox', 'panelLinkProperties', 494, 80, 568, 180),
    Control('label15', 'Label', 'groupBox5', 6, 0, 46, 13, text='Inertial', line=321, bold=True),
    Control('textBoxIxx', 'TextBox', 'groupBox5', 273, 54, 66, 20),
    Control('textBoxIxz', 'TextBox', 'groupBox5', 472, 54, 66, 20),
    Control('textBoxInertialOriginX', 'TextBox', 'groupBox5', 44, 54, 66, 20),
    Control('label16', 'Label', 'groupBox5', 118, 58, 25, 13, text='Roll', line=351),
    Control('textBoxInertialOriginYaw', 'TextBox', 'groupBox5', 150, 102, 66, 20),
    Control('label11', 'Label', 'groupBox5', 447, 54, 19, 13, text='ixz', line=367),
    Control('label12', 'Label', 'groupBox5', 7, 149, 53, 13, text='Mass (kg)', line=376),
    Control('textBoxIyy', 'TextBox', 'groupBox5', 369, 78, 66, 20),
    Control('textBoxInertialOriginPitch', 'TextBox', 'groupBox5', 150, 78, 66, 20),
    Control('label13', 'Label', 'groupBox5', 26, 54, 12, 13, text='x', line=399),
    Control('label14', 'Label', 'groupBox5', 248, 54, 19, 13, text='ixx', line=408),
    Control('textBoxInertialOriginRoll', 'TextBox', 'groupBox5', 150, 54, 66, 20),
    Control('textBoxInertialOriginY', 'TextBox', 'groupBox5', 44, 78, 66, 20),
    Control('label17', 'Label', 'groupBox5', 26, 78, 12, 13, text='y', line=431),
    Control('label18', 'Label', 'groupBox5', 447, 106, 19, 13, text='izz', line=440),
    Control('textBoxIyz', 'TextBox', 'groupBox5', 472, 78, 66, 20),
    Control('label36', 'Label', 'groupBox5', 7, 20, 51, 13, text='Origin (m)', line=456),
    Control('label44', 'Label', 'groupBox5', 235, 20, 144, 13, text='Moment of Inertia (Kg * m^-2)', line=465),
    Control('label45', 'Label', 'groupBox5', 113, 82, 31, 13, text='Pitch', line=474),
    Control('label46', 'Label', 'groupBox5', 116, 106, 28, 13, text='Yaw', line=483),
    Control('textBoxInertialOriginZ', 'TextBox', 'groupBox5', 44, 102, 66, 20),
    Control('label47', 'Label', 'groupBox5', 26, 102, 12, 13, text='z', line=499),
    Control('label48', 'Label', 'groupBox5', 447, 80, 19, 13, text='iyz', line=508),
    Control('label49', 'Label', 'groupBox5', 344, 82, 19, 13, text='iyy', line=517),
    Control('textBoxIxy', 'TextBox', 'groupBox5', 369, 54, 66, 20),
    Control('textBoxIzz', 'TextBox', 'groupBox5', 472, 102, 66, 20),
    Control('label50', 'Label', 'groupBox5', 344, 54, 19, 13, text='ixy', line=540),
    Control('textBoxMass', 'TextBox', 'groupBox5', 65, 149, 66, 20),
    Control('groupBox4', 'GroupBox', 'panelLinkProperties', 494, 278, 568, 305),
    Control('groupBox1', 'GroupBox', 'groupBox4', 184, 147, 122, 90, text='Mesh Format', line=599),
    Control('radioButton3dxml', 'RadioButton', 'groupBox1', 11, 54, 90, 16, text='3dxml (color)', line=609),
    Control('radioButtonStl', 'RadioButton', 'groupBox1', 11, 24, 104, 16, text='STL (grayscale)', line=621, checked=True),
    Control('radioButtonFine', 'RadioButton', 'groupBox4', 101, 171, 45, 16, text='Fine', line=631),
    Control('radioButtonCourse', 'RadioButton', 'groupBox4', 20, 171, 59, 16, text='Course', line=643, checked=True),
    Control('label10', 'Label', 'groupBox4', 7, 147, 66, 12, text='Mesh Detail', line=653),
    Control('label19', 'Label', 'groupBox4', 3, 0, 164, 13, text='Visual and Collision Meshes', line=663, bold=True),
    Control('textBoxVisualOriginZ', 'TextBox', 'groupBox4', 41, 103, 66, 19),
    Control('textBoxVisualOriginYaw', 'TextBox', 'groupBox4', 148, 103, 66, 19),
    Control('label34', 'Label', 'groupBox4', 7, 254, 134, 12, text='Texture (Replaces Color)', line=686),
    Control('textBoxVisualOriginPitch', 'TextBox', 'groupBox4', 148, 79, 66, 19),
    Control('buttonTextureBrowse', 'Button', 'groupBox4', 398, 276, 75, 21, text='Browse...', line=701),
    Control('label28', 'Label', 'groupBox4', 7, 201, 77, 12, text='Material name', line=712),
    Control('textBoxVisualOriginRoll', 'TextBox', 'groupBox4', 148, 55, 66, 19),
    Control('comboBoxMaterials', 'ComboBox', 'groupBox4', 16, 225, 121, 20),
    Control('label26', 'Label', 'groupBox4', 22, 55, 11, 12, text='x', line=736),
    Control('label20', 'Label', 'groupBox4', 114, 103, 26, 12, text='Yaw', line=745),
    Control('domainUpDownAlpha', 'DomainUpDown', 'groupBox4', 412, 130, 60, 19, text='1', line=753),
    Control('label29', 'Label', 'groupBox4', 365, 30, 32, 12, text='Color', line=762),
    Control('label25', 'Label', 'groupBox4', 22, 79, 11, 12, text='y', line=771),
    Control('label21', 'Label', 'groupBox4', 111, 79, 31, 12, text='Pitch', line=780),
    Control('label33', 'Label', 'groupBox4', 372, 132, 34, 12, text='Alpha', line=789),
    Control('domainUpDownRed', 'DomainUpDown', 'groupBox4', 412, 56, 60, 19, text='1', line=797),
    Control('label24', 'Label', 'groupBox4', 22, 103, 10, 12, text='z', line=806),
    Control('label22', 'Label', 'groupBox4', 117, 55, 25, 12, text='Roll', line=815),
    Control('label32', 'Label', 'groupBox4', 378, 108, 28, 12, text='Blue', line=824),
    Control('domainUpDownGreen', 'DomainUpDown', 'groupBox4', 412, 82, 60, 19, text='1', line=832),
    Control('textBoxVisualOriginX', 'TextBox', 'groupBox4', 41, 55, 66, 19),
    Control('label31', 'Label', 'groupBox4', 370, 84, 35, 12, text='Green', line=848),
    Control('domainUpDownBlue', 'DomainUpDown', 'groupBox4', 412, 106, 60, 19, text='1', line=856),
    Control('label23', 'Label', 'groupBox4', 7, 30, 56, 12, text='Origin (m)', line=865),
    Control('textBoxVisualOriginY', 'TextBox', 'groupBox4', 41, 79, 66, 19),
    Control('label30', 'Label', 'groupBox4', 379, 58, 25, 12, text='Red', line=881),
    Control('textBoxTexture', 'TextBox', 'groupBox4', 16, 278, 352, 19),
    Control('treeViewLinkProperties', 'TreeView', 'panelLinkProperties', 12, 74, 451, 525),
    Control('buttonJointNext', 'Button', 'form', 986, 603, 75, 21, text='Next', line=909),
    Control('buttonJointCancel', 'Button', 'form', 12, 603, 75, 21, text='Cancel', line=920),
    Control('label7', 'Label', 'form', 12, 8, 198, 17, text='Configure Joint Properties', line=932, bold=True),
    Control('label6', 'Label', 'form', 633, 264, 89, 12, text='Orientation (rad)', line=941),
    Control('label3', 'Label', 'form', 528, 264, 67, 12, text='Position (m)', line=950),
    Control('textBoxKVelocity', 'TextBox', 'form', 955, 498, 66, 19),
    Control('labelKVelocity', 'Label', 'form', 897, 501, 55, 12, text='k velocity', line=966),
    Control('textBoxSoftLower', 'TextBox', 'form', 955, 425, 66, 19),
    Control('labelSoftLower', 'Label', 'form', 854, 427, 110, 12, text='soft lower limit (rad)', line=982),
    Control('textBoxSoftUpper', 'TextBox', 'form', 955, 450, 66, 19),
    Control('labelSoftUpper', 'Label', 'form', 850, 453, 111, 12, text='soft upper limit (rad)', line=998),
    Control('label80', 'Label', 'form', 952, 398, 101, 13, text='Safety Controller', line=1008, bold=True),
    Control('textBoxKPosition', 'TextBox', 'form', 955, 474, 66, 19),
    Control('labelKPosition', 'Label', 'form', 897, 477, 55, 12, text='k position', line=1024),
    Control('textBoxFriction', 'TextBox', 'form', 766, 425, 66, 19),
    Control('labelFriction', 'Label', 'form', 694, 427, 76, 12, text='friction (N*m)', line=1040),
    Control('textBoxDamping', 'TextBox', 'form', 766, 449, 66, 19),
    Control('labelDamping', 'Label', 'form', 642, 451, 133, 12, text='damping (N*m*s*rad^-1)', line=1056),
    Control('label76', 'Label', 'form', 764, 394, 61, 13, text='Dynamics', line=1066, bold=True),
    Control('textBoxCalibrationRising', 'TextBox', 'form', 531, 425, 66, 19),
    Control('label7CalibrationRising', 'Label', 'form', 494, 427, 33, 12, text='rising', line=1082),
    Control('textBoxCalibrationFalling', 'TextBox', 'form', 531, 449, 66, 19),
    Control('label73', 'Label', 'form', 490, 451, 36, 12, text='falling', line=1098),
    Control('label74', 'Label', 'form', 528, 394, 67, 13, text='Calibration', line=1108, bold=True),
    Control('textBoxLimitVelocity', 'TextBox', 'form', 955, 350, 66, 19),
    Control('labelVelocity', 'Label', 'form', 879, 352, 78, 12, text='velocity (m/s)', line=1124),
    Control('textBoxLimitLower', 'TextBox', 'form', 955, 278, 66, 19),
    Control('labelLowerLimit', 'Label', 'form', 893, 280, 60, 12, text='lower (rad)', line=1140),
    Control('textBoxLimitUpper', 'TextBox', 'form', 955, 302, 66, 19),
    Control('labelLimitUpper', 'Label', 'form', 891, 305, 61, 12, text='upper (rad)', line=1156),
    Control('label68', 'Label', 'form', 952, 248, 33, 13, text='Limit', line=1166, bold=True),
    Control('textBoxLimitEffort', 'TextBox', 'form', 955, 326, 66, 19),
    Control('labelEffort', 'Label', 'form', 890, 328, 68, 12, text='effort (N-m)', line=1182),
    Control('label65', 'Label', 'form', 519, 98, 56, 13, text='Child Link:', line=1192),
    Control('label64', 'Label', 'form', 512, 74, 64, 13, text='Parent Link:', line=1202),
    Control('label63', 'Label', 'form', 513, 120, 60, 13, text='Joint Name', line=1212),
    Control('textBoxJointName', 'TextBox', 'form', 537, 137, 295, 19),
    Control('label62', 'Label', 'form', 854, 122, 56, 13, text='Joint Type', line=1229),
    Control('comboBoxJointType', 'ComboBox', 'form', 890, 138, 121, 20),
    Control('textBoxAxisX', 'TextBox', 'form', 766, 280, 66, 19),
    Control('label58', 'Label', 'form', 749, 280, 11, 12, text='x', line=1260),
    Control('textBoxAxisY', 'TextBox', 'form', 766, 304, 66, 19),
    Control('label59', 'Label', 'form', 749, 306, 11, 12, text='y', line=1276),
    Control('label60', 'Label', 'form', 764, 248, 30, 13, text='Axis', line=1286, bold=True),
    Control('textBoxAxisZ', 'TextBox', 'form', 766, 328, 66, 19),
    Control('label61', 'Label', 'form', 749, 330, 10, 12, text='z', line=1302),
    Control('textBoxJointX', 'TextBox', 'form', 530, 280, 66, 19),
    Control('label51', 'Label', 'form', 606, 283, 25, 12, text='Roll', line=1318),
    Control('textBoxJointYaw', 'TextBox', 'form', 638, 328, 66, 19),
    Control('textBoxJointPitch', 'TextBox', 'form', 638, 304, 66, 19),
    Control('label52', 'Label', 'form', 512, 280, 11, 12, text='x', line=1341),
    Control('textBoxJointRoll', 'TextBox', 'form', 638, 280, 66, 19),
    Control('textBoxJointY', 'TextBox', 'form', 530, 304, 66, 19),
    Control('label53', 'Label', 'form', 512, 306, 11, 12, text='y', line=1364),
    Control('label54', 'Label', 'form', 528, 248, 40, 13, text='Origin', line=1374, bold=True),
    Control('label55', 'Label', 'form', 602, 307, 31, 12, text='Pitch', line=1383),
    Control('label56', 'Label', 'form', 604, 330, 26, 12, text='Yaw', line=1392),
    Control('textBoxJointZ', 'TextBox', 'form', 530, 328, 66, 19),
    Control('label57', 'Label', 'form', 513, 330, 10, 12, text='z', line=1408),
    Control('labelChild', 'Label', 'form', 574, 98, 0, 12),
    Control('labelParent', 'Label', 'form', 574, 74, 0, 12),
    Control('treeViewJointTree', 'TreeView', 'form', 12, 74, 462, 525),
    Control('comboBoxAxis', 'ComboBox', 'form', 570, 209, 468, 20),
    Control('comboBoxOrigin', 'ComboBox', 'form', 570, 176, 468, 20),
    Control('label66', 'Label', 'form', 501, 178, 66, 12, text='Coordinates', line=1460),
    Control('label67', 'Label', 'form', 538, 211, 28, 12, text='Axis', line=1469),
    Control('label69', 'Label', 'form', 22, 31, 451, 50),
    Control('label4', 'Label', 'form', 521, 603, 263, 12, text='Entries that are blank will not be written to URDF.', line=1488),
    Control('label1', 'Label', 'form', 562, 248, 12, 13, text='*', line=1499, bold=True),
    Control('AxisRequiredLabel', 'Label', 'form', 788, 248, 12, 13, text='*', line=1510, bold=True),
    Control('LimitRequiredLabel', 'Label', 'form', 980, 247, 12, 13, text='*', line=1521, hidden=True, bold=True),
    Control('label27', 'Label', 'form', 521, 617, 130, 12, text='* Field group is required', line=1532),
    Control('MimicCheckBox', 'CheckBox', 'form', 530, 535, 116, 16, text='Mimic Other Joint', line=1542),
    Control('MimicJointComboBox', 'ComboBox', 'form', 532, 572, 158, 20, hidden=True),
    Control('MimicJointLabel', 'Label', 'form', 530, 558, 89, 13, text='Joint to Mimic:', line=1565, hidden=True, bold=True),
    Control('textBoxMimicMultiplier', 'TextBox', 'form', 766, 554, 66, 19, hidden=True),
    Control('textBoxMimicOffset', 'TextBox', 'form', 766, 574, 66, 19, hidden=True),
    Control('MimicMultiplierLabel', 'Label', 'form', 704, 553, 52, 12, text='Multiplier', line=1593, hidden=True),
    Control('MimicOffsetLabel', 'Label', 'form', 698, 574, 65, 12, text='Offset (rad)', line=1604, hidden=True),
    Control('MimicEquationLabel', 'Label', 'form', 846, 574, 171, 13, text='pos = multiplier * pos_other + offset', line=1616, hidden=True),
]


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
