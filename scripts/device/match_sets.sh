#!/usr/bin/env bash
# Three-a-side matches of 120 s, one process each, as many at once as the machine has cores:
# seeds FIRST..LAST, one '# match seed S: ...' line each in OUT_DIR/match3_seedsFIRST-LAST.txt
# (what benchmarks/match.py prints per match; sum the goals and falls from those lines). For a
# lent many-core machine; needs the packed simulation stack (scripts/device/pack_python.sh
# .pyb/py.tar.xz), or runs on this checkout's .venv.
#
#   scripts/device/match_sets.sh 17 48 OUT_DIR        # 32 matches: about 4 minutes on 16 cores
set -euo pipefail
first=${1:?usage: match_sets.sh FIRST LAST OUT_DIR}
last=${2:?usage: match_sets.sh FIRST LAST OUT_DIR}
out=${3:?usage: match_sets.sh FIRST LAST OUT_DIR}
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$(dirname "$0")/../.."
# shellcheck source=scripts/device/python_env.sh
source scripts/device/python_env.sh
seq "$first" "$last" | xargs -P "$(nproc)" -I{} sh -c \
  "$python benchmarks/match.py --players 3 --matches 1 --duration ${DURATION:-120} --seed {} \
  >$out/match3_seed{}.txt 2>&1"
for s in $(seq "$first" "$last"); do grep '^# match' "$out/match3_seed$s.txt"; done \
  >"$out/match3_seeds$first-$last.txt"
rm -f "$out"/match3_seed[0-9]*.txt
