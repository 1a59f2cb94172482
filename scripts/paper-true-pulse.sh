#!/usr/bin/env bash
# The speed plane of the paper blade under its true half-sine pulse train (t̄c = 0.01 of a
# revolution, one pulse per revolution), beside the cosine approximation of the main job, into
# stability_maps/sinha2005/true_pulse/ (or the directory given). Run from the repository root after
# building into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-stability_maps/sinha2005/true_pulse}
mkdir -p "$out"
./build/bladestab map stability_maps/sinha2005/blade.toml --set model.terms=8 --set load.approximation=exact \
  --plane speed-fmax --speeds 50:600:26 --fmax 0:10:26 --trace 111 --resolution 400x200 --engine-order 1 --out "$out"
