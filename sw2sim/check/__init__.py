"""`sw2sim check`: what is wrong with an exported package, and how to fix it.

    from sw2sim.check import check
    report = check("path/to/package")        # or a .urdf file, or a sw2sim Package
    print(report.format()); raise SystemExit(report.status)

Each rule module (structure, package_xml, meshes, inertia, joints, collisions, stability)
registers its rules and has one check function; they run in order on one shared Context.
The stability run comes last, and only when nothing so far stops MuJoCo from compiling
the model (problems that matter only to ROS packaging do not). Rule modules build on findings, context, urdf (reading values) and geometry
(shapes, masses, the link tree) and on the tool's modules outside check/, never on each
other (tests/tool/test_structure_of_the_tool.py).
"""

from __future__ import annotations

from .context import Context, open_package
from .repairs import Options
from .findings import (ADVICE, BLOCKS, ERROR, FATAL, GROUPS, PACKAGING, RULES, SIMULATION, WARNING,
                       Finding, Report, Rule)

__all__ = ["check", "check_package", "open_package", "all_rules", "Context", "Finding",
           "Report", "Rule", "RULES", "GROUPS", "FATAL", "ERROR", "WARNING", "BLOCKS",
           "SIMULATION", "PACKAGING", "ADVICE", "Options"]


def _checks():
    # Imported here so that every rule is registered before the first check runs.
    from . import structure, package_xml, hand_edits, meshes, inertia, joints, collisions
    return [structure.check, package_xml.check, hand_edits.check, meshes.check, inertia.check,
            joints.check, collisions.check]


def check(source, *, stability: bool = True, options: Options = Options(),
          urdf: str | None = None) -> Report:
    """Check a package folder, a .urdf file or a Package; never raises on bad input. `urdf`
    names the URDF to read where the package holds several."""
    return check_package(source, stability=stability, options=options, urdf=urdf).report


def check_package(source, *, stability: bool = True, options: Options = Options(),
                  urdf: str | None = None) -> Context:
    """Check as `check` does, and return the Context: its `report`, its `package` as read
    (None when it could not be read) and `repaired_package()`, for a command that goes on
    to use it. `options` are the repairs' (`sw2sim convert`'s flags)."""
    ctx = open_package(source, options, urdf)
    if ctx.usable:
        for run in _checks():
            run(ctx)
        # Problems of ROS packaging alone do not keep MuJoCo from running the model, and
        # the run simulates the model as convert writes it, repairs made.
        if stability and not ctx.report.simulation_stoppers:
            from . import stability as stability_run
            ctx.report.stability = stability_run.check(ctx)
    return ctx


def all_rules() -> dict[str, Rule]:
    """Every registered rule, in troubleshooting-page order (group, then registration)."""
    _checks()
    from . import stability  # noqa: F401  (registers the simulation rules)
    order = list(GROUPS)
    return dict(sorted(RULES.items(), key=lambda item: order.index(item[1].group)))
