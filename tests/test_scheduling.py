"""How `make test` shares the tests among its workers (tests/scheduling.py), played with
pytest-xdist's own scheduler and two stand-in workers that finish each test at once."""

from types import SimpleNamespace

from scheduling import scheduling, scope_of

COLLECTION = [
    "tests/course/test_pages.py::test_page[a]",
    "tests/course/test_pages.py::test_page[b]",
    "tests/ros/test_clock.py::test_clock",
    "tests/ros/test_page_blocks.py::test_page_ros_blocks[a]",
    "tests/ros/test_page_blocks.py::test_page_ros_blocks[b]",
    "tests/site/browser/test_lightbox.py::test_phone",
    "tests/site/browser/test_viewer.py::test_loads",
    "tests/tool/test_loader.py::test_one",
    "tests/tool/test_loader.py::test_two",
    "tests/tool/test_package.py::test_three",
]


class Worker:
    """What the scheduler sees of a pytest-xdist worker: the tests it is sent."""

    def __init__(self, name: str):
        self.gateway = SimpleNamespace(id=name)
        self.shutting_down = False
        self.sent: list[int] = []

    def send_runtest_some(self, indices):
        self.sent.extend(indices)

    def shutdown(self):
        self.shutting_down = True


def run(workers: int, stalled: int | None = None) -> list[list[str]]:
    """The tests each worker is sent, in order, when every test ends as soon as it is sent
    (those of worker `stalled` never end)."""
    config = SimpleNamespace(getvalue=lambda name: [f"{workers}*popen"] if name == "tx" else None,
                             option=SimpleNamespace(loadscopereorder=True))
    scheduler = scheduling(config, SimpleNamespace(loadscopesched=lambda *args: None))
    nodes = [Worker(f"gw{n}") for n in range(workers)]
    for node in nodes:
        scheduler.add_node(node)
        scheduler.add_node_collection(node, COLLECTION)
    scheduler.schedule()
    done = {node: 0 for node in nodes}
    running = [node for n, node in enumerate(nodes) if n != stalled]
    while any(done[node] < len(node.sent) for node in running):
        for node in running:
            while done[node] < len(node.sent):
                scheduler.mark_test_complete(node, node.sent[done[node]])
                done[node] += 1
    return [[COLLECTION[i] for i in node.sent] for node in nodes]


def test_units_of_work():
    assert scope_of(COLLECTION[0]) == scope_of(COLLECTION[1]) == "tests/course/test_pages.py"
    # every ROS page is a unit of its own; the browser tests are one unit for the folder
    assert scope_of(COLLECTION[3]) != scope_of(COLLECTION[4])
    assert scope_of(COLLECTION[5]) == scope_of(COLLECTION[6]) == "tests/site/browser/"


def test_the_first_worker_runs_the_ros_tests_from_the_start():
    first, second = run(2)
    assert sorted(first + second) == sorted(COLLECTION), "each test runs once"
    ros = [t for t in COLLECTION if t.startswith("tests/ros/")]
    assert first[:len(ros)] == ros
    assert not any(t.startswith("tests/ros/") for t in second)


def test_the_other_workers_take_the_ros_tests_once_nothing_else_is_left():
    (alone,) = run(1)
    assert sorted(alone) == sorted(COLLECTION)
    # the first worker stuck in its first ROS tests: the second runs all else, then the
    # ROS tests the first has not been sent
    first, second = run(2, stalled=0)
    assert sorted(first + second) == sorted(COLLECTION)
    others = [t for t in COLLECTION if not t.startswith("tests/ros/")]
    assert sorted(second[:len(others)]) == sorted(others)
    assert second[len(others):] and all(t.startswith("tests/ros/") for t in second[len(others):])
    # three workers: only the first is sent ROS tests while there is other work
    first, second, third = run(3)
    assert sorted(first + second + third) == sorted(COLLECTION)
    assert not any(t.startswith("tests/ros/") for t in second + third)
