"""The fix a link of wrong mass or inertia gets when its meshes can give the right ones: the
exact `sw2sim convert ... --density` command, with the package as the user named it, or
under `sw2sim convert` the user's own command with --density added."""

from __future__ import annotations

import shlex
from pathlib import Path

from .context import display
from .geometry import link_geometry

# The density the fix of a massless moving link proposes: aluminium 6061, the most common
# material of machined robot parts; the fix names steel's and ABS's beside it.
PROPOSED_DENSITY = 2700


def by_density(ctx, link) -> str | None:
    """The fix for a link whose mass or inertia convert can compute from its geometry with
    --density: the exact command that converts the package so, with the path the user gave.
    None when the link has no geometry to compute from, or the command would change nothing
    (--density given already, or --strict)."""
    if ctx.options.density is not None or ctx.options.strict:
        return None
    if not any(link_geometry(ctx, link, kind) for kind in ("collision", "visual")):
        return None
    return (f"`{convert_command(ctx)}` converts the package with the mass, centre of mass and "
            "inertia of every such link computed from its meshes as a solid of aluminium 6061 "
            f"({PROPOSED_DENSITY} kg/m^3; steel: 7850, ABS: 1040: give your material's); or "
            "give the link its real mass (SolidWorks: Mass Properties) and export again")


def convert_command(ctx, density: float = PROPOSED_DENSITY) -> str:
    """`sw2sim convert PKG -o PKG_mujoco --density ...` for the package as the user named it
    (a folder, a .urdf or a .zip), ready to paste into a shell; under `sw2sim convert`, the
    user's own command with --density added."""
    if ctx.options.command:
        return shlex.join([*ctx.options.command, "--density", f"{density:g}"])
    given = Path(ctx.path)
    if given.suffix.lower() == ".zip":
        base = given.with_suffix("")
    else:
        base = given if given.is_dir() else Path(display(ctx.package.root))
    if base.name in ("", ".", ".."):   # the package is the working folder: write beside it
        base = base / ".." / base.resolve().name
    words = ["sw2sim", "convert", str(given), "-o", f"{base}_mujoco"]
    if ctx.package.other_urdfs:
        words += ["--urdf", (ctx.package.expanded_from or ctx.package.urdf).name]
    return shlex.join(words + ["--density", f"{density:g}"])
