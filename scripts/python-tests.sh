#!/usr/bin/env bash
# The Python package's tests: builds the package into a fresh virtual environment
# (target/python-venv) with its test extras (pytest, pandas, pymoo), then runs python/tests,
# which compare the package with the release binary of this checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin covga
venv=target/python-venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --upgrade pip
"$venv/bin/pip" install --quiet "./python[test]"
COVGA_BIN="$PWD/target/release/covga" "$venv/bin/pytest" -q python/tests
