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
  # "512x512, 26 spp, ..." or, adaptive, "512x512, 32 to 90 (mean 53.3) spp, ..."
  spp=$(echo "$line" | sed -E 's/.*[0-9]+x[0-9]+, (.*) spp, [0-9]+ triangles.*/\1/' \
    | sed -E 's/^([0-9]+) to ([0-9]+) \(mean ([0-9.]+)\)$/\3 (\1–\2)/')
  secs=$(echo "$line" | grep -o 'render [0-9.]* s' | head -1 | cut -d' ' -f2)
  echo "$2 · $spp spp in $secs s · ${3:-4 λ}"
}

compose() { # one side-by-side image: indicatrix-vs-iris compose ARGS, its numbers to $STATS
  "$BIN" compose "$@" | tee -a "$STATS"
  echo >> "$STATS"
}

FOOT="same stone (Iris's Tolkowsky mesh), face-up camera (100 radii, FOV 1.32°), display (indicatrix's ACES), no denoising"

for S in $STONES; do
  for L in $LIGHTINGS; do
    case $L in
      tent) what="light tent + white tray" ;;
      ring) what="studio ring lights" ;;
    esac
    if [ "$S" = moissanite ]; then lam="Stokes, 4 λ until the stone, then 1"; else lam="4 λ"; fi
    compose --glb "$OUT/$S.glb" \
      --left "$R/ix_${S}_${L}_s0.exr" --left2 "$R/ix_${S}_${L}_s1.exr" \
      --right "$R/iris_${S}_${L}_s0.exr" --right2 "$R/iris_${S}_${L}_s1.exr" \
      --label-left "indicatrix 0.9.0 — $S, $what" \
      --sub-left "$(ix_sub "ix_${S}_${L}_s0" "analytic studio")" \
      --label-right "Iris — $S, $what" \
      --sub-right "$(iris_sub "iris_${S}_${L}_s0" "baked: --env env_$L.exr" "$lam")" \
      --footer "$FOOT" \
      --out "$OUT/side_${S}_${L}.png"
  done
  if [ -f "$R/ixbaked_${S}_tent_s0.exr" ]; then
    compose --glb "$OUT/$S.glb" \
      --left "$R/ix_${S}_tent_s0.exr" --right "$R/ixbaked_${S}_tent_s0.exr" \
      --label-left "indicatrix — $S, light tent" \
      --sub-left "$(ix_sub "ix_${S}_tent_s0" "analytic studio")" \
      --label-right "indicatrix — $S, light tent baked" \
      --sub-right "$(ix_sub "ixbaked_${S}_tent_s0" "env_tent map (EnvironmentMap)")" \
      --footer "check of the bake: indicatrix lit by its own studio and by the map Iris gets" \
      --out "$OUT/check_bake_${S}_tent.png"
  fi
done

# Checks (run.sh PHASES=checks).
if [ -f "$R/furnace_iris.exr" ]; then
  for MB in 12 64; do
    compose --glb "$OUT/diamond.glb" \
      --left "$R/furnace_ix_b$MB.exr" --right "$R/furnace_iris.exr" \
      --label-left "indicatrix, $MB bounces" --sub-left "white furnace, 16 spp" \
      --label-right "Iris, --env 1" --sub-right "white furnace, 16 spp" \
      --footer "a lossless stone is 1 everywhere" \
      --out "$OUT/check_furnace_b$MB.png"
  done
fi
if [ -f "$R/irisiso_moissanite_tent_s0.exr" ]; then
  compose --glb "$OUT/moissanite.glb" \
    --left "$R/ix_moissanite_tent_s0.exr" --right "$R/ixiso_moissanite_tent_s0.exr" \
    --label-left "indicatrix — moissanite, birefringent" --sub-left "$(ix_sub ix_moissanite_tent_s0 "light tent")" \
    --label-right "indicatrix — moissanite, one index n_o" --sub-right "$(ix_sub ixiso_moissanite_tent_s0 "light tent")" \
    --footer "indicatrix reflects every mode as a mirror: the birefringent stone looks like the one-index one" \
    --out "$OUT/check_biref_indicatrix.png"
  compose --glb "$OUT/moissanite.glb" \
    --left "$R/iris_moissanite_tent_s0.exr" --right "$R/irisiso_moissanite_tent_s0.exr" \
    --label-left "Iris — moissanite, polarized (birefringent)" --sub-left "$(iris_sub iris_moissanite_tent_s0 "light tent" "Stokes, 4 λ until the stone, then 1")" \
    --label-right "Iris — moissanite, --polarization off (n_o)" --sub-right "$(iris_sub irisiso_moissanite_tent_s0 "light tent")" \
    --footer "Iris conserves n·k_t per mode at internal reflections: the table shows two images ~10° apart" \
    --out "$OUT/check_biref_iris.png"
  compose --glb "$OUT/moissanite.glb" \
    --left "$R/ixiso_moissanite_tent_s0.exr" --right "$R/irisiso_moissanite_tent_s0.exr" \
    --label-left "indicatrix — moissanite, one index n_o" --sub-left "$(ix_sub ixiso_moissanite_tent_s0 "light tent")" \
    --label-right "Iris — moissanite, one index n_o" --sub-right "$(iris_sub irisiso_moissanite_tent_s0 "light tent")" \
    --footer "with one index the two renderers agree, as for diamond" \
    --out "$OUT/check_moissanite_one_index.png"
fi

# Enlarged crops (mean of the two seeds), 200 px at 2x.
for S in $STONES; do
  [ -f "$R/iris_${S}_tent_s1.exr" ] || continue
  compose --glb "$OUT/$S.glb" \
    --left "$R/ix_${S}_tent_s0.exr" --left2 "$R/ix_${S}_tent_s1.exr" \
    --right "$R/iris_${S}_tent_s0.exr" --right2 "$R/iris_${S}_tent_s1.exr" \
    --zoom 20,150,200,2 \
    --label-left "indicatrix — $S, light tent (crop, 2 seeds)" \
    --label-right "Iris — $S, light tent (crop, 2 seeds)" \
    --out "$OUT/zoom_${S}_tent.png" > /dev/null
done
