#!/usr/bin/env bash
# Equal-time light-traced caustic runs on the peers' caustic sphere (issue 31), then
# scripts/caustic-peak.py against a reference (BENCHMARKS.md "Light-traced caustics").
#   scripts/caustic-peak-eq.sh OUTDIR BUDGET_S REF.exr [REF_SHIFT]
# Needs the peers' venv (PEERS=luxcore,mitsuba) and target/peers/cs.glb (peers README).
set -euo pipefail
out=$1 budget=$2 ref=$3 shift_rows=${4:-0}
V=${PEERS_VENV:-$HOME/.cache/iris-peers/venv}/bin/python
P=${PEERS_DIR:-/work/shared/peers}
scene=target/peers/cs.glb
mkdir -p "$out"
export SIZE=${SIZE:-128x128} SEED=${SEED:-1}
IRIS_EXTRA="--caustics light --adaptive off" $V "$P/run_eq.py" "$scene" "$out" lt "$budget" iris_hybrid
IRIS_EXTRA="--adaptive off" $V "$P/run_eq.py" "$scene" "$out" lt "$budget" iris_sppm
$V "$P/run_eq.py" "$scene" "$out" lt "$budget" lx_pathhyb mitsuba_ptracer
$V "$(dirname "$0")/caustic-peak.py" "$scene" "$ref" --ref-shift "$shift_rows" "$out"/*_"$budget"s.exr
