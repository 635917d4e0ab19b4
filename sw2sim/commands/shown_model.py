"""The model `view` and `render` show: the package checked without the simulation, then
compiled, with sliders for the viewer and an off-screen buffer big enough for a picture."""

from __future__ import annotations

from .options import EXIT_ERRORS, EXIT_UNUSABLE, say


def shown_model(args, *, sliders: bool = False, size: tuple[int, int] | None = None):
    """The package's model as the viewer or a picture shows it, or an exit status.

    The static check runs first: a package it cannot use stops here; other findings
    are printed and the model is still loaded, since looking at it is how to find
    what they mean.
    """
    from ..check import check_package
    from ..check.stability import mujoco_warnings
    from ..package import LoadError
    checked = check_package(args.path, stability=False, urdf=args.urdf)
    report = checked.report
    if report.status == EXIT_UNUSABLE:
        print(report.format())
        return EXIT_UNUSABLE
    if report.findings:
        print(report.format())
    try:
        with mujoco_warnings():   # the check has reported them; no MUJOCO_LOG.TXT here
            return _compiled(checked.package, sliders, size)
    except LoadError as exc:
        say(f"sw2sim {args.command}: {exc}")
        return EXIT_ERRORS
    except ValueError as exc:
        message = " ".join(str(exc).split())
        say(f"sw2sim {args.command}: MuJoCo cannot compile the model: {message}")
        return EXIT_ERRORS


def _compiled(package, sliders: bool, size: tuple[int, int] | None):
    from ..actuators import add_actuators
    from ..loader import load_package
    from ..package import LoadError
    fixed = package.world_fixed
    spec = load_package(package, fixed_base=fixed)
    if sliders:
        try:
            add_actuators(spec, package, sliders=True)
        except LoadError as exc:
            print(f"no sliders: {exc}")
            spec = load_package(package, fixed_base=fixed)
    if size is not None:
        spec.visual.global_.offwidth = max(spec.visual.global_.offwidth, size[0])
        spec.visual.global_.offheight = max(spec.visual.global_.offheight, size[1])
    return spec.compile()
