#!/usr/bin/env bash
# The Python package's tests: builds the package's wheel with maturin into the workspace's
# target/ (so the covga library compiled for the Rust tests is linked, not compiled again),
# installs it into a virtual environment with the package's test extras (pytest, pandas,
# pymoo, mypy, nbclient, …), type-checks the package and its pymoo example (`mypy --strict`)
# and runs python/tests (the example notebook included), which compare the package with the
# release binary of this checkout.
#
# The environment lives in $COVGA_CACHE (default ~/.cache/covga) and is kept between runs on
# one machine while python/pyproject.toml and the interpreter stay the same (a stamp of both);
# it is never required: a cold run builds it. COVGA_FRESH_VENV=1 builds it anew.
#
#   bash scripts/python-tests.sh            # everything
#   bash scripts/python-tests.sh --prepare  # only the environment (CI starts it early)
set -euo pipefail
cd "$(dirname "$0")/.."
cache="${COVGA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/covga}"
venv="$cache/python-venv"
stamp="$(cat python/pyproject.toml; python3 -c 'import sys; print(sys.version)')"
stamp=$(printf '%s' "$stamp" | sha256sum | cut -c1-16)

prepare() {
  if [ -z "${COVGA_FRESH_VENV:-}" ] && [ -f "$venv/.covga-stamp" ] && [ "$(cat "$venv/.covga-stamp")" = "$stamp" ]; then
    echo "python: reusing $venv"
    return
  fi
  rm -rf "$venv"
  mkdir -p "$cache"
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --upgrade pip
  # The build backend and the test extras, from pyproject.toml (the package itself comes later).
  local requirements
  requirements=$(python3 - <<'PY'
import re
text = open("python/pyproject.toml").read()
def array(name):
    body = re.search(name + r"\s*=\s*\[(.*?)\]\n", text, re.S).group(1)
    return re.findall(r'"([^"]+)"', re.sub(r"#[^\n]*", "", body))
print("\n".join(array("requires") + array("dependencies") + array("test")))
PY
)
  local specs
  mapfile -t specs <<<"$requirements"
  "$venv/bin/pip" install --quiet "${specs[@]}"
  echo "$stamp" >"$venv/.covga-stamp"
}

prepare
[ "${1:-}" = "--prepare" ] && exit 0

# With the workspace's features (as scripts/test.sh builds): the library is the one maturin links.
cargo build --release --workspace --bin covga
wheels=target/python-wheels
rm -rf "$wheels"
# Same target folder and profile as the Rust tests: maturin links the library they built.
(cd python && "$venv/bin/maturin" build --release --quiet --out "../$wheels")
"$venv/bin/pip" install --quiet --force-reinstall --no-deps "$wheels"/*.whl
# The package's own annotations against its stubs of the compiled module, and the shipped
# example as a user's code typed against the package; one run, its cache kept in target/.
(cd python && MYPYPATH=. "$venv/bin/mypy" --strict --cache-dir ../target/mypy-cache covga examples/pymoo_nsga2.py)
COVGA_BIN="$PWD/target/release/covga" "$venv/bin/pytest" -q python/tests
