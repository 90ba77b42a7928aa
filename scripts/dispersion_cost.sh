#!/usr/bin/env bash
# What dispersion costs: error against run time on a dispersive scene for the spectral path
# tracer and for RGB transport (which ignores dispersion: every wavelength refracts with n_d),
# both measured against one long spectral reference with `iris diff`.
#   scripts/dispersion_cost.sh [OUTDIR]      (default target/dispersion_cost)
# Prints: transport, spp, render seconds (the renderer's own timing, load excluded), RMSE and
# RMSE relative to the reference mean.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
out=${1:-target/dispersion_cost}
mkdir -p "$out"
iris=target/release/iris
scene=assets/scenes/diamond.glb
size=160x160
secs() { sed -n 's/.* render \([0-9.]*\) s .*/\1/p'; }
"$iris" render "$scene" --method path --spectral on --spp 1024 --size $size --seed 99 \
    -o "$out/reference.exr" --quiet 2>&1 | secs | sed 's/^/reference (1024 spp, seed 99): /;s/$/ s/'
echo "transport spp seconds rmse relative_rmse"
for spp in 4 16 64 256; do
    for mode in off on; do
        t=$("$iris" render "$scene" --method path --spectral $mode --spp $spp --size $size \
            -o "$out/$mode-$spp.exr" --quiet 2>&1 | secs)
        d=$("$iris" diff "$out/$mode-$spp.exr" "$out/reference.exr")
        name=$([ $mode = on ] && echo spectral || echo rgb)
        echo "$name $spp $t $(echo "$d" | awk '{print $2, $4}')"
    done
done
