"""Every figure on the site, and `python -m course.media` to bring them up to date.

Each practice lists its figures in `course/practices/<practice>/figures.py` as
`FIGURES = [Figure(...), ...]`. A figure with lettering also has a phone variant
(course/phone.py), which its code writes beside it in the same run, from the same data:
`Figure(..., phone=True)`. When a figure is made, media/manifest.json records the
hash of its inputs and a digest of each file written. Its inputs are the module that
draws it, every repository module that module (or a script it lists) imports, the files
it lists as read, and the versions of the libraries that can change it. A figure is
stale when either no longer matches: an input changed, or the file was changed by hand.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from importlib import import_module
from pathlib import Path
from typing import Callable

from . import freshness
from .freshness import Fingerprint, cores  # noqa: F401  (tools/benchmark.py imports cores here)
# What a figure's code raises when it cannot be made on this machine. It is defined in
# freshness, which is never run as __main__: under `python -m course.media` this module
# is, and a class of its own would not be the one the figures' code raises.
from .freshness import Unavailable
from .phone import phone_paths
from .sharp import sharp_paths
from .practices import PRACTICES, ROOT

MANIFEST = ROOT / "media" / "manifest.json"
# Every figure module imports this one for `Figure`; it draws nothing, so it is no input.
MODULE = Path(__file__).resolve()
# Libraries whose version can change a figure: simulation, rendering, plots and their
# layout, meshes, the drawings' geometry, and the parsers of the files the scripts read.
RENDERERS = ("mujoco", "matplotlib", "numpy", "trimesh", "manifold3d", "pillow", "shapely",
             "scipy", "kiwisolver", "PyYAML", "lxml")


@dataclass
class Figure:
    """One file under media/, and how to make it."""

    output: str                      # path from the repository root, e.g. media/practice-1/x.png
    make: Callable[[Path], None]     # writes the figure to the path it is given
    inputs: list[str] = field(default_factory=list)  # files or folders it reads, from the root
    caption: str = ""
    phone: bool = False              # a plot or drawing: `make` also writes its phone variants
    sharp: bool = False              # a render: `make` also writes its sharp file (course/sharp.py)

    @property
    def path(self) -> Path:
        return ROOT / self.output

    @property
    def outputs(self) -> list[str]:
        """Every file the figure's code writes: its own, then its variants'."""
        return [self.output, *(p.as_posix() for p in self.variants(self.output))]

    def variants(self, path: str | Path) -> list[Path]:
        """The files the figure's code writes beside `path`: a plot's sharp file and phone
        variants (phone), a render's sharp file (sharp)."""
        return [*(sharp_paths(path) if self.phone or self.sharp else []),
                *(phone_paths(path) if self.phone else [])]

    def input_hash(self) -> str:
        module = Path(sys.modules[self.make.__module__].__file__)
        listed = _files(self.inputs)
        code = freshness.imported_closure([module, *(f for f in listed if f.suffix == ".py")],
                                          leave_out=[MODULE])
        return (Fingerprint().files({*listed, *code}, ROOT).libraries(RENDERERS)
                .text(self.make.__qualname__).hexdigest())


def variant_paths(path: str | Path) -> list[Path]:
    """Every file a figure may write beside its own: a PNG's sharp file (course/sharp.py),
    then the phone variant's (course/phone.py)."""
    return [*sharp_paths(path), *phone_paths(path)]


def _files(inputs: list[str]) -> list[Path]:
    out: list[Path] = []
    for rel in inputs:
        p = ROOT / rel
        if not (p.is_dir() or p.is_file()):
            raise FileNotFoundError(f"figure input {rel!r} does not exist")
        out.extend(freshness.files_in(p))
    return out


def all_figures() -> list[Figure]:
    figures: list[Figure] = []
    for practice in PRACTICES:
        module = import_module(f"course.practices.{practice}.figures")
        figures.extend(module.FIGURES)
    return figures


def make_figure(output: str, path: str | Path) -> float | str:
    """Make the figure whose output is `output` into `path`; return the seconds it took, or
    why it cannot be made here (see `Unavailable`; nothing is written then).

    It takes names, not a Figure, so that a worker process can run it: `make media` and
    the tests make several figures at once, each in a process of its own.
    """
    start = time.perf_counter()
    for fig in all_figures():
        if fig.output == output:
            variants, declared = variant_paths(path), fig.variants(path)
            for variant in variants:
                variant.unlink(missing_ok=True)
            try:
                fig.make(Path(path))
            except Unavailable as exc:
                return str(exc)
            for variant in variants:
                if variant.is_file() != (variant in declared):
                    where = sys.modules[fig.make.__module__].__file__
                    flag = "phone" if variant in phone_paths(path) or fig.phone else "sharp"
                    raise RuntimeError(
                        f"{output}: its code {'wrote' if variant.is_file() else 'did not write'} "
                        f"{variant.name} but its Figure says {flag}={getattr(fig, flag)}: in "
                        f"{where}, give it {flag}={variant.is_file()}")
            return time.perf_counter() - start
    raise KeyError(f"no figure makes {output}")


def read_manifest() -> dict[str, dict[str, str]]:
    """output -> {"inputs": input hash, "output": digest of the file} as last made."""
    return freshness.read_manifest(MANIFEST)


def is_current(fig: Figure, manifest: dict[str, dict[str, str]]) -> bool:
    """Whether its files are exactly what was made from inputs all as they are now."""
    hashed: list[str] = []

    def inputs() -> str:   # hashed once for the figure and its phone variant
        if not hashed:
            hashed.append(fig.input_hash())
        return hashed[0]

    return all(freshness.is_recorded(manifest, output, ROOT / output, inputs)
               for output in fig.outputs)


def stale(figures: list[Figure], manifest: dict[str, dict[str, str]]) -> list[Figure]:
    return [f for f in figures if not is_current(f, manifest)]


def _bar(done: int, total: int, width: int = 24) -> str:
    filled = round(width * done / total) if total else width
    return "[" + "#" * filled + "-" * (width - filled) + f"] {done}/{total}"


def main(argv: list[str] | None = None) -> int:
    args = freshness.command_line(
        argv, prog="python -m course.media", description=__doc__.splitlines()[0],
        force="remake every figure", check="only list stale figures; exit 1 if any",
        jobs="figures made at once, each in a process of its own (default: cores)",
        only="make only figures whose path contains one of these")
    figures = freshness.chosen(all_figures(), args.only, lambda f: f.output)
    manifest = read_manifest()
    todo = figures if args.force else stale(figures, manifest)
    if args.check:
        return freshness.report_stale(f"stale: {f.output}" for f in todo)
    if not todo:
        print(f"media: all {len(figures)} figures are up to date")
        return 0
    for fig in todo:
        fig.path.parent.mkdir(parents=True, exist_ok=True)
    interactive = sys.stdout.isatty()
    made = freshness.run_jobs(make_figure, [(f, (f.output, f.path)) for f in todo], args.jobs)
    for i, (fig, seconds) in enumerate(made, start=1):
        if isinstance(seconds, str):   # cannot be made here: kept as it is, still stale
            line = f"{_bar(i, len(todo))} {fig.output} kept as it is: {seconds}"
        else:
            inputs = fig.input_hash()
            for output in fig.outputs:
                manifest[output] = freshness.manifest_entry(ROOT / output, inputs)
            line = f"{_bar(i, len(todo))} {fig.output} ({seconds:.1f} s)"
        # A figure kept as it is keeps its line; the others' lines replace each other.
        last = i == len(todo) or isinstance(seconds, str)
        print(("\r\033[K" + line) if interactive else line, end="" if interactive and not last else "\n",
              flush=True)
        freshness.write_manifest(MANIFEST, manifest)
    return 0


if __name__ == "__main__":
    sys.exit(main())
