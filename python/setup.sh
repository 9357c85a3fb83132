#!/bin/sh
# Build the Python package from this repository into a virtual environment:
#     sh python/setup.sh [VENV]        (default VENV: .venv at the repository root)
# creates VENV if missing, installs the pinned build and test requirements
# (python/requirements.txt) and builds and installs `vibrissa` (release, via maturin).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
venv=${1:-"$root/.venv"}
# absolute: the build runs in another directory and finds maturin on PATH through it
case "$venv" in /*) ;; *) venv="$PWD/$venv" ;; esac
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$root/python/requirements.txt"
# --no-build-isolation: build with the pinned maturin just installed; --locked: with the
# dependency versions of python/Cargo.lock
MATURIN_PEP517_ARGS="${MATURIN_PEP517_ARGS:---locked}" PATH="$venv/bin:$PATH" "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation --force-reinstall --no-deps "$root/python"
echo "vibrissa installed into $venv: $venv/bin/python -c 'import vibrissa'"
