#!/usr/bin/env bash
# 003 Figs. 4.2-4.5 (map 1, R_rot = 0) and the whole-study report from a Table 4.3 study folder,
# each figure laid out as the thesis lays it out (rows x columns of the two parameters):
#   covga grid grids/thesis-table-4-3.toml --jobs 2 --out out/thesis-table-4-3
#   scripts/thesis-figures.sh out/thesis-table-4-3
# Writes DIR/report (all runs, by selection), DIR/report-fig-4-{2,3-ts,3-sp,4,5} and
# DIR/report-tables-a1-a2 (the best configuration of each map x R_rot x selection x fitness
# function over seeds, as 003 Tables A.1/A.2 list them).
set -euo pipefail
dir=${1:?usage: scripts/thesis-figures.sh STUDY_DIR}
covga=${COVGA:-covga}
m1=(--where map.source=thesis-1 --where robot.rot_speed=0)
"$covga" report "$dir" --by thesis.selection
"$covga" report "$dir" "${m1[@]}" --by thesis.selection --by scorer.projection --name fig-4-2
"$covga" report "$dir" "${m1[@]}" --where thesis.selection=tournament \
  --by thesis.tournament_size --by scorer.projection --name fig-4-3-ts
"$covga" report "$dir" "${m1[@]}" --where thesis.selection=rrws \
  --by thesis.selection_pressure --by scorer.projection --name fig-4-3-sp
"$covga" report "$dir" "${m1[@]}" --by thesis.c_len --by thesis.c_child --name fig-4-4
"$covga" report "$dir" "${m1[@]}" --by thesis.p_mi --by thesis.p_ma --name fig-4-5
"$covga" report "$dir" --by map.source --by robot.rot_speed --by thesis.selection --by scorer.projection \
  --name tables-a1-a2
