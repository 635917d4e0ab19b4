"""Packages of every shape `sw2sim check` meets, for tools/benchmark.py's `commands` section.

The lessons' packages are small binary-STL exports; what users give the check is wider:
exports from the exporter's older releases, meshes saved as COLLADA (alone, or with the
STL beside them that Gazebo reads), OBJ or text STL, robots of forty links, and parts
tessellated into hundreds of thousands of triangles. Each function below writes one such
package into a scratch folder and returns its path, so that the check can be timed on
each as a user runs it. The exporter-shaped ones start from tests/tool/check/
exporter_packages.py, which writes packages byte for byte as the SolidWorks exporter does.
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import trimesh

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(1, str(ROOT / "tests" / "tool" / "check"))

from exporter_packages import (CRLF, FOUR_WHEELER_NESTED, REAL_EXPORTS, Export, Joint,  # noqa: E402
                               Link, write_export)
from course.practices import PRACTICES, package_dir  # noqa: E402


def real_exports(folder: Path) -> dict[str, Path]:
    """The three exports of the exporter's own repository, as it writes them."""
    return {name: write_export(export, folder / "real") for name, export in REAL_EXPORTS.items()}


def _reformatted(folder: Path, label: str, suffix: str, write, keep_stl: bool = False) -> Path:
    """The four-wheeler with each mesh rewritten by `write(mesh, path)` as `suffix`, and
    the URDF naming those files; `keep_stl` leaves the exporter's STL beside each one."""
    package = write_export(FOUR_WHEELER_NESTED, folder / label)
    for stl in sorted((package / "meshes").glob("*.STL")):
        write(trimesh.load(stl), stl.with_suffix(suffix))
        if not keep_stl and suffix != ".STL":
            stl.unlink()
    urdf = package / "urdf" / f"{package.name}.urdf"
    urdf.write_bytes(urdf.read_bytes().replace(b".STL\"", suffix.encode() + b"\""))
    return package


def collada(folder: Path) -> Path:
    """Meshes as COLLADA only: the check and the model read them through a conversion."""
    return _reformatted(folder, "collada", ".dae", lambda m, p: m.export(p))


def collada_beside_stl(folder: Path) -> Path:
    """COLLADA named in the URDF with the same-named STL beside each, as RViz packages do."""
    return _reformatted(folder, "collada_beside", ".dae", lambda m, p: m.export(p), keep_stl=True)


def obj(folder: Path) -> Path:
    """Meshes as Wavefront OBJ."""
    return _reformatted(folder, "obj", ".obj", lambda m, p: m.export(p))


def ascii_stl(folder: Path) -> Path:
    """Meshes as text STL, under the exporter's names."""
    return _reformatted(folder, "ascii", ".STL",
                        lambda m, p: p.write_bytes(m.export(file_type="stl_ascii").encode()))


def _box_link(name: str, size: tuple[float, float, float], mass: float, com: str) -> Link:
    """A link whose inertia is a solid box's (exporter_packages makes the box mesh from it)."""
    a, b, c = size
    ixx, iyy, izz = (mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12,
                     mass * (a * a + b * b) / 12)
    number = "{:.15G}".format
    return Link(name, com, number(mass), (number(ixx), "0", "0", number(iyy), "0", number(izz)))


def forty_links(folder: Path) -> Path:
    """A body of 40 links: a chassis and thirteen legs of three links each (hip about z,
    thigh and shin about y), every joint revolute with limits, standing on the floor."""
    links = [_box_link("base_link", (0.8, 0.3, 0.06), 4.0, "0 0 0")]
    joints = []
    for leg in range(13):
        side = 1 if leg % 2 else -1
        x = -0.36 + leg * 0.06
        hip, thigh, shin = f"hip_{leg}", f"thigh_{leg}", f"shin_{leg}"
        links += [_box_link(hip, (0.03, 0.04, 0.02), 0.05, "0 0 0"),
                  _box_link(thigh, (0.02, 0.025, 0.12), 0.08, "0 0 -0.06"),
                  _box_link(shin, (0.015, 0.02, 0.14), 0.06, "0 0 -0.07")]
        limit = ("-0.5", "0.5", "10", "2")
        joints += [Joint(f"{hip}_joint", "revolute", f"{x:.4f} {side * 0.17:.2f} 0", "0 0 0",
                         "base_link", hip, "0 0 1", limit),
                   Joint(f"{thigh}_joint", "revolute", "0 0 -0.01", "0 0 0", hip, thigh,
                         "0 1 0", limit),
                   Joint(f"{shin}_joint", "revolute", "0 0 -0.12", "0 0 0", thigh, shin,
                         "0 1 0", limit)]
    export = Export(name="forty_links_description", links=tuple(links), joints=tuple(joints),
                    version=("25f2e4c", "1.6.9650.27696"))
    return write_export(export, folder / "forty", newline=CRLF)


def heavy_arm(folder: Path, suffix: str = ".STL", limit: int = 200_000) -> Path:
    """Practice 3's arm with each link's mesh subdivided (each triangle into four) as long
    as it stays within `limit` triangles: 266,752 in all with the default, MuJoCo's STL limit,
    so that the model still loads; written as binary STL or (suffix ".obj") as OBJ."""
    package = folder / f"heavy_arm_{limit}{suffix.lower().replace('.', '_')}"
    shutil.copytree(package_dir(PRACTICES[2]), package)
    urdf = next((package / "urdf").glob("*.urdf"))
    for stl in sorted((package / "meshes").glob("*.STL")):
        mesh = trimesh.load(stl)
        while len(mesh.faces) * 4 <= limit:
            mesh = mesh.subdivide()
        mesh.export(stl.with_suffix(suffix))
        if suffix != ".STL":
            stl.unlink()
            urdf.write_text(urdf.read_text().replace(stl.name, stl.stem + suffix))
    return package


def all_shapes(folder: Path) -> dict[str, Path]:
    """Every package above, by a label for the benchmark's lines."""
    folder.mkdir(parents=True, exist_ok=True)
    shapes = {f"real export {name}": path for name, path in real_exports(folder).items()}
    shapes.update({
        "COLLADA meshes only": collada(folder),
        "COLLADA, the STL beside each": collada_beside_stl(folder),
        "OBJ meshes": obj(folder),
        "text (ASCII) STL meshes": ascii_stl(folder),
        "40 links": forty_links(folder),
        "3 meshes of 64,000-102,000 triangles, binary STL": heavy_arm(folder),
        "3 meshes of 64,000-102,000 triangles, OBJ": heavy_arm(folder, ".obj"),
        "a mesh beyond MuJoCo's 200,000 triangles": heavy_arm(folder, limit=300_000),
    })
    return shapes
