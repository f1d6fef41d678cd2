#!/usr/bin/env bash
# Path figures of the heterogeneous three-robot fleet on thesis map 1 (one colour per robot),
# planned centrally, by negotiation and by area division, for results/fleets/.
#   bash scripts/fleet-figures.sh [covga binary]
set -euo pipefail
covga=${1:-target/release/covga}
out=results/fleets/figures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
sed 's/mode = "negotiate"/mode = "divide"/' experiments/fleet-thesis1-hetero.toml > "$tmp/divide.toml"
for mode in central negotiate divide; do
  case $mode in
    central) file=experiments/fleet-thesis1-hetero-central.toml ;;
    negotiate) file=experiments/fleet-thesis1-hetero.toml ;;
    divide) file=$tmp/divide.toml ;;
  esac
  "$covga" run "$file" --out "$tmp/$mode" --quiet
  cp "$tmp/$mode/path.png" "$out/thesis1-hetero3-$mode.png"
done
echo "wrote $out"
