#!/usr/bin/python3
"""Checks every shaded cell of a stability map against an independent `stability` run.

Usage: scripts/verify-map.py MAP.json [--set section.key=value ...]

For each grid point of the map (θ or Ω, F̄) the verdict the map draws (max|ρ| above its
`stable_below`) is compared with `bladestab stability` at that point with the monodromy at
tolerance 1e-8, whose own verdict comes with its whole error budget. A cell is false where the
two verdicts differ and the stability answer is outside its error estimate of 1. Prints one line
per false cell and a summary; exits 1 if any cell is false.
"""
import concurrent.futures
import csv
import json
import math
import subprocess
import sys


def main():
    path, overrides = sys.argv[1], sys.argv[2:]
    m = json.load(open(path))
    grid = path.replace(".json", "_grid.csv")
    rows = [r for r in csv.DictReader(open(grid))]
    scene, threshold = m["scene"], m["stable_below"]
    speed_plane = m["plane"] == "speed-fmax"
    theta_plane_speed = None
    if not speed_plane:
        theta_plane_speed = json.loads(subprocess.run(
            ["./build/bladestab", "stability", scene, *overrides, "--format", "json", "--tolerance", "1e-2"],
            capture_output=True, text=True).stdout or "{}").get("speed_rad_s")

    def check(row):
        x, fbar, shaded = float(row["x_rad_s"]), float(row["fmax_over_fcr"]), row["max_abs_multiplier"]
        if shaded in ("", "nan") or x <= 0:
            return None
        point = [f"load.fmax_over_fcr={fbar}"]
        point += [f"operation.speed_rad_s={x}"] if speed_plane else [f"load.pulse_frequency_hz={x / (2 * math.pi)}"]
        run = subprocess.run(["./build/bladestab", "stability", scene, *overrides, *point, "--method", "monodromy",
                              "--tolerance", "1e-8", "--format", "json"], capture_output=True, text=True)
        if run.returncode != 0:
            return (x, fbar, float(shaded), None, None, run.stderr.strip())
        a = json.loads(run.stdout)
        return (x, fbar, float(shaded), a["max_abs_multiplier"], a["error_estimate"], None)

    false_cells, checked = [], 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for r in pool.map(check, rows):
            if r is None:
                continue
            checked += 1
            x, fbar, shaded, rho, err, failure = r
            if failure:
                false_cells.append(f"  ({x:g}, {fbar:g}): map {shaded:.6g}, stability failed: {failure}")
                continue
            map_unstable, true_unstable = shaded > threshold, rho > 1 + err
            certain = abs(rho - 1) > err
            if map_unstable != true_unstable and certain:
                false_cells.append(f"  ({x:g}, {fbar:g}): map {shaded:.6g} ({'un' if map_unstable else ''}stable), "
                                   f"stability {rho:.10g} ± {err:.1e}")
    print(f"{path}: {checked} cells checked, {len(false_cells)} false")
    for line in false_cells:
        print(line)
    sys.exit(1 if false_cells else 0)


if __name__ == "__main__":
    main()
