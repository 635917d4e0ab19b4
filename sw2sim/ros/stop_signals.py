"""The signals that ask `sw2sim ros` to stop: SIGINT (Ctrl-C), SIGTERM (`kill`, a service
manager) and SIGHUP (its terminal closed).

Each becomes a `Stopped` exception in the main thread, so that the run's `finally` stops
what it started. The handlers are set whatever the signals' inherited state: a process
started in the background of a shell without job control (a script's `cmd &`) inherits
SIGINT ignored, and Python then leaves it ignored, so that Ctrl-C or `kill -INT` did
nothing at all. The exit status is 128 + the signal's number, as a shell reports a
process the signal ended: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP.

Only the first signal raises: a second one (Ctrl-C pressed twice) does not interrupt the
stopping the first began. Once the run is stopping for another reason (its --duration is
over, its nodes died), `hold()` keeps a first signal from interrupting that too.
"""

from __future__ import annotations

import signal
import threading

SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class Stopped(Exception):
    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


class StopSignals:
    """`with StopSignals() as signals:` the handlers are set inside, the previous ones
    restored after. `signals.received` is the first signal's number, or None."""

    def __init__(self):
        self.received: int | None = None
        self._holding = False
        self._previous: dict[int, object] = {}

    def __enter__(self) -> "StopSignals":
        if threading.current_thread() is threading.main_thread():   # where Python allows it
            for sig in SIGNALS:
                self._previous[sig] = signal.signal(sig, self._handle)
        return self

    def __exit__(self, kind, value, trace) -> None:
        for sig, handler in self._previous.items():
            signal.signal(sig, handler)

    def _handle(self, signum, frame) -> None:
        if self.received is None:
            self.received = signum
            if not self._holding:
                raise Stopped(signum)

    def hold(self) -> None:
        """From now on a signal is only noted: the stopping under way goes on."""
        self._holding = True

    @property
    def name(self) -> str:
        return signal.Signals(self.received).name if self.received else ""

    @property
    def exit_status(self) -> int:
        return 128 + self.received if self.received else 0
