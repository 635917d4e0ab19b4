"""Print how long the expensive parts of `make test` take on this machine.

    .venv/bin/python tools/benchmark.py

Figures, not assertions: compare them before and after a change (2-core machines are
the target). Nothing here is run by the tests.
"""

import time
from pathlib import Path

import sw2sim
import mujoco
from sw2sim.media import all_figures
from sw2sim.practices import PRACTICES, ROOT, package_dir
from sw2sim.snippets import find_pages, parse_page, run_page


def timed(label: str, fn, *args, **kwargs):
    start = time.perf_counter()
    result = fn(*args, **kwargs)
    print(f"{label:55} {time.perf_counter() - start:7.2f} s")
    return result


def main() -> None:
    print("== models")
    for practice in PRACTICES:
        pkg = package_dir(practice)
        spec = timed(f"load_package {pkg.name}", sw2sim.load_package, pkg)
        model = timed(f"compile {pkg.name}", spec.compile)
        data = mujoco.MjData(model)
        steps = 5000
        start = time.perf_counter()
        for _ in range(steps):
            mujoco.mj_step(model, data)
        rate = steps / (time.perf_counter() - start)
        print(f"{'step rate ' + pkg.name:55} {rate:7.0f} steps/s ({rate * model.opt.timestep:.0f}x real time)")

    print("== pages (each in a fresh process)")
    for page_path in find_pages(ROOT):
        page = parse_page(page_path, ROOT)
        result = timed(str(page_path.relative_to(ROOT)), run_page, page, ROOT)
        if not result.ok:
            print("   failed")

    print("== figures")
    tmp = Path("/tmp/sw2sim-benchmark")
    tmp.mkdir(exist_ok=True)
    for fig in all_figures():
        timed(fig.output, fig.make, tmp / fig.path.name)


if __name__ == "__main__":
    main()
