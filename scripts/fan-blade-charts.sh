#!/usr/bin/env bash
# The example tapered, pretwisted fan blade of stability_maps/fan_blade/ (docs/guide/scenes.md,
# section tables; docs/theory.md §9): its Campbell diagram with the flap and edge families and its
# speed-plane stability map, written to stability_maps/fan_blade/ (or the directory given). Part of
# the main job (scripts/paper-charts.sh). Run from the repository root after building into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=stability_maps/fan_blade/blade.toml
out=${1:-stability_maps/fan_blade}
mkdir -p "$out"
./build/bladestab campbell "$scene" --speeds 0:1000:51 --engine-orders 1,2,3,4,5,6,7,8 --count 8 --out "$out"
./build/bladestab map "$scene" --set model.terms=8 --plane speed-fmax --speeds 100:1000:19 --fmax 0:4:17 --trace 111 --resolution 300x150 --engine-order 1 --out "$out"
