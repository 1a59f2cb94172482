#!/usr/bin/python3
"""One revolution of the blade's transient with SciPy's solve_ivp, on the equations
`transient_peers SCENE --export-system FILE.json` writes (the scene's Ritz model, 2n states,
premultiplied by M⁻¹): f̈ = c − K f − C ḟ + F(t) (p_u − G f + p_friction), F(t) the half-sine
pulse train, from the rotating equilibrium, landing on the pulse edges.

  scipy_transient.py FILE.json [--method DOP853] [--rtol 1e-6] [--atol-factor 1e-6] [--revolutions 1]
                     [--repeats 3]

prints one JSON object: method, rtol, atol, times_s (each repeat: the integration only),
median_s, nfev, peak_tip_lateral_m. Only Debian's python3-numpy and python3-scipy are needed.
"""
import argparse
import json
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp


def main():
    p = argparse.ArgumentParser()
    p.add_argument("system")
    p.add_argument("--method", default="DOP853")
    p.add_argument("--rtol", type=float, default=1e-6)
    p.add_argument("--atol-factor", type=float, default=1e-6)
    p.add_argument("--revolutions", type=float, default=1)
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    with open(a.system) as f:
        s = json.load(f)
    n = s["n"]
    K, C, G = (np.array(s[k]) for k in ("K", "C", "G"))
    c, pu, pf, eq, tip = (np.array(s[k]).ravel() for k in ("c", "p_u", "p_friction", "equilibrium", "tip_lateral"))
    peak, tc, T = s["peak_n"], s["contact_s"], s["period_s"]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])

    def force(t):
        tau = t - np.floor(t / T) * T
        return -peak * np.sin(np.pi * tau / tc) if tau < tc else 0.0

    def rhs(t, x):
        dx = A @ x
        dx[n:] += c
        F = force(t)
        if F != 0.0:
            dx[n:] += F * (pu - G @ x[:n] + pf)
        return dx

    t_end = a.revolutions * s["revolution_s"]
    edges = sorted({0.0, t_end} | {e for k in range(int(np.ceil(t_end / T)) + 1)
                                   for e in (k * T, k * T + tc) if 0 < e < t_end})
    times, nfev, peak_tip = [], 0, 0.0
    for _ in range(a.repeats):
        x = eq.copy()
        nfev = 0
        start = time.perf_counter()
        for t0, t1 in zip(edges[:-1], edges[1:]):
            r = solve_ivp(rhs, (t0, t1), x, method=a.method, rtol=a.rtol, atol=a.rtol * a.atol_factor,
                          dense_output=False)
            if not r.success:
                raise SystemExit(f"scipy_transient: {r.message}")
            nfev += r.nfev
            peak_tip = max(peak_tip, float(np.max(np.abs(tip @ r.y[:n]))))
            x = r.y[:, -1]
        times.append(time.perf_counter() - start)
    print(json.dumps({"method": a.method, "rtol": a.rtol, "atol": a.rtol * a.atol_factor, "revolutions": a.revolutions,
                      "times_s": times, "median_s": statistics.median(times), "nfev": nfev,
                      "peak_tip_lateral_m": peak_tip}))


if __name__ == "__main__":
    main()
