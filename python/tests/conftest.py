"""Shared helpers: the repository, the `vibrissa` program to compare with, running it."""

import csv
import io
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
SCENES = REPO / "data" / "scenes"


def program_path() -> pathlib.Path:
    """The program to compare with: $VIBRISSA_BIN, else target/release/vibrissa, else
    target/debug/vibrissa (built by `cargo test`; .ci/run uses it). Debug and release builds
    compute the same doubles (no fast-math: the optimizer does not reassociate)."""
    target = REPO / "target"
    default = target / "release" / "vibrissa"
    if not default.exists():
        default = target / "debug" / "vibrissa"
    p = pathlib.Path(os.environ.get("VIBRISSA_BIN", default))
    if not p.exists():
        pytest.fail(
            f"the vibrissa program is not at {p}: build it with `cargo build --release` "
            "(or `cargo test`), or set VIBRISSA_BIN"
        )
    return p


@pytest.fixture(scope="session")
def program():
    """Runs the program with the given arguments; returns its stdout (fails on a non-zero exit)."""
    exe = program_path()

    def run(*args: str) -> str:
        r = subprocess.run([str(exe), *args], capture_output=True, text=True)
        assert r.returncode == 0, f"vibrissa {' '.join(args)}: {r.stderr}"
        return r.stdout

    run.path = exe
    return run


def read_csv(text: str):
    """CSV text as a list of dicts of strings."""
    return list(csv.DictReader(io.StringIO(text)))
