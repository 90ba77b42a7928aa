#!/usr/bin/env bash
# Seed-to-seed spread of the candidate methods on the scenes `--method auto` decides
# (issue 31; BENCHMARKS.md "Choosing VCM and BPT"). Two seeds per method at equal time;
# prints, per scene and method, the relative RMSE between the seeds (iris diff "relative")
# and the two image means. One render at a time.
#   scripts/auto-evidence.sh OUTDIR SECONDS SIZE "METHODS" SCENE...
# IRIS_EXTRA adds flags to every render. A method written hybrid+light renders `--method hybrid --caustics light`.
set -euo pipefail
out=$1 secs=$2 size=$3 methods=$4
shift 4
I=${IRIS:-target/release/iris}
mkdir -p "$out"
for s in "$@"; do
  n=$(basename "${s%.*}")
  for m in $methods; do
    for seed in 1 2; do
      c=(); [[ $m == *+* ]] && c=(--caustics "${m#*+}")
      $I render "$s" --method "${m%+*}" "${c[@]}" --time "$secs" --seed $seed --size "$size" \
        --adaptive off --denoise off --quiet ${IRIS_EXTRA:-} -o "$out/${n}_${m}_$seed.exr" 2>/dev/null
    done
    d=$($I diff "$out/${n}_${m}_1.exr" "$out/${n}_${m}_2.exr")
    echo "$n $m $(echo "$d" | awk '{print "spread", $4, "means", $8, $11}')"
  done
done
