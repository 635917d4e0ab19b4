"""One command of a page's ```bash block, run by bash to its end as in the reader's
terminal: what it changes of the shell (`cd`, `export`, `source ...`) is read back, so
that the page's next command starts from it."""

from __future__ import annotations

import subprocess
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Finished:
    done: subprocess.CompletedProcess   # status and output
    cwd: Path                          # the folder the shell was in at the end
    env: dict[str, str]                # its environment at the end


def finish(text: str, cwd: Path, env: dict[str, str], state: Path,
           timeout: float) -> Finished:
    """Run `text` with bash in `cwd` and `env`, in a session of its own (Ctrl-C reaches
    it); `state` names the files the shell's folder and environment are written to.
    Raises subprocess.TimeoutExpired when it does not end within `timeout` seconds."""
    from sw2sim.ros.run import with_ctrl_c
    script = (f"{text}\nstatus=$?\npwd > '{state}.cwd'\nenv -0 > '{state}.env'\n"
              "exit $status\n")
    done = subprocess.run(["bash", "-c", script], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=timeout, start_new_session=True,
                          preexec_fn=with_ctrl_c)
    try:
        cwd = Path(Path(f"{state}.cwd").read_text().strip())
        pairs = Path(f"{state}.env").read_bytes().decode(errors="replace").split("\0")
        env = dict(p.split("=", 1) for p in pairs if "=" in p)
    except OSError:   # the command ended the shell itself (`exit`)
        pass
    return Finished(done, cwd, env)


def start(text: str, cwd: Path, env: dict[str, str], log: Path) -> subprocess.Popen:
    """Start `text` with bash in the background, as in a terminal of its own: in a session
    (and process group) of its own that Ctrl-C reaches, its output in `log`."""
    from sw2sim.ros.run import with_ctrl_c
    with open(log, "wb") as out:
        return subprocess.Popen(["bash", "-c", text], cwd=cwd, env=env, stdout=out,
                                stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                start_new_session=True, preexec_fn=with_ctrl_c)
