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
# shellcheck source=scripts/device/python_env.sh
source scripts/device/python_env.sh
jobs=$(nproc)
# smaller runs for a smoke test: SEEDS="100 101" MATCHES=2 DURATION=5 TYPES="0"
seeds=${SEEDS:-$(seq -s ' ' 100 131)}
types=${TYPES:-0 1 2 3 4}
matches=${MATCHES:-16}
export DURATION=${DURATION:-120}
off="--set dfdl.controller.default.touch_reach=.inf --set lfdl.controller.default.touch_reach=.inf"
# shellcheck disable=SC2086
$python benchmarks/dribble.py --types $types --seeds $seeds --distance 10 --jobs "$jobs" \
  >"$out/dribble_planner_seeds100-131.txt" 2>&1
# shellcheck disable=SC2086
$python benchmarks/dribble.py --types $types --seeds $seeds --distance 10 --jobs "$jobs" \
  $off >"$out/dribble_no_planner_seeds100-131.txt" 2>&1
play_matches() {  # label, checkout to play from (its own scripts/device/match_sets.sh)
  local label=$1 tree=$2
  PYTHON=$python "$tree/scripts/device/match_sets.sh" 1 "$matches" "$out/$label"
  mv "$out/$label/match3_seeds1-$matches.txt" "$out/match3_${label}_seeds1-$matches.txt"
  rmdir "$out/$label"
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
