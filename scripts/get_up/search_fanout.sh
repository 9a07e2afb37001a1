#!/usr/bin/env bash
# Sixteen independent coordinate searches of type 3's back get-up (learning/get_up_search.py),
# one per core, each on its own bank of 24 fresh falls ending on the back and validated on
# another 24: the "random restarts" that one 2-core session cannot afford. Runs differ in the
# frames they search (sit-up, fold, crouch, squat, rise) and in their falls, so a gain that
# shows on one bank only is visible as such.
#   PYTHON=.venv/bin/python BUDGET_S=380 scripts/get_up/search_fanout.sh OUT_DIR
# Each run writes OUT_DIR/search_K.log (the improvements, the best entry as YAML, the
# validation lines). Seeds: banks 50000 + 1000 K, validation 90000 + 1000 K (the benchmark's
# falls are seeds 3000-3019 + S).
set -euo pipefail
out=${1:?usage: search_fanout.sh OUT_DIR}
python=${PYTHON:-.venv/bin/python}
budget=${BUDGET_S:-380}
mkdir -p "$out"
# "first_frame frames joint_step" for runs 0-15
plans=("0 2 15" "0 2 15" "1 3 15" "1 3 15" "2 4 15" "2 4 15" "2 4 8" "3 5 15" "3 5 15" "3 5 8"
       "4 6 15" "4 6 8" "1 2 8" "1 2 8" "0 6 8" "0 6 15")
for k in "${!plans[@]}"; do
  read -r first frames step <<<"${plans[$k]}"
  "$python" learning/get_up_search.py --sequence get_up_back_type3 --type 3 \
    --direction back,front,left,right --lying-on back --falls 24 \
    --seed $((50000 + 1000 * k)) --validate-seed $((90000 + 1000 * k)) \
    --first-frame "$first" --frames "$frames" --joint-step "$step" --passes 3 \
    --budget-s "$budget" >"$out/search_$k.log" 2>&1 &
done
wait
