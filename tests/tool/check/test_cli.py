"""The `sw2sim` command: its help, exit statuses, output, and no tracebacks."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
from PIL import Image

from packages import copy_example, edit, urdf_of, zipped
from sw2sim import cli
from sw2sim.commands import view
from sw2sim.check import stability
from test_stability import negative_damping

from repository import ROOT
EXAMPLE_4 = str(ROOT / "examples" / "example_4")
FINDING = re.compile(r"^\S+: (fatal|error|warning)( \([a-zA-Z ']+\))? \[[a-z0-9-]+\] .+\. Fix: .+$")
COMMANDS = ["check", "convert", "view", "render"]


def run(capsys, *argv):
    """Run the command in this process: (exit status, stdout, stderr)."""
    status = cli.main(list(argv))
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return status, out, err


# --- help ------------------------------------------------------------------------------

def test_the_help_lists_every_command_with_examples(capsys):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["--help"])
    out = capsys.readouterr().out
    assert exit_.value.code == 0
    for command in COMMANDS:
        assert re.search(rf"^\s+{command}\s+\S", out, re.M), command
    assert "examples:" in out and "Exit status" in out


@pytest.mark.parametrize("command", COMMANDS)
def test_each_command_has_help_with_examples(capsys, command):
    with pytest.raises(SystemExit) as exit_:
        cli.main([command, "--help"])
    out = capsys.readouterr().out
    assert exit_.value.code == 0
    assert "examples:" in out and f"sw2sim {command} " in out and "PATH" in out


def test_no_command_prints_the_help_and_exits_2(capsys):
    status, out, _ = run(capsys)
    assert status == 2 and "usage: sw2sim" in out


def test_the_installed_command_and_python_m_run_the_same_program(tmp_path):
    command = Path(sys.executable).parent / "sw2sim"
    assert command.exists(), "install with `pip install -e .` (make setup does)"
    for argv in ([str(command), "--help"], [sys.executable, "-m", "sw2sim", "--help"]):
        result = subprocess.run(argv, capture_output=True, text=True, timeout=60, cwd=tmp_path)
        assert result.returncode == 0, result.stderr
        assert "usage: sw2sim" in result.stdout and "convert" in result.stdout


# --- check -----------------------------------------------------------------------------

def test_check_of_a_sound_package_exits_0_with_a_summary(capsys):
    status, out, _ = run(capsys, "check", EXAMPLE_4)
    assert status == 0
    assert out.splitlines()[-1].startswith(f"{EXAMPLE_4}: 0 error(s)")
    assert "stability run: 4.0 s simulated" in out


def test_check_of_a_missing_path_exits_2(capsys, tmp_path):
    status, out, _ = run(capsys, "check", str(tmp_path / "nothing_here"))
    assert status == 2 and "fatal [input-missing]" in out
    assert FINDING.match(out.splitlines()[0])


def test_check_of_a_file_that_is_not_xml_exits_2(capsys, tmp_path):
    package = copy_example(4, tmp_path)
    urdf_of(package).write_text("this is not XML\n")
    status, out, _ = run(capsys, "check", str(package))
    assert status == 2 and "[xml-syntax]" in out


def test_check_of_a_package_with_errors_exits_1_one_line_per_finding(capsys, tmp_path):
    status, out, _ = run(capsys, "check", str(negative_damping(tmp_path)))
    lines = out.splitlines()
    assert status == 1
    assert any("[sim-unstable]" in line for line in lines)
    assert all(FINDING.match(line) for line in lines[:-1]), lines
    assert re.search(r": \d+ error\(s\), \d+ warning\(s\)", lines[-1])


def test_check_json_parses_and_holds_the_findings_and_the_run(capsys, tmp_path):
    status, out, _ = run(capsys, "check", str(negative_damping(tmp_path)), "--json")
    report = json.loads(out)
    assert status == report["status"] == 1
    assert "sim-unstable" in {f["rule"] for f in report["findings"]}
    assert report["stability"]["steps"] < 2000


def test_check_no_sim_skips_the_stability_run(capsys, tmp_path):
    status, out, _ = run(capsys, "check", str(negative_damping(tmp_path)), "--json", "--no-sim")
    report = json.loads(out)
    assert report["stability"] is None and "sim-unstable" not in out


def test_a_crashing_check_gives_a_message_not_a_traceback(capsys, monkeypatch):
    def crash(ctx):
        raise RuntimeError("boom in the stability run")
    monkeypatch.setattr(stability, "check", crash)
    status, out, err = run(capsys, "check", EXAMPLE_4)
    assert status == 2
    assert "unexpected error" in err and "boom in the stability run" in err


# --- convert ---------------------------------------------------------------------------

def test_convert_writes_the_folder_and_says_how_to_open_it(capsys, tmp_path):
    out_dir = tmp_path / "example_4_mujoco"
    status, out, _ = run(capsys, "convert", EXAMPLE_4, "-o", str(out_dir))
    assert status == 0
    assert {p.name for p in out_dir.iterdir()} == {"example_4.xml", "scene.xml", "README.md",
                                                    "assets"}
    assert "python -m mujoco.viewer --mjcf=" in out and "1 actuator(s)" in out


def test_convert_refuses_a_non_empty_folder_and_writes_nothing(capsys, tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    status, _, err = run(capsys, "convert", EXAMPLE_4, "-o", str(tmp_path))
    assert status == 2 and "not empty" in err and "--force" in err
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]


def test_convert_refuses_a_file_as_its_folder(capsys, tmp_path):
    target = tmp_path / "model.xml"
    target.write_text("<mujoco/>")
    status, _, err = run(capsys, "convert", EXAMPLE_4, "-o", str(target))
    assert status == 2 and "is a file" in err
    assert target.read_text() == "<mujoco/>"


def test_force_replaces_only_converts_own_files(capsys, tmp_path):
    (tmp_path / "assets").mkdir()
    (tmp_path / "notes.txt").write_text("mine")
    (tmp_path / "assets" / "mine.stl").write_text("mine too")
    (tmp_path / "scene.xml").write_text("an old scene")
    status, _, _ = run(capsys, "convert", EXAMPLE_4, "-o", str(tmp_path), "--force")
    assert status == 0
    assert (tmp_path / "notes.txt").read_text() == "mine"
    assert (tmp_path / "assets" / "mine.stl").read_text() == "mine too"
    assert "<include" in (tmp_path / "scene.xml").read_text()
    mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))


def test_convert_refuses_a_package_with_errors_and_lists_them(capsys, tmp_path):
    out_dir = tmp_path / "out"
    status, out, err = run(capsys, "convert", str(negative_damping(tmp_path)), "-o", str(out_dir))
    assert status == 1 and "[sim-unstable]" in out and "not converted" in err
    assert not out_dir.exists()


def test_convert_of_a_missing_path_exits_2(capsys, tmp_path):
    status, out, _ = run(capsys, "convert", str(tmp_path / "nope"), "-o", str(tmp_path / "out"))
    assert status == 2 and "[input-missing]" in out


# --- render ----------------------------------------------------------------------------

def test_render_writes_a_picture_of_the_model(capsys, tmp_path):
    picture = tmp_path / "car.png"
    status, out, _ = run(capsys, "render", str(ROOT / "examples" / "example_5"), "-o",
                         str(picture), "--width", "320", "--height", "200", "--azimuth", "150")
    assert status == 0 and f"wrote {picture}" in out
    image = np.asarray(Image.open(picture).convert("RGB")).astype(int)
    assert image.shape == (200, 320, 3)
    assert image.std() > 10, "not a blank picture"
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    orange = (r > 180) & (g > 80) & (g < 180) & (b < 90)
    assert orange.sum() > 50, "the orange wheels are in the picture"


def test_render_keeps_an_existing_file_unless_forced(capsys, tmp_path):
    picture = tmp_path / "block.png"
    picture.write_bytes(b"old")
    status, _, err = run(capsys, "render", EXAMPLE_4, "-o", str(picture))
    assert status == 2 and "--force" in err and picture.read_bytes() == b"old"
    status, _, _ = run(capsys, "render", EXAMPLE_4, "-o", str(picture), "--force",
                       "--width", "64", "--height", "48")
    assert status == 0 and picture.read_bytes()[:4] == b"\x89PNG"


def test_render_of_a_broken_package_writes_nothing(capsys, tmp_path):
    package = copy_example(4, tmp_path)
    edit(urdf_of(package), "<robot", "<robt")
    picture = tmp_path / "block.png"
    status, out, _ = run(capsys, "render", str(package), "-o", str(picture))
    assert status == 2 and "fatal" in out and not picture.exists()


def test_render_rejects_a_silly_size(capsys, tmp_path):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["render", EXAMPLE_4, "-o", str(tmp_path / "x.png"), "--width", "0"])
    assert exit_.value.code == 2 and "outside 16 to 4096" in capsys.readouterr().err


# --- view ------------------------------------------------------------------------------

def test_view_without_a_display_says_what_to_do_instead(capsys, monkeypatch):
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    status, _, err = run(capsys, "view", EXAMPLE_4)
    assert status == 2
    assert "DISPLAY" in err and f"sw2sim render {EXAMPLE_4} -o picture.png" in err
    assert "ssh -X" in err


@pytest.fixture
def viewer(monkeypatch):
    """A display that seems to work, and a viewer that records what it was given."""
    import mujoco.viewer
    shown = []
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setenv("DISPLAY", ":0")
    monkeypatch.setenv("MUJOCO_GL", os.environ.get("MUJOCO_GL", "osmesa"))
    monkeypatch.setattr(view, "_glfw_starts", lambda: True)
    monkeypatch.setattr(mujoco.viewer, "launch", lambda model, *a, **k: shown.append(model))
    return shown


def test_view_opens_example_4_with_the_slider_the_practice_4_page_describes(capsys, viewer):
    status, _, _ = run(capsys, "view", EXAMPLE_4)
    assert status == 0 and len(viewer) == 1
    assert os.environ["MUJOCO_GL"] == "glfw", "the viewer's GL platform is chosen"
    model = viewer[0]
    servo = model.actuator("block_controller")
    assert model.nu == 1
    assert servo.ctrlrange.tolist() == pytest.approx([0.0, 2.69])
    assert servo.gainprm[0] == 2000 and servo.biasprm[2] == -200
    page = (ROOT / "_pages/practice-4/04-testing-and-scripting.md").read_text()
    for claim in ("sw2sim view examples/example_4", "`block_controller`",
                  "(kp 2000 N/m, kv 200 N·s/m)", "0 to 2.69 m"):
        assert claim in page, claim


def test_view_gives_every_joint_a_slider_where_the_package_has_no_actuators(capsys, viewer):
    status, _, _ = run(capsys, "view", str(ROOT / "examples" / "example_1"))
    model = viewer[0]
    assert status == 0 and model.nu == model.njnt == 4, "four wheels, four sliders"
    assert all(model.actuator_ctrllimited), "each slider has a range"


def test_view_on_a_display_that_does_not_work_exits_2_with_a_message(tmp_path):
    env = dict(os.environ, DISPLAY=":77", PYTHONPATH="")
    env.pop("WAYLAND_DISPLAY", None)
    result = subprocess.run([sys.executable, "-m", "sw2sim", "view", EXAMPLE_4],
                            capture_output=True, text=True, timeout=120, cwd=tmp_path, env=env)
    assert result.returncode == 2, result.stderr
    assert "no window can open on display :77" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()


def test_a_reader_that_stops_early_ends_the_command_quietly(tmp_path):
    """`sw2sim check PATH | head -1`: the command stops at the closed pipe with the status a
    shell gives such a command, and says nothing of a fault."""
    package = copy_example(3, tmp_path)
    edit(urdf_of(package), 'effort="', 'effort="-', count=2)   # two findings, two lines
    read, write = os.pipe()
    os.close(read)    # the reader is gone before the first line is written
    try:
        done = subprocess.run([sys.executable, "-m", "sw2sim", "check", str(package), "--no-sim"],
                              stdout=write, stderr=subprocess.PIPE, text=True, timeout=60)
    finally:
        os.close(write)
    assert done.returncode == cli.EXIT_BROKEN_PIPE, done.stderr
    assert done.stderr == ""


def test_several_packages_are_checked_in_turn_with_a_line_for_them_all(tmp_path, capsys,
                                                                      monkeypatch):
    """`sw2sim check submissions/*.zip`: each its report, then one line; the worst status."""
    import tempfile
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    sound = copy_example(4, tmp_path / "a")
    broken = copy_example(3, tmp_path / "b")
    edit(urdf_of(broken), 'effort="', 'effort="-')
    student = zipped(sound, tmp_path / "student.zip")
    status, out, _ = run(capsys, "check", str(sound), str(broken), str(student),
                         str(tmp_path / "missing"), "--no-sim")
    assert status == 2, "the worst of 0, 1, 0 and 2"
    summaries = [line for line in out.splitlines() if re.search(r": \d+ error\(s\), ", line)]
    assert len(summaries) == 4
    assert out.rstrip().endswith("4 packages checked: 2 without errors, 1 with errors, "
                                 "1 that could not be used")
    assert list((tmp_path / "tmp").iterdir()) == [], "each unpacked zip goes after its check"

    status, out, _ = run(capsys, "check", str(sound), str(broken), "--json", "--no-sim")
    reports = json.loads(out)
    assert [r["status"] for r in reports] == [0, 1] and status == 1

    status, _, err = run(capsys, "check", str(sound), str(broken), "--urdf", "example_3.urdf")
    assert status == 2 and "give one PATH with it" in err
