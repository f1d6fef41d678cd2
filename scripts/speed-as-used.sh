#!/usr/bin/env bash
# Times covga as users run it (issue "speed as users meet it"), old binaries against new, each
# run pinned to one core with one thread, the binaries interleaved run by run:
#   the reference experiment (experiments/thesis-map1-elite.toml) for seeds 1-5, with and
#   without output.diversity_every = 10; covga eval --pattern boustrophedon / spiral on a map;
#   on basement (experiments/maps/basement.yaml), the real-map reference run with routed moves
#   (start (0, 0), Elite, init_actions 150, init_dist_max 6, max_genome_len 600, 20 000
#   evaluations) and experiments/cell-order-basement.toml (its set-up and 50 000 evaluations),
#   three times each.
# usage: scripts/speed-as-used.sh MAP_YAML BIG_MAP_IMAGE OUT_DIR BIN...   (the last BIN is the
# newest; only it runs the diversity_every = 10 variant; binaries named in RUN_ONLY, e.g.
# RUN_ONLY="covga-bc0", time only the reference run). EVAL_THREADS (default 1) lists the
# thread counts eval is timed with: one thread is pinned to one core, n threads to n cores.
# Prints one line per timed command and writes OUT_DIR/times.csv (what, binary, seed or
# repeat, seconds; eval with n > 1 threads is named eval-...-tn).
set -euo pipefail
map=${1:?map yaml}; big=${2:?big map image (0.05 m per pixel)}; out=${3:?out dir}; shift 3
bins=("$@"); newest=${bins[-1]}
mkdir -p "$out"; csv="$out/times.csv"; echo "what,binary,repeat,seconds" > "$csv"
threads=1
pin() { # the last $threads cores
  if command -v taskset >/dev/null; then taskset -c "$(( $(nproc) - threads ))-$(( $(nproc) - 1 ))" "$@"; else "$@"; fi
}
timed() { # what binary repeat command...
  local what=$1 bin=$2 rep=$3; shift 3
  local t0 t1 ms; t0=$(date +%s%N); RAYON_NUM_THREADS=$threads pin "$@" >/dev/null 2>&1 || { echo "FAILED: $*"; return 0; }
  t1=$(date +%s%N); ms=$(( (t1 - t0) / 1000000 ))
  printf '%s,%s,%s,%d.%03d\n' "$what" "$(basename "$bin")" "$rep" $((ms / 1000)) $((ms % 1000)) >> "$csv"
  printf '%-28s %-14s %s %d.%03d s\n' "$what" "$(basename "$bin")" "$rep" $((ms / 1000)) $((ms % 1000))
}
for seed in 1 2 3 4 5; do
  for div in 1 10; do
    f="$out/ref-$seed-$div.toml"
    sed "s/^seed = .*/seed = $seed/; s|^dir = .*|dir = \"$out/run\"|" experiments/thesis-map1-elite.toml > "$f"
    [ "$div" = 10 ] && printf 'diversity_every = 10\n' >> "$f"
  done
  for bin in "${bins[@]}"; do
    rm -rf "$out/run"; timed run-reference "$bin" "$seed" "$bin" run "$out/ref-$seed-1.toml"
  done
  rm -rf "$out/run"; timed run-reference-div10 "$newest" "$seed" "$newest" run "$out/ref-$seed-10.toml"
done
for rep in 1 2 3; do
  for threads in ${EVAL_THREADS:-1}; do
    suffix=$([ "$threads" = 1 ] || echo "-t$threads")
    for bin in "${bins[@]}"; do
      case " ${RUN_ONLY:-} " in *" $(basename "$bin") "*) continue ;; esac
      for pattern in boustrophedon spiral; do
        timed "eval-$pattern$suffix" "$bin" "$rep" "$bin" eval --map "$map" --pattern "$pattern" --out "$out/eval"
      done
      timed "eval-big-boustrophedon$suffix" "$bin" "$rep" "$bin" eval --map "$big" --resolution 0.05 \
        --pattern boustrophedon --start 25.3,10.1 --out "$out/eval-big"
    done
  done
done
cat > "$out/routed-basement.toml" <<TOML
seed = 1
planner = "thesis"
[map]
source = "experiments/maps/basement.yaml"
[stations]
start = [0.0, 0.0]
[thesis]
selection = "elite"
pop_min = 100
init_actions = 150
init_dist_max = 6.0
max_genome_len = 600
moves = "routed"
[budget]
iterations = 1000000
evaluations = 20000
TOML
threads=1
for rep in 1 2 3; do
  for bin in "${bins[@]}"; do
    case " ${RUN_ONLY:-} " in *" $(basename "$bin") "*) continue ;; esac
    rm -rf "$out/run"; timed run-routed-basement "$bin" "$rep" "$bin" run "$out/routed-basement.toml" --out "$out/run"
    rm -rf "$out/run"; timed run-cell-order-basement "$bin" "$rep" "$bin" run experiments/cell-order-basement.toml --out "$out/run"
  done
done
