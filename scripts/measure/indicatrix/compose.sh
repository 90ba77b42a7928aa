#!/usr/bin/env bash
# Side-by-side PNGs and the numbers from the renders run.sh made (README.md).
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-/work/indicatrix-out}
STONES=${STONES:-"diamond moissanite"}
LIGHTINGS=${LIGHTINGS:-"tent ring"}
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/work/target-indicatrix}
BIN=$CARGO_TARGET_DIR/release/indicatrix-vs-iris
R=$OUT/renders
STATS=$OUT/stats.txt
: > "$STATS"

ix_sub() { # the spp and time of an indicatrix render
  local spp secs
  spp=$(awk '/^spp /{print $2}' "$R/$1.txt")
  secs=$(awk '/^seconds /{print $2}' "$R/$1.txt")
  echo "$2 · $spp spp in $secs s · 8 λ, Stokes"
}

iris_sub() { # the spp and time of an Iris render
  local line spp secs
  line=$(grep '^iris:' "$R/$1.log" | head -1)
  spp=$(echo "$line" | grep -o '[0-9]* spp' | head -1)
  secs=$(echo "$line" | grep -o 'render [0-9.]* s' | head -1 | cut -d' ' -f2)
  echo "$2 · $spp in $secs s · 4 λ"
}

FOOT="same stone (Iris's Tolkowsky mesh), face-up camera (100 radii, FOV 1.32°), display (indicatrix's ACES), no denoising"

for S in $STONES; do
  for L in $LIGHTINGS; do
    case $L in
      tent) what="light tent + white tray" ;;
      ring) what="studio ring lights" ;;
    esac
    if [ "$S" = moissanite ]; then pol=" · Stokes"; else pol=""; fi
    "$BIN" compose --glb "$OUT/$S.glb" \
      --left "$R/ix_${S}_${L}_s0.exr" --left2 "$R/ix_${S}_${L}_s1.exr" \
      --right "$R/iris_${S}_${L}_s0.exr" --right2 "$R/iris_${S}_${L}_s1.exr" \
      --label-left "indicatrix 0.9.0 — $S, $what" \
      --sub-left "$(ix_sub "ix_${S}_${L}_s0" "analytic studio")" \
      --label-right "Iris — $S, $what" \
      --sub-right "$(iris_sub "iris_${S}_${L}_s0" "baked: --env env_$L.exr${pol}")" \
      --footer "$FOOT" \
      --out "$OUT/side_${S}_${L}.png" | tee -a "$STATS"
    echo >> "$STATS"
  done
  if [ -f "$R/ixbaked_${S}_tent_s0.exr" ]; then
    "$BIN" compose --glb "$OUT/$S.glb" \
      --left "$R/ix_${S}_tent_s0.exr" --right "$R/ixbaked_${S}_tent_s0.exr" \
      --label-left "indicatrix — $S, light tent" \
      --sub-left "$(ix_sub "ix_${S}_tent_s0" "analytic studio")" \
      --label-right "indicatrix — $S, light tent baked" \
      --sub-right "$(ix_sub "ixbaked_${S}_tent_s0" "env_tent map (EnvironmentMap)")" \
      --footer "check of the bake: indicatrix lit by its own studio and by the map Iris gets" \
      --out "$OUT/check_bake_${S}_tent.png" | tee -a "$STATS"
    echo >> "$STATS"
  fi
done
