"""What each URDF parser says of the peer cases (tests/tool/check/peer_cases/*.urdf).

The cases restate, as small URDFs of this project's own, what the test suites of urdfdom
(ROS's reference parser, whose check_urdf Debian ships in liburdfdom-tools),
urdf_parser_py and yourdfpy feed their parsers, plus the cases where `sw2sim check` and
check_urdf once disagreed. peer_cases/verdicts.json records, per case, each parser's
verdict ("accepts" or "refuses", with the first error it gives) next to the error rules
`sw2sim check` reports; test_peer_cases.py holds sw2sim to check_urdf's verdict, or to a
rule whose text says why it differs.

Rewrite the table after adding a case or upgrading a parser (check_urdf must be
installed; urdf_parser_py, which neither Debian 12 nor the pinned environment ships, is
asked where it can be imported, e.g. from a checkout's src/ on PYTHONPATH):

    .venv/bin/python tests/tool/check/peer_verdicts.py

The hand-written fields of each case ("about", "from", "differs") are kept.
"""

from __future__ import annotations

import importlib
import io
import json
import logging
import shutil
import subprocess
import sys
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

CASES = Path(__file__).parent / "peer_cases"
TABLE = CASES / "verdicts.json"
ACCEPTS, REFUSES = "accepts", "refuses"


def check_urdf(path: Path) -> dict | None:
    """check_urdf's verdict (its exit status) and first error line; None if not installed."""
    if shutil.which("check_urdf") is None:
        return None
    done = subprocess.run(["check_urdf", str(path)], capture_output=True, text=True, timeout=60)
    errors = [line.split(":", 1)[1].strip() for line in (done.stderr + done.stdout).splitlines()
              if line.startswith("Error:")]
    return {"verdict": ACCEPTS if done.returncode == 0 else REFUSES,
            "says": errors[0] if errors else None}


def urdf_parser_py(path: Path) -> dict | None:
    """urdf_parser_py's verdict: whether URDF.from_xml_string raises; None if not importable."""
    parser = _urdf_parser_py()
    if parser is None:
        return None
    said = io.StringIO()
    try:
        with redirect_stderr(said), redirect_stdout(said):
            parser.URDF.from_xml_string(path.read_bytes())
    except Exception as exc:  # noqa: BLE001  (any exception is the parser refusing the file)
        return {"verdict": REFUSES, "says": _short(f"{type(exc).__name__}: {exc}")}
    return {"verdict": ACCEPTS, "says": None}


def _urdf_parser_py():
    """urdf_parser_py.urdf (PyPI's urdf_parser_py 0.0.4, in the test extra and
    requirements.txt), or None where it is not installed."""
    try:
        return importlib.import_module("urdf_parser_py.urdf")
    except ImportError:
        return None


def yourdfpy(path: Path) -> dict:
    """yourdfpy's verdict: whether URDF.load raises (meshes are not read; the cases have none)."""
    import yourdfpy as module
    logging.getLogger("yourdfpy").setLevel(logging.CRITICAL)
    try:
        module.URDF.load(str(path), load_meshes=False)
    except Exception as exc:  # noqa: BLE001  (any exception is the parser refusing the file)
        return {"verdict": REFUSES, "says": _short(f"{type(exc).__name__}: {exc}")}
    return {"verdict": ACCEPTS, "says": None}


def sw2sim_errors(path: Path) -> list[str]:
    """The rules `sw2sim check` reports as errors (or fatal) for a case, without the
    stability run: the other parsers read the file and simulate nothing."""
    from sw2sim.check import ERROR, FATAL, check
    report = check(path, stability=False)
    return sorted({f.rule for f in report.findings if f.severity in (ERROR, FATAL)})


def verdict(errors: list[str]) -> str:
    return REFUSES if errors else ACCEPTS


def _short(text: str) -> str:
    text = " ".join(text.split())
    return text if len(text) <= 160 else text[:157] + "..."


def _version(distribution: str) -> str | None:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version(distribution)
    except PackageNotFoundError:
        return None


def _check_urdf_version() -> str | None:
    done = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "liburdfdom-tools"],
                          capture_output=True, text=True)
    return f"liburdfdom-tools {done.stdout}" if done.returncode == 0 else None


def rewrite() -> dict:
    """Ask every parser about every case and write verdicts.json; return the table."""
    if shutil.which("check_urdf") is None:
        raise SystemExit("check_urdf is not installed (Debian: liburdfdom-tools); the table "
                         "records its verdicts, so it cannot be rewritten without it")
    old = json.loads(TABLE.read_text()) if TABLE.exists() else {"cases": {}}
    cases = {}
    for path in sorted(CASES.glob("*.urdf")):
        kept = old["cases"].get(path.stem, {})
        errors = sw2sim_errors(path)
        cases[path.stem] = {
            "about": kept.get("about", ""), "from": kept.get("from", ""),
            # urdf_parser_py's verdicts are kept where it cannot be imported now
            "check_urdf": check_urdf(path),
            "urdf_parser_py": urdf_parser_py(path) or kept.get("urdf_parser_py"),
            "yourdfpy": yourdfpy(path),
            "sw2sim": {"verdict": verdict(errors), "errors": errors},
            "differs": kept.get("differs")}
    table = {"about": old.get("about", ""),
             "parsers": {"check_urdf": _check_urdf_version(),
                         "urdf_parser_py": _urdf_parser_py_version(old),
                         "yourdfpy": _version("yourdfpy")},
             "cases": cases}
    TABLE.write_text(json.dumps(table, indent=2, ensure_ascii=False) + "\n")
    return table


def _urdf_parser_py_version(old: dict) -> str | None:
    """Its installed version, else the one recorded (it is run from a source checkout)."""
    recorded = old.get("parsers", {}).get("urdf_parser_py")
    parser = _urdf_parser_py()
    if parser is None:
        return recorded
    return _version("urdf_parser_py") or recorded or f"from {Path(parser.__file__).parent}"


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[3]))
    written = rewrite()
    print(f"{TABLE}: {len(written['cases'])} cases")
