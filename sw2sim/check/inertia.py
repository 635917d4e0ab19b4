"""Checks of each link's mass, centre of mass and inertia tensor.

MuJoCo is stricter than ROS here, and what it refuses is an error: an inertia tensor that
is not all zeros must have positive principal moments that satisfy A + B >= C, whether
the link moves or not, and a body that moves must have more mass and inertia than
mjMINVAL (1e-15), counting the links fixed to it. A link held by the world (or fixed to a
link that brings the mass) may be massless: it is a frame, not a part. What MuJoCo
accepts but no real part has (a milligram, a centre of mass outside the part, a density
no material has) is a warning.
"""

from __future__ import annotations

import numpy as np

from ..xmlsafe import source_line
from .findings import ERROR, WARNING, rule
from .geometry import (Inertial, Tree, enclosed_volume, inertial_of, link_geometry,
                       model_size, origin_matrix, solid_of, solid_triangles)
from .density_command import by_density
from .repairs import balanced, repair, write_inertial, write_tensor
from .trimeshes import corners, hull_planes, hull_volume

# MuJoCo's smallest mass or principal moment of inertia (mjMINVAL).
MJMINVAL = 1e-15
# A moving part lighter than a milligram is not a part: the smallest screws of an assembly
# weigh tens of milligrams. Such values come from unit slips (grams typed as tonnes) or
# placeholders such as 1e-9; MuJoCo accepts them down to mjMINVAL, but next to kilogram
# links they make the mass matrix so ill-conditioned that the link jitters or explodes.
TINY_MASS = 1e-6
# A + B >= C is checked with this relative slack, the noise of computing eigenvalues in
# double precision: MuJoCo itself refuses a shortfall of 1e-12 of C.
TRIANGLE_SLACK = 1e-14
# A shortfall up to this fraction of C is rounding in the written values (a thin plate's
# C = A + B typed with five digits): `convert` balances it. Larger ones are real errors.
ROUNDING = 1e-3
# Densities outside this range belong to no material a machine part is made of: balsa, the
# lightest wood, is about 150 kg/m^3 (only foams are lighter), osmium, the densest element,
# 22,600 kg/m^3. Judged on a mesh's convex hull, which holds more than the part, a density
# still reads low for a hollow part, but not below 100 unless its walls are foil.
DENSITY_RANGE = (100.0, 25_000.0)

# A link with no visual or collision geometry is a frame (a tool point, a sensor mount):
# nothing measures its shape, so a tensor MuJoCo refuses there can only be a placeholder
# (ixx = iyy = 1, izz = 100 is one seen in exported packages). Its mass is kept, as it may
# be real (a tool's weight typed in) and weighs on the joints; the tensor becomes that of a
# solid sphere of that mass at this density, MuJoCo's own default for geometry without a
# mass: positive, A = B = C, and about 3e-5 kg m^2 for 100 g, too small to change how an
# arm turns. balanceinertia would keep the placeholder's size instead, and the tool point
# would turn like a flywheel. A massless frame gets the zero tensor, as a point has; MuJoCo
# accepts it where another link of the body brings the inertia.
FRAME_DENSITY = 1000.0

# A tensor MuJoCo refuses on a link with geometry belongs to a real part, unless it is
# absurd for the link's mass. No body of mass m can have a principal moment above m D^2,
# where D is the largest distance from its centre of mass to any of its points: at most the
# diagonal of the box around the whole model at rest, which the link lies within. A
# largest moment ten times that bound (the margin covers a model whose size is known only
# roughly) is a placeholder typed in, such as (1, 100, 1) kg m^2 on a 0.1 g frame: it
# becomes the inertia of the link's own geometry as a uniform solid of its stated mass.
# Merged with its parent by a fixed joint, the placeholder would change the parent too.
PLACEHOLDER_MARGIN = 10.0

FRAME_FIX = ("give the frame a tensor a body can have: the inertia of what it carries (a "
             "tool's, from SolidWorks' Mass Properties), or for a bare frame the same small "
             "value for ixx, iyy and izz and zero for the products, as convert does")
FRAME = (f"its mass is kept, and the tensor becomes that of a solid sphere of that mass at "
         f"{FRAME_DENSITY:g} kg/m^3 (MuJoCo's default density), or zero for a massless frame.")

PLACEHOLDER = (f"on a link with geometry, a tensor whose largest moment exceeds "
               f"{PLACEHOLDER_MARGIN:g} m D^2 (m the link's mass, D the diagonal of the box "
               f"around the model at rest; no body of mass m within that size can reach m "
               f"D^2) is a placeholder too: it becomes the inertia of the link's geometry as a "
               f"uniform solid of its stated mass, and the mass is kept.")
PLACEHOLDER_FIX = ("write the part's real tensor (SolidWorks: Mass Properties, at the centre of "
                   "mass), or for a frame that carries nothing, a small one: the same small "
                   "value for ixx, iyy and izz and zero for the products")

RECOMPUTE = ("only when asked: with `--density KG_PER_M3` (your material's density), the link's "
             "mass, centre of mass and inertia are computed from its collision mesh, or its "
             "visual mesh, as a solid of that density; from the mesh's convex hull when the "
             "mesh is not closed, which overestimates them.")

rule("inertial-missing", WARNING, "inertia", "A moving link has no <inertial>",
     symptom="MuJoCo gives the link a mass computed from its collision geometry as if it were "
             "water (1000 kg/m^3); Gazebo drops the link and everything fixed to it.",
     cause="The <inertial> block was deleted by hand, or the link was written by hand "
           "without one. The exporter writes one for every link.",
     fix="Add an <inertial> with the part's mass, centre of mass and inertia tensor, from "
         "SolidWorks' Mass Properties (Tools, Evaluate, Mass Properties), or export again.")
rule("root-link-massless", ERROR, "inertia", "A free-floating robot's root link has no mass",
     symptom="MuJoCo stops with \"mass and inertia of moving bodies must be larger than "
             "mjMINVAL\"; Gazebo drops the link, or the robot falls through the floor.",
     cause="The URDF has no link named `world`, so the root link floats free, as a vehicle's "
           "or a walking robot's does, and a free body needs mass. Its <inertial> is missing "
           "or zero: a placeholder base link, or an arm meant to be bolted down.",
     fix="Either give the root link its real mass and inertia (SolidWorks: Mass Properties) "
         "for a base that moves freely, or bolt the robot down: add <link name=\"world\"/> "
         "and a fixed joint from world to the root link, as an arm on a table needs.",
     repair=RECOMPUTE)
rule("inertial-incomplete", ERROR, "inertia", "An <inertial> lacks its mass or a term of "
     "its inertia",
     symptom="MuJoCo stops with \"missing element: 'mass'\" (or 'inertia') or \"required "
             "attribute missing\"; ROS reads the missing values as zero.",
     cause="A hand edit that dropped <mass value>, <inertia>, or one of ixx, ixy, ixz, iyy, "
           "iyz, izz.",
     fix="Write all of them: <mass value=\"...\"/> and <inertia ixx ixy ixz iyy iyz izz/>, "
         "with zeros for the products of inertia of a symmetric part.")
rule("mass-not-positive", ERROR, "inertia", "A mass is negative, or a moving link weighs "
     "nothing",
     symptom="MuJoCo stops with \"mass and inertia of moving bodies must be larger than "
             "mjMINVAL\"; Gazebo ignores the link or the model flies apart.",
     cause="A link with no components, or whose components are all suppressed (SolidWorks "
           "leaves suppressed components out of mass properties), or an <inertial> written "
           "by hand with a placeholder value.",
     fix="Set the mass to the part's real mass (SolidWorks: Mass Properties, or the "
         "exporter's mass field) and export again.",
     seen_in=("mujoco#739",),
     repair=RECOMPUTE)
rule("mass-tiny", WARNING, "inertia", "A moving link weighs less than a milligram",
     symptom="MuJoCo loads the model, but the light link jitters, drifts or makes the "
             "simulation explode, and small time steps do not help.",
     cause="A unit slip (grams or tonnes for kilograms) or a placeholder such as 1e-9 left "
           "in the URDF; no real part of a SolidWorks assembly is that light.",
     fix="Write the mass in kilograms, as SolidWorks' Mass Properties gives it.",
     seen_in=("mujoco#739",),
     repair=RECOMPUTE)
rule("inertia-not-positive-definite", ERROR, "inertia", "An inertia tensor is not positive "
     "definite",
     symptom="MuJoCo stops with \"inertia must have positive eigenvalues\" or \"mass and "
             "inertia of moving bodies must be larger than mjMINVAL\".",
     cause="A principal moment of inertia is zero or negative: a sign error in a product of "
           "inertia, values typed into the wrong attributes, or a point mass (all terms "
           "zero) on a link that moves.",
     fix="Export again, or copy the tensor again from SolidWorks' Mass Properties, taken at "
         "the centre of mass and aligned with the output coordinate system: Lxx, Lyy and "
         "Lzz as shown, the products with their signs changed (ixy = -Lxy, ixz = -Lxz, "
         "iyz = -Lyz), as the exporter writes them.",
     seen_in=("mujoco#759", "mujoco#2491"),
     repair=f"a link with no visual or collision geometry (a tool or sensor frame) has only a "
            f"placeholder tensor: {FRAME} And {PLACEHOLDER} A moving link whose six terms "
            f"are all zero is "
            f"repaired {RECOMPUTE}")
rule("inertia-triangle", ERROR, "inertia", "The principal moments break A + B >= C",
     symptom="MuJoCo stops with \"inertia must satisfy A + B >= C; use 'balanceinertia' to "
             "fix\".",
     cause="No rigid body can have one principal moment larger than the sum of the other "
           "two; such a tensor comes from values typed by hand, moments taken about a point "
           "other than the centre of mass, or a tensor for another unit or part.",
     fix="Copy the tensor again from SolidWorks' Mass Properties at the centre of mass. "
         "balanceinertia=\"true\" in MuJoCo's <compiler> hides the error by averaging the "
         "moments, but the link then turns with the wrong inertia.",
     seen_in=("mujoco#375",),
     repair=f"a shortfall of at most {ROUNDING:.1%} of C is rounding: the two smaller moments are "
            f"raised together until A + B = C, the principal axes kept. Larger ones are "
            f"repaired only on a link with no visual or collision geometry (a tool or sensor "
            f"frame), whose tensor can only be a placeholder: {FRAME} And {PLACEHOLDER}")
rule("com-outside-geometry", WARNING, "inertia", "The centre of mass lies outside the link",
     symptom="The link leans, tips or swings as if weighted on one side; the model falls "
             "over where the real machine stands.",
     cause="The mesh and the mass properties describe different parts: the mesh was "
           "simplified or replaced after the export, or the parts that carry the mass were "
           "left out of Link Components while a simplified shell stands in for them (#101); "
           "or the inertia of a multi-part link was combined without moving it to the link's "
           "frame.",
     fix="Check the link's components in the exporter dialog and SolidWorks' Mass "
         "Properties of exactly those parts, then export again.",
     seen_in=("solidworks_urdf_exporter#117", "solidworks_urdf_exporter#101"))
rule("density-implausible", WARNING, "inertia", "The mass does not fit the mesh's volume",
     symptom="The link behaves as if made of foam or of something denser than any metal.",
     cause="The mass was typed by hand and does not fit the part; the part has no material "
           "(SolidWorks then uses 1000 kg/m³); its mass was set with SolidWorks' Override "
           "Mass Properties, which the exporter ignores (#172, #164); or the parts that carry "
           "the mass were left out of Link Components while a simplified shell stands in for "
           "them (#101).",
     fix="Compare the link's mass with its volume in SolidWorks' Mass Properties and set the "
         "part's material (a custom one of the density the wanted mass needs), or correct "
         "the mass.",
     seen_in=("solidworks_urdf_exporter#101", "solidworks_urdf_exporter#164"),
     repair=RECOMPUTE)


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    tree = Tree(ctx)
    inertials = {name: inertial_of(link) for name, link in ctx.links.items()}
    for name, link in ctx.links.items():
        inertial = inertials[name]
        # Only a link that heads a moving body must bring mass and inertia to it.
        mass, inertia = (_body_has(ctx, tree, inertials, name) if tree.moves(name)
                         else (True, True))
        if inertial is None:
            if not mass:
                ctx.add("mass-not-positive", f'link "{name}" moves (joint '
                        f'"{tree.joint_name(name)}") but has no <inertial> and no collision '
                        "geometry for MuJoCo to compute a mass from",
                        line=source_line(link), repair=_recompute(ctx, link),
                        fix=by_density(ctx, link))
            elif tree.moves(name):
                ctx.add("inertial-missing", f'link "{name}" moves (joint '
                        f'"{tree.joint_name(name)}") but has no <inertial>' + _fallback(link),
                        line=source_line(link))
            continue
        if inertial.missing:
            # Point at <inertia> when all that is missing are some of its terms.
            whole = {"<mass value>", "<inertia>"} & set(inertial.missing)
            at = inertial.element if whole else inertial.element.find("inertia")
            ctx.add("inertial-incomplete", f'link "{name}": the <inertial> has no '
                    f"{', '.join(inertial.missing)}", line=source_line(at, None))
        mass_ok = _mass(ctx, tree, name, inertial, alone=not mass)
        _tensor(ctx, tree, link, inertial, alone=not inertia)
        if mass_ok and inertial.centre is not None:
            _placement(ctx, link, inertial)
    _free_root(ctx, tree, inertials)


def _free_root(ctx, tree: Tree, inertials: dict) -> None:
    """The root link of a robot without a `world` link floats free, as in Gazebo: MuJoCo
    gives it a free joint, and it (with the links fixed to it) must bring mass."""
    if ctx.package.world_fixed:
        return
    roots = [name for name in ctx.links if tree.parent(name) is None]
    if len(roots) != 1:
        return   # structure.py reports several roots, or a cycle
    root = roots[0]
    link = ctx.links[root]
    members = [name for name in ctx.links if tree.body(name) is None]
    mass = inertia = False
    for name in members:
        inertial = inertials.get(name)
        if inertial is None:
            if ctx.links[name].find("collision") is not None:
                mass = inertia = True   # MuJoCo computes both from the collision geometry
            continue
        mass = mass or (inertial.mass is not None and inertial.mass > MJMINVAL)
        inertia = inertia or (inertial.tensor is not None and bool(inertial.tensor.any()))
    if not (mass and inertia):
        lacks = "mass" if not mass else "inertia"
        own = "no <inertial>" if inertials.get(root) is None else f"no {lacks}"
        ctx.add("root-link-massless", f'the root link "{root}" has {own}, and no link fixed '
                f"to it brings any, so as the free-floating base of a robot without a "
                f'"world" link it cannot be simulated', line=source_line(link),
                repair=_recompute(ctx, link))
    elif inertials.get(root) is None:
        ctx.add("inertial-missing", f'the root link "{root}" floats free (the URDF has no '
                '"world" link) but has no <inertial>' + _fallback(link),
                line=source_line(link))


def _body_has(ctx, tree: Tree, inertials: dict, head: str) -> tuple[bool, bool]:
    """Whether the rigid body that the moving link `head` starts (it and the links fixed to
    it) has a mass, and an inertia, that MuJoCo can use."""
    mass = inertia = False
    for name in tree.rigid_body(head):
        inertial = inertials.get(name)
        if inertial is None:
            link = ctx.links.get(name)
            if link is not None and link.find("collision") is not None:
                return True, True  # MuJoCo computes both from the collision geometry
            continue
        mass = mass or (inertial.mass is not None and inertial.mass > MJMINVAL)
        inertia = inertia or (inertial.tensor is not None and bool(inertial.tensor.any()))
    return mass, inertia


def _fallback(link) -> str:
    if link.find("collision") is not None:
        return ("; MuJoCo computes its mass from the collision geometry at 1000 kg/m^3, and "
                "Gazebo drops the link")
    return "; its mass comes only from links fixed to it, and Gazebo drops the link"


def _mass(ctx, tree: Tree, name: str, inertial: Inertial, alone: bool) -> bool:
    """Report the mass; True when it is a usable positive mass."""
    mass = inertial.mass
    if mass is None:
        return False
    line = source_line(inertial.element.find("mass"), "value")
    if mass < 0:
        ctx.add("mass-not-positive", f'link "{name}" has a negative mass, {mass:g} kg',
                line=line, repair=_recompute(ctx, ctx.links[name]),
                fix=by_density(ctx, ctx.links[name]))
        return False
    if mass <= MJMINVAL:
        if alone:
            ctx.add("mass-not-positive", f'link "{name}" moves (joint '
                    f'"{tree.joint_name(name)}") but its mass is {mass:g} kg, and no link '
                    "fixed to it has mass", line=line, repair=_recompute(ctx, ctx.links[name]),
                    fix=by_density(ctx, ctx.links[name]))
        return False
    if mass < TINY_MASS and tree.body(name) is not None:
        ctx.add("mass-tiny", f'link "{name}" moves but weighs {mass:.3g} kg, less than a '
                f"milligram ({TINY_MASS:g} kg)", line=line,
                repair=_recompute(ctx, ctx.links[name]))
        return False
    return True


def _tensor(ctx, tree: Tree, link, inertial: Inertial, alone: bool) -> None:
    """Report an inertia tensor MuJoCo refuses."""
    name = link.get("name", "")
    tensor = inertial.tensor
    if tensor is None:
        return
    element = inertial.element.find("inertia")
    line = source_line(element, None)
    if not tensor.any():
        if alone:
            ctx.add("inertia-not-positive-definite", f'link "{name}" moves but all six terms '
                    "of its inertia are zero, and no link fixed to it has inertia", line=line,
                    fix=by_density(ctx, link) or
                    "write the part's inertia tensor from SolidWorks' Mass Properties; "
                    "for a small part, that of a solid box of its size will do",
                    repair=_recompute(ctx, link))
        return
    a, b, c = (float(m) for m in np.linalg.eigvalsh(tensor))
    shown = f"{a:.4g}, {b:.4g}, {c:.4g} kg m^2"
    frame = _frame_tensor(link, inertial)
    fix = FRAME_FIX
    if frame is None and (a <= MJMINVAL or a + b < c * (1 - ROUNDING)):
        frame, fix = _placeholder_tensor(ctx, tree, link, inertial, c), PLACEHOLDER_FIX
    if a <= MJMINVAL:
        ctx.add("inertia-not-positive-definite", f'link "{name}": the principal moments of '
                f"its inertia are {shown}; all three must be positive", line=line,
                repair=frame, fix=fix if frame else None)
    elif a + b < c * (1 - TRIANGLE_SLACK):
        short = c - (a + b)
        fixed = None
        if short <= ROUNDING * c:
            # The tensor as written (in the <inertial>'s own axes), balanced.
            turn = origin_matrix(inertial.element)[:3, :3]
            written = balanced(turn.T @ tensor @ turn)
            fixed = repair(f'the moments of link "{name}" are raised by {short / 2:.3g} kg m^2 '
                           f"each, {short / c:.2g} of C, as a shortfall that small is rounding",
                           (element, write_tensor(written)))
        else:
            fixed = frame
        digits = _digits_apart(a + b, c)
        shown = ", ".join(f"{m:.{digits}g}" for m in (a, b, c)) + " kg m^2"
        ctx.add("inertia-triangle", f'link "{name}": the principal moments of its inertia are '
                f"{shown}, and {a:.{digits}g} + {b:.{digits}g} = {a + b:.{digits}g} is less "
                f"than {c:.{digits}g}", line=line,
                repair=fixed, fix=fix if frame and fixed is frame else None)


def _frame_tensor(link, inertial: Inertial):
    """For a link with no visual or collision geometry, whose tensor MuJoCo refuses: the
    repair that gives it a valid one, a sphere's of its mass (see FRAME_DENSITY). None for a
    link with geometry, whose tensor belongs to a real part."""
    if link.find("visual") is not None or link.find("collision") is not None:
        return None
    mass, element = inertial.mass, inertial.element.find("inertia")
    if mass is None or mass < 0 or element is None:
        return None   # inertial-incomplete or mass-not-positive says so
    name = link.get("name", "")
    if mass <= MJMINVAL:
        return repair(f'link "{name}" has no visual or collision geometry and no mass, so its '
                      "tensor is a placeholder: it becomes zero, a massless frame's",
                      (element, write_tensor(np.zeros((3, 3)))))
    radius = (3 * mass / (4 * np.pi * FRAME_DENSITY)) ** (1 / 3)
    moment = 0.4 * mass * radius ** 2
    return repair(f'link "{name}" has no visual or collision geometry, so its tensor is a '
                  f"placeholder: its mass, {mass:.4g} kg, is kept, and the tensor becomes that "
                  f"of a solid sphere of that mass at {FRAME_DENSITY:g} kg/m^3 (radius "
                  f"{radius * 1000:.3g} mm), {moment:.3g} kg m^2 about every axis",
                  (element, write_tensor(np.eye(3) * moment)))


def _digits_apart(low: float, high: float) -> int:
    """The significant digits (4 at least) that print `low` < `high` as two numbers in that
    order: a shortfall of one part in a million must not read "1.702e-10 is less than
    1.702e-10"."""
    for digits in range(4, 18):
        if float(f"{low:.{digits}g}") < float(f"{high:.{digits}g}"):
            return digits
    return 17


def _placeholder_tensor(ctx, tree: Tree, link, inertial: Inertial, largest: float):
    """For a link with geometry whose tensor MuJoCo refuses: when the largest moment is
    absurd for the link's mass (see PLACEHOLDER_MARGIN), the repair that gives it the
    inertia of its geometry as a uniform solid of that mass; else None."""
    mass, element = inertial.mass, inertial.element.find("inertia")
    if mass is None or mass <= MJMINVAL or element is None:
        return None   # mass-not-positive, inertial-incomplete: the mass is in doubt
    size = model_size(ctx, tree)
    bound = mass * size ** 2
    if not largest > PLACEHOLDER_MARGIN * bound:
        return None
    solid = solid_of(ctx, link)
    if solid is None:
        return None
    kind, closed, volume, tensor = solid
    tensor = tensor * (mass / volume)
    turn = origin_matrix(inertial.element)[:3, :3]
    written = turn.T @ tensor @ turn
    moments = np.linalg.eigvalsh(tensor)
    name = link.get("name", "")
    what = f"its closed {kind} geometry" if closed else f"the convex hull of its {kind} geometry"
    return repair(f'link "{name}" weighs {mass:.4g} kg, and its largest moment, {largest:.4g} '
                  f"kg m^2, is {largest / bound:.3g} times the most any body of that mass "
                  f"within the model's {size:.3g} m can have (m D^2 = {bound:.3g} kg m^2), so "
                  f"the tensor is a placeholder: its mass is kept, and the tensor becomes that "
                  f"of {what} as a uniform solid of that mass, principal moments "
                  f"{', '.join(f'{m:.3g}' for m in moments)} kg m^2",
                  (element, write_tensor(written)))


def _recompute(ctx, link):
    """With --density: the link's mass, centre of mass and inertia from its geometry as a
    solid of that density (its convex hull when the geometry is not closed); else None."""
    density = ctx.options.density
    if density is None:
        return None
    solid = solid_triangles(ctx, link)
    if solid is None:
        return None
    kind, closed, triangles = solid
    import trimesh   # only with --density: the check itself does without it
    props = trimesh.triangles.mass_properties(triangles, density=density)
    if not props.mass > 0 or not np.all(np.isfinite(props.inertia)):
        return None
    what = (f"its closed {kind} geometry" if closed else
            f"the convex hull of its {kind} geometry (not closed, so an overestimate)")
    return repair(f'link "{link.get("name", "")}" gets {props.mass:.4g} kg, with its centre of '
                  f"mass and inertia, computed from {what} at {density:g} kg/m^3 (--density)",
                  (link, write_inertial(props.mass, props.center_mass, props.inertia)))


def _placement(ctx, link, inertial: Inertial) -> None:
    """The centre of mass against the link's geometry, and the mass against its volume."""
    name = link.get("name", "")
    for kind in ("collision", "visual"):
        pieces = link_geometry(ctx, link, kind)
        if pieces:
            break
    else:
        return
    points = np.vstack([p.mesh.vertices for p in pieces])
    outside = _distance_outside(points, inertial.centre)
    low, high = corners(points)
    size = float(np.linalg.norm(high - low))
    margin = max(0.001, 0.05 * size)
    if outside > margin:
        x, y, z = inertial.centre
        origin = inertial.element.find("origin")
        ctx.add("com-outside-geometry", f'link "{name}": the centre of mass ({x:.4g}, {y:.4g}, '
                f"{z:.4g}) m lies {outside * 1000:.0f} mm outside its {kind} geometry, which is "
                f"{size * 1000:.0f} mm across",
                line=source_line(origin if origin is not None else inertial.element,
                                 "xyz" if origin is not None else None))
    volumes = [enclosed_volume(p) for p in pieces]
    if None not in volumes:
        volume, what = sum(volumes), f"closed {kind} geometry"
    else:
        # SolidWorks meshes are often not closed: their convex hull holds at least the
        # part's volume, so the density it gives is a lower bound, and one above every
        # material's is wrong all the same. Far below, it is wrong too: the hull of a part
        # is never hundreds of times its volume.
        volume, what = hull_volume(points), f"the convex hull of its {kind} geometry (the " \
            "mesh is not closed)"
    density = inertial.mass / volume if volume > 0 else None
    low, high = DENSITY_RANGE   # with the noise of the volume's last digits (1e-9)
    if density is not None and not low * (1 - 1e-9) <= density <= high * (1 + 1e-9):
        ctx.add("density-implausible", f'link "{name}": {inertial.mass:.4g} kg in '
                f"{volume * 1e6:.4g} cm^3 of {what} makes {_density(density)} kg/m^3 "
                "(aluminium: 2,700, steel: 7,850)",
                line=source_line(inertial.element.find("mass"), "value"),
                repair=_recompute(ctx, link))


def _density(value: float) -> str:
    """To the unit (3 digits below 10), or with the digits that put it outside the range."""
    shown = f"{value:,.0f}" if value >= 10 else f"{value:.3g}"
    for digits in range(4, 18):
        if DENSITY_RANGE[0] <= float(shown.replace(",", "")) <= DENSITY_RANGE[1]:
            shown = f"{value:.{digits}g}"
    return shown


def _distance_outside(points: np.ndarray, centre: np.ndarray) -> float:
    """How far `centre` lies outside the convex hull of `points` (0 inside): the height above
    the farthest face plane, exact near a face and a little short near an edge or corner."""
    planes = hull_planes(points)   # outward normal n and offset d: n.x + d <= 0 inside
    if planes is not None and len(planes):
        return max(0.0, float((planes[:, :3] @ centre + planes[:, 3]).max()))
    low, high = corners(points)   # flat points: the bounding box
    return float(np.linalg.norm(np.maximum(0, np.maximum(low - centre, centre - high))))
