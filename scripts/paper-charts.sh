#!/usr/bin/env bash
# The main job: the paper blade's Campbell diagram, stability maps (the speed plane also for the
# true pulse train) and frequency sweeps, written to
# stability_maps/sinha2005/ (or the directory given: scripts/check-outputs-stable.sh); and the
# example tapered, pretwisted fan blade's, to stability_maps/fan_blade/ (or fan_blade/ in the
# directory given). Run from the repository root after building into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=stability_maps/sinha2005/blade.toml
out=${1:-stability_maps/sinha2005}
./build/bladestab campbell "$scene" --speeds 0:600:61 --engine-orders 1,2,3,4,5,6,7,8 --count 6 --out "$out"
# Stability maps with the Legendre N = 8 model (the SPEC's reference model for stability),
# the paper's cosine approximation of the one-pulse-per-revolution load.
./build/bladestab map "$scene" --set model.terms=8 --plane theta-fmax --theta 100:1000:26 --fmax 0:10:26 --trace 101 --resolution 400x200 --out "$out"
./build/bladestab map "$scene" --set model.terms=8 --plane speed-fmax --speeds 50:600:26 --fmax 0:10:26 --trace 111 --resolution 400x200 --engine-order 1 --out "$out"
# The same speed plane under the true half-sine pulse train, side by side with it (README, `map`).
bash scripts/paper-true-pulse.sh "$out/true_pulse"
# Natural frequencies against the slenderness d̄ (the paper's Figs. 7 and 8, Tables 4 and 5) and
# against a static compressive tip load F_a / F_cr up to just below buckling (Fig. 9a, 9b: the
# paper blade buckles at 0.99923 F_cr at rest and at 4.954 F_cr at 300 rad/s), modes tracked by shape.
./build/bladestab sweep "$scene" --key blade.slenderness --values 0.005:0.1:20 --set operation.speed_rad_s=0 --count 8 --out "$out" --name sweep_slenderness_rest
./build/bladestab sweep "$scene" --key blade.slenderness --values 0.005:0.1:20 --count 8 --out "$out" --name sweep_slenderness_300
./build/bladestab sweep "$scene" --key operation.tip_compression_over_fcr --values 0:0.999:28 --set operation.speed_rad_s=0 --count 8 --out "$out" --name sweep_compression_rest
./build/bladestab sweep "$scene" --key operation.tip_compression_over_fcr --values 0:4.95:23 --count 8 --out "$out" --name sweep_compression_300
# The tapered, pretwisted fan blade: Campbell diagram (flap and edge families) and speed-plane map.
bash scripts/fan-blade-charts.sh "${1:+$1/fan_blade}"
