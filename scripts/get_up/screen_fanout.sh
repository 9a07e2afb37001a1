#!/usr/bin/env bash
# Screen get-up variants on many never-tuned falls at once: sixteen
# scripts/get_up/screen_sequences.py processes, one per core, each on five benchmark seeds
# (S = 100000 + 500 i, i = 0..79: 1600 type-3 trials per variant), the base and every
# variant of VARIANTS_FILE (one screen_sequences variant per line) on the same falls.
#   PYTHON=.venv/bin/python LIMIT_S=290 scripts/get_up/screen_fanout.sh VARIANTS_FILE OUT_DIR
# Each process writes OUT_DIR/screen_J.log; its "seed S (20 trials): N N ..." lines hold the
# trials up per variant (base first, then the file's order). LIMIT_S stops a process that
# runs long (its finished seeds stay in its log). Sum them with
# scripts/get_up/sum_screens.py OUT_DIR.
set -euo pipefail
variants=${1:?usage: screen_fanout.sh VARIANTS_FILE OUT_DIR}
out=${2:?usage: screen_fanout.sh VARIANTS_FILE OUT_DIR}
python=${PYTHON:-.venv/bin/python}
limit=${LIMIT_S:-3600}
mkdir -p "$out"
mapfile -t lines <"$variants"
args=(--variant base)
for v in "${lines[@]}"; do args+=(--variant "$v"); done
for j in $(seq 0 15); do
  seeds=()
  for i in 0 1 2 3 4; do seeds+=(--seed $((100000 + 500 * (5 * j + i)))); done
  timeout "$limit" "$python" scripts/get_up/screen_sequences.py --types 3 "${seeds[@]}" \
    "${args[@]}" >"$out/screen_$j.log" 2>&1 &
done
wait
