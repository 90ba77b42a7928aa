#!/usr/bin/env bash
# Equal-time comparisons of --method vcm / bpt with the other methods (issue 31;
# BENCHMARKS.md "Vertex connection and merging"). Runs one render at a time.
#   scripts/vcm-eq.sh OUTDIR
# Needs the peers' venv (PEERS=mitsuba) for the caustic sphere's reference and metrics,
# and ../shared/assets for the Cornell boxes.
set -euo pipefail
out=$1
V=${PEERS_VENV:-$HOME/.cache/iris-peers/venv}/bin/python
P=${PEERS_DIR:-/work/shared/peers}
A=${IRIS_SHARED_ASSETS:-/work/shared/assets}
I=${IRIS:-target/release/iris}
mkdir -p "$out"
open="--adaptive off --denoise off --spp 1000000 --passes 1000000 --quiet"

# 1. The peers' caustic sphere (point light): Mitsuba ptracer 150 s reference, 20 s each.
mkdir -p target/peers
[ -f target/peers/scenes/caustic_sphere.glb ] || $V "$P/make_scenes.py" --out target/peers/scenes
$V "$P/make_variant.py" --r0 --spec0 target/peers/scenes/caustic_sphere.glb target/peers/cs.glb
export SIZE=128x128 SEED=1
[ -f "$out/mitsuba_ptracer_ref_150s.exr" ] || $V "$P/run_eq.py" target/peers/cs.glb "$out" ref 150 mitsuba_ptracer
for m in vcm bpt sppm path; do
  IRIS_EXTRA="--adaptive off" $V "$P/run_eq.py" target/peers/cs.glb "$out" eq20 20 iris_$m
done
IRIS_EXTRA="--caustics light --adaptive off" $V "$P/run_eq.py" target/peers/cs.glb "$out" lt20 20 iris_hybrid
$V scripts/caustic-peak.py target/peers/cs.glb "$out/mitsuba_ptracer_ref_150s.exr" "$out"/iris_*.exr

# 2. The Cornell boxes seen from the front: BPT 90 s reference (seed 9), 10 s each.
for sc in Original Water; do
  d="$out/cb$sc"; mkdir -p "$d"
  s="$A/obj/CornellBox-McGuire/CornellBox-$sc.obj"
  o="--size 128x128 --view front $open"
  [ -f "$d/ref.exr" ] || $I render "$s" --method bpt --time 90 --seed 9 $o -o "$d/ref.exr"
  for m in path hybrid sppm bpt vcm; do
    $I render "$s" --method $m --time 10 --seed 1 $o -o "$d/$m.exr"
  done
  $V "$P/metrics.py" "$d/ref.exr" "$d"/{path,hybrid,sppm,bpt,vcm}.exr
done

# 3. The glass of water (area lights): path tracer 120 s reference (seed 9), 15 s each.
d="$out/gow"; mkdir -p "$d"
o="--size 256x144 $open"
[ -f "$d/ref.exr" ] || $I render assets/scenes/glass_of_water.glb --method path --time 120 --seed 9 $o -o "$d/ref.exr"
for m in path hybrid bpt vcm; do
  $I render assets/scenes/glass_of_water.glb --method $m --time 15 --seed 1 $o -o "$d/$m.exr"
done
$V "$P/metrics.py" "$d/ref.exr" "$d"/{path,hybrid,bpt,vcm}.exr
