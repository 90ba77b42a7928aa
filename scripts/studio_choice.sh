#!/bin/bash
# The default-studio evidence (BENCHMARKS.md "Default studio for gems"): the four bare
# diamond cuts under soft, jeweller and bright; fire, brilliance, contrast, scintillation.
# usage: scripts/studio_choice.sh IRIS_BIN OUTDIR   (PYTHON with numpy, OpenEXR, Pillow)
set -e
HERE="$(cd "$(dirname "$0")" && pwd)"
B=$1; O=$2; mkdir -p $O; cd $O
for cut in round emerald oval pear; do
  [ -f $cut.glb ] || $B gem --cut $cut --stone diamond --bare -o $cut.glb >/dev/null
  for st in soft jeweller bright; do
    n=${cut}_$st
    $B render $cut.glb -o ${n}_mask.png --size 288x216 --method whitted --spp 4 --ground off --background transparent --studio $st -q >/dev/null
    $B render $cut.glb -o ${n}_N.exr --size 288x216 --method path --spp 64 --seed 1 --studio $st -q >/dev/null
    $B render $cut.glb -o ${n}_4N.exr --size 288x216 --method path --spp 256 --seed 2 --studio $st -q >/dev/null
    $B render $cut.glb -o ${n}_4N.png --size 288x216 --method path --spp 256 --seed 2 --studio $st -q >/dev/null
    "${PYTHON:-python3}" "$HERE/gem_look.py" $n
  done
done
