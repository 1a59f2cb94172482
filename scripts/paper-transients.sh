#!/usr/bin/env bash
# The paper's transient runs on the example blade: Figs. 10/11, 14, 15, 16/17 (60 revolutions
# each) and the clearance-controlled rub of Appendix C (20 revolutions); data and charts into
# stability_maps/sinha2005/transients/. Run from the repository root after building into build/
# (about four minutes on one core).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=stability_maps/sinha2005/blade.toml
out=stability_maps/sinha2005/transients
run() { ./build/bladestab transient "$scene" --set model.terms=8 --revolutions 60 --tolerance 1e-7 --out "$out" "$@"; }
# Figs. 10 and 11: one half-sine pulse, F̄ = 5, t̄c = 0.01, no friction.
run --name fig10_11_single_pulse --set load.pulse_count=1 --set load.fmax_over_fcr=5
# Fig. 14 (μ = 0) and Fig. 15 (μ = 0.2): a pulse every revolution at F̄ = 1, 2, 5, 10.
for mu in 0 0.2; do
  for f in 1 2 5 10; do
    run --name "fig$([ "$mu" = 0 ] && echo 14 || echo 15)_fbar${f}_mu${mu}" --set load.fmax_over_fcr=$f --set load.friction=$mu
  done
done
# Figs. 16 and 17: F̄ = 5, μ = 0, contact time t̄c = 0.01, 0.1, 0.3, 0.5 of a revolution.
for tc in 0.01 0.1 0.3 0.5; do
  run --name "fig16_17_tc${tc}" --set load.fmax_over_fcr=5 --set load.contact_time_rev=$tc
done
# Appendix C / Fig. 19: the displacement-controlled rub. The casing at 3 mm running clearance with a
# 3.03 mm deep, 3.6° half-sine distortion met once per revolution (30 µm interference), μ = 0 and
# 0.2; 20 revolutions each. The tip load is an output.
for mu in 0 0.2; do
  ./build/bladestab transient "$scene" --set model.terms=8 --revolutions 20 --tolerance 1e-7 --out "$out" \
    --name "clearance_bump_mu${mu}" --set load.mode=clearance --set load.intrusion=3.03e-3 --set load.friction=$mu
done
