#!/usr/bin/env bash
# Issue 34: a round brilliant by indicatrix 0.9.0 and by Iris, side by side (README.md).
# Everything it writes goes to $OUT (default /work/indicatrix-out), nothing into the repo.
#
#   scripts/measure/indicatrix/run.sh            # T=60 s per render, 512x512, 2 threads
#   T=20 SIZE=256 scripts/measure/indicatrix/run.sh
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-/work/indicatrix-out}
IRIS=${IRIS:-/work/main/target/release/iris}
T=${T:-60}
SIZE=${SIZE:-512}
THREADS=${THREADS:-2}
STONES=${STONES:-"diamond moissanite"}
LIGHTINGS=${LIGHTINGS:-"tent ring"}
# indicatrix's own default is 12 bounces; Iris does not count smooth (delta) bounces against
# --max-depth at all (up to 1024, src/shading/step.rs), so indicatrix gets 64 here (white
# furnace: 0.996 of the light kept at 64, 0.968 at 12).
BOUNCES=${BOUNCES:-64}
PHASES=${PHASES:-"main checks"}   # main: the side-by-side renders; checks: furnace, one-index controls
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/work/target-indicatrix}

cargo build --release --manifest-path "$HERE/Cargo.toml"
BIN=$CARGO_TARGET_DIR/release/indicatrix-vs-iris
R=$OUT/renders
mkdir -p "$R"
LOG=$OUT/run.log
{
  echo "== $(date -u +%FT%TZ) run.sh T=$T SIZE=$SIZE THREADS=$THREADS BOUNCES=$BOUNCES"
  rustc --version
  "$IRIS" --version
  nproc
} | tee -a "$LOG"

for S in $STONES; do
  "$IRIS" gem --cut round --stone "$S" --bare -o "$OUT/$S.glb"
done
"$BIN" planes --glb "$OUT/diamond.glb" > "$OUT/planes.txt"
head -1 "$OUT/planes.txt" | tee -a "$LOG"
for L in $LIGHTINGS; do
  "$BIN" bake --glb "$OUT/diamond.glb" --lighting "$L" --out "$OUT/env_$L.exr" | tee -a "$LOG"
done
LOOKAT=$("$BIN" iris-camera --glb "$OUT/diamond.glb")
echo "Iris --camera-look-at $LOOKAT" | tee -a "$LOG"

ix() { # NAME ARGS...: one indicatrix render, timed
  local name=$1; shift
  echo "-- $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg) indicatrix $name" | tee -a "$LOG"
  /usr/bin/time -f "process wall %e s, user %U s, sys %S s" -o "$R/$name.time" \
    "$BIN" render --size "$SIZE" --time "$T" --threads "$THREADS" --max-bounces "$BOUNCES" \
    --out "$R/$name" "$@" > /dev/null 2>&1
  grep '^result' "$R/$name.txt" | tee -a "$LOG"
  cat "$R/$name.time" | tee -a "$LOG"
}

iris() { # NAME ARGS...: one Iris render, timed
  local name=$1; shift
  # The checkout's binary may be rebuilt by others between renders: name the one used.
  echo "-- $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg) iris $name (binary $(date -u -r "$IRIS" +%FT%TZ), sha256 $(sha256sum "$IRIS" | cut -c1-16))" | tee -a "$LOG"
  /usr/bin/time -f "process wall %e s, user %U s, sys %S s" -o "$R/$name.time" \
    "$IRIS" render --camera-look-at "$LOOKAT" --ground off --denoise off --threads "$THREADS" \
    --size "${SIZE}x${SIZE}" --time "$T" --explain -o "$R/$name.exr" "$@" > "$R/$name.log" 2>&1
  grep '^iris:' "$R/$name.log" | tee -a "$LOG"
  cat "$R/$name.time" | tee -a "$LOG"
}

if [[ " $PHASES " == *" main "* ]]; then
for S in $STONES; do
  for L in $LIGHTINGS; do
    for SEED in 0 1; do
      [ "${SIDES:-ix iris}" = iris ] || ix "ix_${S}_${L}_s$SEED" --glb "$OUT/$S.glb" --stone "$S" --lighting "$L" --seed "$SEED"
      [ "${SIDES:-ix iris}" = ix ] || iris "iris_${S}_${L}_s$SEED" "$OUT/$S.glb" --stone "$S" --env "$OUT/env_$L.exr" --seed "$SEED"
    done
  done
  # Check of the map: indicatrix itself lit by the baked light tent (an EnvironmentMap)
  # instead of its analytic studio.
  [ "${SIDES:-ix iris}" = iris ] || case " $LIGHTINGS " in *" tent "*)
    ix "ixbaked_${S}_tent_s0" --glb "$OUT/$S.glb" --stone "$S" --lighting tent --env baked ;;
  esac
done
fi

if [[ " $PHASES " == *" checks "* ]]; then
  # White furnace: a uniform white environment and a clear stone; every stone pixel should
  # be exactly 1 (D65 white, Y = 1) if no light is lost. 16 spp, 256x256.
  for MB in 12 64; do
    "$BIN" render --glb "$OUT/diamond.glb" --stone diamond --lighting furnace --size 256 --spp 16 \
      --threads "$THREADS" --max-bounces "$MB" --out "$R/furnace_ix_b$MB" | grep '^result' | tee -a "$LOG"
  done
  "$IRIS" render "$OUT/diamond.glb" --stone diamond --env 1 --camera-look-at "$LOOKAT" --ground off \
    --denoise off --threads "$THREADS" --size 256x256 --spp 16 -q -o "$R/furnace_iris.exr" \
    2>&1 | grep '^iris:' | tee -a "$LOG"
  # Birefringence controls: moissanite with one index (n_o) in both renderers.
  if [[ " $STONES " == *" moissanite "* ]]; then
    ix "ixiso_moissanite_tent_s0" --glb "$OUT/moissanite.glb" --stone moissanite-iso --lighting tent
    iris "irisiso_moissanite_tent_s0" "$OUT/moissanite.glb" --stone moissanite --polarization off \
      --env "$OUT/env_tent.exr"
    python3 "$HERE/birefringence_exit_angles.py" | tee "$OUT/birefringence_exit_angles.txt"
  fi
fi

"$HERE/compose.sh"
