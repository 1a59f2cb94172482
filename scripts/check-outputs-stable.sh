#!/usr/bin/env bash
# Does a regeneration of the main job leave the committed outputs as they are (docs/outputs.md)?
# Runs scripts/paper-charts.sh into a scratch directory and compares every file it writes, byte for
# byte, with its namesake in stability_maps/sinha2005/ (the fan blade's, fan_blade/, in
# stability_maps/fan_blade/); names the files that differ and exits 1 if
# any does. As long as the main job (1–2 minutes of both cores). Run after building into build/;
# OPENBLAS_CORETYPE=Haswell (Prescott, Zen, …) before the command runs it on other BLAS kernels.
set -euo pipefail
cd "$(dirname "$0")/.."
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
bash scripts/paper-charts.sh "$scratch" > /dev/null
count=0 differ=0
while IFS= read -r -d '' file; do
  committed=stability_maps/sinha2005/${file#"$scratch"/}
  case "$file" in "$scratch"/fan_blade/*) committed=stability_maps/fan_blade/${file#"$scratch"/fan_blade/} ;; esac
  count=$((count + 1))
  if ! cmp -s "$file" "$committed"; then
    echo "differs: $committed"
    differ=$((differ + 1))
  fi
done < <(find "$scratch" -type f -print0 | sort -z)
echo "$((count - differ)) of $count files of the main job as committed in stability_maps/"
[ "$differ" -eq 0 ]
