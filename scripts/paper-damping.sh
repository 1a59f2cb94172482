#!/usr/bin/env bash
# Stability maps of the paper blade with damping, around the principal region of mode 1 at
# 300 rad/s (θ ≈ 2ω₁ = 853 rad/s): undamped, 1 % modal damping and the paper's damping (37),
# C_D = (2ζ/Ω) K_S with ζ = 2 %, into stability_maps/sinha2005/damping/. Run from the
# repository root after building into build/ (about half a minute on two cores). Each map goes
# to its own directory (map_theta_fmax.*).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=stability_maps/sinha2005/blade.toml
out=stability_maps/sinha2005/damping
run() {
  local dir="$out/$1"
  shift
  mkdir -p "$dir"
  ./build/bladestab map "$scene" --set model.terms=8 --plane theta-fmax --theta 650:1000:15 --fmax 0:3:13 \
    --trace 121 --resolution 400x200 --out "$dir" "$@"
}
run undamped
run modal_1pc --set damping.model=modal --set damping.ratio=0.01
run paper_2pc --set damping.model=paper --set damping.ratio=0.02
