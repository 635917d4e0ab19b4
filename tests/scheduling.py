"""How `make test` (pytest-xdist, `--dist loadscope`) shares the tests among its workers:
what one unit of work is, and which units go to which worker first.
"""

# Folders whose test modules share session fixtures that are costly to make: the browser
# tests load and audit every page of the site once, for all their modules. Under
# `--dist loadscope` (make test) each such folder goes to one pytest-xdist worker whole,
# instead of each worker making the fixtures again for the modules it was given.
SHARED_SESSION_FOLDERS = ("tests/site/browser/",)


# Modules whose tests are long and share nothing: each test is a unit of its own, so that
# the workers split them (every ROS page runs its own master and simulation).
SPLIT_MODULES = ("tests/ros/test_page_blocks.py", "tests/ros2/test_ros2_page_blocks.py")


# Tests that spend most of their time waiting on processes of their own (a ROS master,
# roslaunch, a simulation running at ten times real time, `sw2sim ros2` at one to five
# times real time with the ROS 2 pages' nodes): the first worker takes them
# from the start, while the others run tests that keep a core busy; the waits then fill
# with the others' work instead of idling the machine at the end of the run.
WAITING_FOLDERS = ("tests/ros/", "tests/ros2/")


def scope_of(nodeid: str) -> str:
    """The unit of work a test belongs to: its folder if listed above, the test itself in
    a split module, else its module."""
    for folder in SHARED_SESSION_FOLDERS:
        if nodeid.startswith(folder):
            return folder
    module = nodeid.split("::", 1)[0]
    return nodeid if module in SPLIT_MODULES else module


def scheduling(config, log):
    """pytest-xdist's loadscope scheduling with the units of scope_of, and the waiting
    folders' units sent to the first worker first (to the others only once nothing else
    is left)."""
    from xdist.scheduler import LoadScopeScheduling

    class Scheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return scope_of(nodeid)

        def _assign_work_unit(self, node) -> None:
            waits = node is self.nodes[0]
            for scope in self.workqueue:
                if scope.startswith(WAITING_FOLDERS) == waits:
                    self.workqueue.move_to_end(scope, last=False)
                    break
            super()._assign_work_unit(node)

    return Scheduling(config, log)
