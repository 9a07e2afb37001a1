#!/usr/bin/env bash
# Session 21's check of the dribbles' touch planner on a lent 16-core machine, in one call:
# both dribbles on every type over 32 never-tuned seeds (100-131) with the planner and without
# it (touch_reach .inf), then 16 three-a-side matches of 120 s with it and without it (seeds
# 1-16, as runs/bounce_default/match3_s1.txt). Outputs go to $OUT (or the folder
# given). Needs the packed simulation stack (scripts/device/pack_python.sh .pyb/py.tar.xz).
#
#   scripts/device/touch_planner_check.sh OUT_DIR        # about 6 minutes on 16 cores
set -euo pipefail
out=${1:-${OUT:?usage: touch_planner_check.sh OUT_DIR}}
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$(dirname "$0")/../.."
if [ -f .pyb/py.tar.xz ]; then
  mkdir -p /tmp/b && tar xJf .pyb/py.tar.xz -C /tmp/b
  b=/tmp/b/py
  export LD_LIBRARY_PATH=$b/lib PYTHONHOME=$b PYTHONPATH=$b/site:$PWD PYTHONNOUSERSITE=1
  python=$b/bin/python3.11
else
  python=$PWD/.venv/bin/python
fi
jobs=$(nproc)
# smaller runs for a smoke test: SEEDS="100 101" MATCHES=2 DURATION=5 TYPES="0"
seeds=${SEEDS:-$(seq -s ' ' 100 131)}
types=${TYPES:-0 1 2 3 4}
matches=${MATCHES:-16}
duration=${DURATION:-120}
off="--set dfdl.controller.default.touch_reach=.inf --set lfdl.controller.default.touch_reach=.inf"
# shellcheck disable=SC2086
$python benchmarks/dribble.py --types $types --seeds $seeds --distance 10 --jobs "$jobs" \
  >"$out/dribble_planner_seeds100-131.txt" 2>&1
# shellcheck disable=SC2086
$python benchmarks/dribble.py --types $types --seeds $seeds --distance 10 --jobs "$jobs" \
  $off >"$out/dribble_no_planner_seeds100-131.txt" 2>&1
play_matches() {  # label, checkout to play from
  local label=$1 tree=$2
  seq 1 "$matches" | xargs -P "$jobs" -I{} sh -c \
    "cd $tree && PYTHONPATH=$tree:\${PYTHONPATH:-} $python benchmarks/match.py --players 3 \
    --matches 1 --duration $duration --seed {} >$out/match3_${label}_seed{}.txt 2>&1"
  for s in $(seq 1 "$matches"); do grep '^# match' "$out/match3_${label}_seed$s.txt"; done \
    >"$out/match3_${label}_seeds1-$matches.txt"
  rm -f "$out/match3_${label}"_seed[0-9]*.txt
}
play_matches planner "$PWD"
# matches read the packaged dribble.yaml: play the ones without the planner from a copy of the
# checkout whose dribble.yaml has it off
copy=$(mktemp -d)
tar cf - --exclude=./.venv --exclude=./.pyb --exclude=./.git . | (cd "$copy" && tar xf -)
sed -i 's/^\( *touch_reach:\) .*/\1 .inf/' "$copy/behaviors/data/dribble.yaml"
(cd "$copy" && PYTHONPATH=$copy:${PYTHONPATH:-} $python -c "from behaviors.dribble import \
dribble_gait as g; print('touch_reach in the copy:', g('lfdl', 0).touch_reach, g('dfdl', 0).touch_reach)") \
  >"$out/no_planner_check.txt"
play_matches no_planner "$copy"
rm -rf "$copy"
