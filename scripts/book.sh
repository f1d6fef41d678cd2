#!/usr/bin/env bash
# Builds the book (docs/ into docs/book/) with mdbook 0.5.4, installed from crates.io into a
# cache kept between runs on one machine ($COVGA_CACHE, default ~/.cache/covga): the first run
# compiles it (about 2 minutes on 2 cores), later runs find it there.
set -euo pipefail
cd "$(dirname "$0")/.."
version=0.5.4
tools="${COVGA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/covga}/tools"
mdbook="$tools/bin/mdbook"
if ! { [ -x "$mdbook" ] && "$mdbook" --version | grep -qx "mdbook v$version"; }; then
  cargo install mdbook --locked --no-default-features --version "$version" --root "$tools"
fi
"$mdbook" build docs
