"""Shared fixtures: the repository, the `covga` binary the CLI comparisons run, small inputs."""

import _thread
import os
import signal
import subprocess
import threading
import warnings
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def interrupt_after(seconds: float) -> threading.Timer:
    """Ctrl-C in `seconds`, as a user's interpreter delivers it: `_thread.interrupt_main` calls
    Python's SIGINT handler, so Python's own (which raises `KeyboardInterrupt`) is put back
    first if a library an earlier test used left another one installed; a warning names it."""
    handler = signal.getsignal(signal.SIGINT)
    if handler is not signal.default_int_handler:
        warnings.warn(f"an earlier test left SIGINT's handler at {handler!r}; Python's own put back")
        signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(seconds, _thread.interrupt_main)
    timer.start()
    return timer


@pytest.fixture(scope="session")
def covga_bin() -> Path:
    """The command-line binary (`COVGA_BIN`, else the release build of this checkout)."""
    path = Path(os.environ.get("COVGA_BIN", REPO / "target" / "release" / "covga"))
    if not path.is_file():
        raise RuntimeError(f"{path}: no covga binary; run `cargo build --release` first or set COVGA_BIN")
    return path


@pytest.fixture()
def cli(covga_bin):
    """Runs `covga ARGS...`; returns the finished process (text output)."""

    def call(*args, check=True):
        done = subprocess.run([str(covga_bin), *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"covga {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
        return done

    return call


SHORT_THESIS = """\
seed = 5
planner = "thesis"
[map]
source = "thesis-1"
[thesis]
pop_min = 30
init_actions = 30
[budget]
iterations = 40
"""


@pytest.fixture()
def short_thesis(tmp_path) -> Path:
    """A thesis experiment of a second or so."""
    path = tmp_path / "short.toml"
    path.write_text(SHORT_THESIS)
    return path
