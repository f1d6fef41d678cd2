#!/usr/bin/env bash
# Every test suite, each a timed step (scripts/steps.sh): the Rust build of every test binary,
# the Rust tests (unit and property tests, the end-to-end tests of tests/it, the heavy replays
# of the committed studies in tests/replays), the Python package's tests
# (scripts/python-tests.sh) and, where Slurm is installed or CI runs as root, the Slurm
# job-array test (tests/slurm/smoke-array.sh). .ci/run calls it after formatting, lints and
# the documentation. All the Rust steps share one release build (no debug info): the tests, the
# binary the end-to-end and Python tests drive, and the library the Python extension links
# (the extension's own tests are python/tests: its Rust crate has none).
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/steps.sh

slurm=false
if command -v slurmctld >/dev/null || { [ -n "${CI:-}" ] && [ "$(id -u)" = 0 ]; }; then slurm=true; fi

# Installs that wait on the network and the disk more than on the processors start now, in the
# background, so that they overlap the build: the Python environment and Slurm's packages.
mkdir -p target
trap 'kill $(jobs -p) 2>/dev/null || true' EXIT
bash scripts/python-tests.sh --prepare >target/python-prepare.log 2>&1 &
python_prepare=$!
if $slurm; then
  bash scripts/slurm-local.sh install >target/slurm-install.log 2>&1 &
  slurm_install=$!
fi
# Waits for background job $1, showing its log $2 when it failed.
finished() {
  wait "$1" || { cat "$2" >&2; return 1; }
}

# `--workspace`: the dependencies' features are then those the Python extension (python/)
# builds with, so the covga library is compiled once for both; `--tests` (not `--lib`), so the
# extension's crate, which has no Rust tests, is left to maturin. The unit tests, tests/it and
# tests/replays run one binary after the other, each printing its own time.
step build cargo test --release --workspace --tests --no-run
step rust-tests cargo test --release --workspace --tests
step python-env finished "$python_prepare" target/python-prepare.log
step python bash scripts/python-tests.sh
if $slurm; then
  step slurm-install finished "$slurm_install" target/slurm-install.log
  step slurm bash tests/slurm/smoke-array.sh
else
  echo "slurm: skipped (CI installs slurm-wlm as root; or install it and run tests/slurm/smoke-array.sh)"
fi
