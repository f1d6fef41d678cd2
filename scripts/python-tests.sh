#!/usr/bin/env bash
# The Python package's tests: builds the package into a fresh virtual environment
# (target/python-venv) with its test extras (pytest, pandas, pymoo, mypy, nbclient), type-checks the package and
# its pymoo example (`mypy --strict`) and runs python/tests (the example notebook included),
# which compare the package with the release binary of this checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin covga
venv=target/python-venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --upgrade pip
"$venv/bin/pip" install --quiet "./python[test]"
# The package's own annotations, against its stubs of the compiled module.
(cd python && MYPYPATH=. "../$venv/bin/mypy" --strict --no-incremental covga)
# The shipped example as a user's code: typed against the package.
(cd python && MYPYPATH=. "../$venv/bin/mypy" --strict --no-incremental examples/pymoo_nsga2.py)
COVGA_BIN="$PWD/target/release/covga" "$venv/bin/pytest" -q python/tests
