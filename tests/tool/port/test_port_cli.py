"""`sw2sim port` as a command: exit codes, messages, the output folder rules, the source
left untouched."""

from __future__ import annotations

import hashlib

from packages import copy_example, zipped
from sw2sim.cli import main


def _tree_hash(folder):
    digest = hashlib.sha256()
    for path in sorted(folder.rglob("*")):
        digest.update(path.relative_to(folder).as_posix().encode())
        if path.is_file():
            digest.update(path.read_bytes())
    return digest.hexdigest()


def test_port_writes_and_exits_0_leaving_the_source_untouched(tmp_path, capsys):
    src = copy_example(5, tmp_path / "src")
    before = _tree_hash(src)
    assert main(["port", str(src), "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "choice(s) made for you" in out and "wrote" in out
    assert "bicycle" not in out and "pid_controller/PidController" in out
    assert "scripts/ was not ported" in out
    assert _tree_hash(src) == before
    assert (tmp_path / "out" / "urdf" / "example_5.urdf").is_file()


def test_a_missing_path_exits_2_naming_it(tmp_path, capsys):
    assert main(["port", str(tmp_path / "nothing"), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "sw2sim port:" in err and "nothing" in err and "no such file or folder" in err
    assert not (tmp_path / "out").exists()


def test_a_non_empty_output_is_refused_and_an_earlier_port_replaced_keeping_own_files(tmp_path, capsys):
    src = copy_example(3, tmp_path / "src")
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("keep me")
    assert main(["port", str(src), "-o", str(out)]) == 2
    assert "not empty" in capsys.readouterr().err
    assert [p.name for p in out.iterdir()] == ["mine.txt"]
    (out / "mine.txt").unlink()
    assert main(["port", str(src), "-o", str(out)]) == 0
    assert main(["port", str(src), "-o", str(out), "--name", "arm"]) == 0
    assert "replaced the earlier port" in capsys.readouterr().out
    assert (out / "urdf" / "arm.urdf").is_file() and not (out / "urdf" / "example_3.urdf").exists()
    (out / "notes.md").write_text("mine")
    assert main(["port", str(src), "-o", str(out)]) == 0
    assert "kept your files, which the port does not write: notes.md" in \
        capsys.readouterr().out
    assert (out / "notes.md").read_text() == "mine"
    assert (out / "urdf" / "example_3.urdf").is_file() and not (out / "urdf" / "arm.urdf").exists()


WHEELS = "front_left_joint,front_right_joint,rear_left_joint,rear_right_joint"


def test_porting_again_keeps_the_readers_node_and_edits(tmp_path, capsys):
    """Practice 1's ROS 2 page has the reader save scripts/wheel_pulse.py in the port and add
    lines to its CMakeLists.txt and package.xml; Practice 2's page ports example_1 again
    into the same folder. The second port keeps all three, and says so."""
    src = copy_example(1, tmp_path / "src")
    out = tmp_path / "ws" / "src" / "example_1"
    assert main(["port", str(src), "-o", str(out), "--effort-joints", WHEELS]) == 0
    capsys.readouterr()
    node = out / "scripts" / "wheel_pulse.py"
    node.parent.mkdir()
    node.write_text("#!/usr/bin/env python3\n")
    node.chmod(0o755)
    (out / "scripts" / "empty").mkdir()
    cmake = out / "CMakeLists.txt"
    edited = cmake.read_text().replace(
        "ament_package()", "install(PROGRAMS scripts/wheel_pulse.py\n  DESTINATION "
        "lib/${PROJECT_NAME})\n\nament_package()")
    cmake.write_text(edited)
    assert main(["port", str(src), "-o", str(out), "--effort-joints", WHEELS]) == 0
    printed = capsys.readouterr().out
    assert "kept your files, which the port does not write: scripts/wheel_pulse.py" in printed
    assert "kept as you changed them: CMakeLists.txt" in printed
    assert node.read_text() == "#!/usr/bin/env python3\n" and node.stat().st_mode & 0o111
    assert (out / "scripts" / "empty").is_dir()
    assert cmake.read_text() == edited
    # a port that writes a changed file differently: the new one in place, the reader's aside
    yaml = out / "config" / "controllers.yaml"
    yaml.write_text(yaml.read_text() + "# mine\n")
    assert main(["port", str(src), "-o", str(out)]) == 0   # no effort joints: another YAML
    printed = capsys.readouterr().out
    assert "config/controllers.yaml: you had changed it" in printed
    assert "config/controllers.yaml.mine" in printed
    assert (out / "config" / "controllers.yaml.mine").read_text().endswith("# mine\n")
    assert "effort_controller" not in yaml.read_text()
    assert cmake.read_text() == edited and node.is_file()
    # a port's file the reader did not change is replaced, and one it no longer writes goes
    assert main(["port", str(src), "-o", str(out), "--effort-joints", WHEELS]) == 0
    assert "effort_controller" in yaml.read_text()
    assert (out / "config" / "controllers.yaml.mine").is_file()


def test_output_inside_the_source_is_refused(tmp_path, capsys):
    src = copy_example(3, tmp_path / "src")
    before = _tree_hash(src)
    assert main(["port", str(src), "-o", str(src / "ros2")]) == 2
    assert "inside the source package" in capsys.readouterr().err
    assert _tree_hash(src) == before


def test_a_zip_is_ported_and_bad_options_exit_2(tmp_path, capsys):
    archive = zipped(copy_example(4, tmp_path / "src"), tmp_path / "example_4.zip")
    assert main(["port", str(archive), "-o", str(tmp_path / "out")]) == 0
    assert "example_4.zip" in capsys.readouterr().out
    assert main(["port", str(archive), "-o", str(tmp_path / "o2"), "--name", "Bad.Name"]) == 2
    assert "bad_name" in capsys.readouterr().err
    assert main(["port", str(archive), "-o", str(tmp_path / "o3"),
                 "--effort-joints", "block_joint,ghost"]) == 2
    err = capsys.readouterr().err
    assert "ghost" in err and "block_joint" in err
