#!/usr/bin/env bash
# The main job: the paper blade's Campbell diagram and stability maps, written to
# stability_maps/sinha2005/. Run from the repository root after building into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=stability_maps/sinha2005/blade.toml
out=stability_maps/sinha2005
./build/bladestab campbell "$scene" --speeds 0:600:61 --engine-orders 1,2,3,4,5,6,7,8 --count 6 --out "$out"
# Stability maps with the Legendre N = 8 model (the SPEC's reference model for stability),
# the paper's cosine approximation of the one-pulse-per-revolution load.
./build/bladestab map "$scene" --set model.terms=8 --plane theta-fmax --theta 100:1000:26 --fmax 0:10:26 --trace 101 --resolution 400x200 --out "$out"
./build/bladestab map "$scene" --set model.terms=8 --plane speed-fmax --speeds 50:600:26 --fmax 0:10:26 --trace 111 --resolution 400x200 --engine-order 1 --out "$out"
