"""The command line's shape: one module per command under sw2sim/commands/, named in one
table, imported only when its command runs; a mistyped command gets the closest name."""

from __future__ import annotations

import subprocess
import sys

import pytest

from sw2sim import cli, commands


@pytest.mark.parametrize("name", sorted(commands.COMMANDS))
def test_each_command_has_its_help_options_and_entry_point(name, capsys):
    module = commands.module(name)
    assert module.HELP.strip() and "examples:" in module.HELP
    assert callable(module.add_arguments) and callable(module.run)
    with pytest.raises(SystemExit) as ended:
        cli.main([name, "--help"])
    assert ended.value.code == 0
    shown = capsys.readouterr().out
    assert shown.startswith(f"usage: sw2sim {name}")
    assert module.HELP.splitlines()[0] in shown


def test_the_top_level_help_lists_every_command_with_its_summary(capsys):
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    shown = " ".join(capsys.readouterr().out.split())
    for name, (_, summary) in commands.COMMANDS.items():
        assert f"{name} {' '.join(summary.split())}" in shown, name


def test_a_mistyped_command_is_named_with_the_closest_one(capsys):
    assert cli.main(["chek", "examples/example_4"]) == cli.EXIT_UNUSABLE
    err = capsys.readouterr().err
    assert "'chek' is not a command; did you mean `sw2sim check`?" in err
    assert cli.main(["frobnicate"]) == cli.EXIT_UNUSABLE
    assert "did you mean" not in capsys.readouterr().err


def test_only_the_command_being_run_is_imported():
    code = ("import sys; from sw2sim import cli; "
            "parser = cli._parser(['render', 'x']); "
            "print(sorted(m for m in sys.modules if m.startswith('sw2sim.commands.')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    loaded = done.stdout.strip()
    assert "'sw2sim.commands.render'" in loaded
    for other in ("check", "convert", "port", "ros2", "edits"):
        assert f"'sw2sim.commands.{other}'" not in loaded, loaded
