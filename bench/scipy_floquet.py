#!/usr/bin/python3
"""Floquet multipliers with SciPy's solve_ivp on the matrices `bladestab stability
--export-matrices FILE.json` writes: the monodromy Φ(T) of ẏ = (A0 + φ(t) B) y, φ = F(t) − F0,
integrated as one matrix ODE Φ' = A(t) Φ, Φ(0) = I (all columns at once, the right-hand side a
matrix product), max|ρ| from numpy.linalg.eigvals(Φ(T)).

  scipy_floquet.py MANIFEST.json --method DOP853 --rtol 1e-6 1e-8 [--atol-factor 1e-3] [--repeats 5]
                   [--budget-s B] [--cap-s C]

prints one JSON object per line and tolerance: method, rtol, atol, times_s (each repeat: the solve
and the eigenvalues, not Python's start or the file reading), median_s, cpu_times_s and
median_cpu_s (the process's CPU time for the same), max_abs_multiplier, nfev,
njev, nlu, success; "capped": true where one solve ran past --cap-s and was given up (the tighter
tolerances after it are not tried). Radau gets the exact Jacobian, block diagonal kron(I, A(t)) in
sparse form.
Only Debian's python3-numpy and python3-scipy are needed.
"""
import argparse
import json
import os
import statistics
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse
from scipy.integrate import solve_ivp


def load_system(manifest_path):
    with open(manifest_path) as f:
        manifest = json.load(f)
    folder = os.path.dirname(os.path.abspath(manifest_path))
    def read(key):
        x = scipy.io.mmread(os.path.join(folder, manifest[key]))
        return x.toarray() if scipy.sparse.issparse(x) else np.asarray(x)
    return manifest, read("A0"), read("B"), read("load").ravel().astype(complex)


class Capped(Exception):
    pass


class Monodromy:
    def __init__(self, A0, B, F, theta):
        self.A0, self.B, self.theta = A0, B, theta
        self.m = np.arange(1, len(F))
        self.F = F[1:]
        self.n = A0.shape[0]
        self.eye = scipy.sparse.identity(self.n, format="csc")
        self.deadline = float("inf")

    def phi(self, t):  # F(t) − F0 = 2 Re Σ_{m≥1} F_m e^{imθt}
        return 2.0 * np.real(np.sum(self.F * np.exp(1j * self.m * self.theta * t)))

    def A(self, t):
        return self.A0 + self.phi(t) * self.B

    def rhs(self, t, y):  # y = Φ in column-major order, so the Jacobian is kron(I, A)
        if time.perf_counter() > self.deadline:
            raise Capped()
        n = self.n
        return (self.A(t) @ y.reshape((n, n), order="F")).ravel(order="F")

    def jac(self, t, y):
        return scipy.sparse.kron(self.eye, scipy.sparse.csc_matrix(self.A(t)), format="csc")

    def run(self, method, period, rtol, atol):
        y0 = np.eye(self.n).ravel(order="F")
        extra = {"jac": self.jac} if method in ("Radau", "BDF", "LSODA") else {}
        sol = solve_ivp(self.rhs, (0.0, period), y0, method=method, t_eval=[period], rtol=rtol, atol=atol, **extra)
        Phi = sol.y[:, -1].reshape((self.n, self.n), order="F")
        rho = float(np.max(np.abs(np.linalg.eigvals(Phi))))
        return sol, rho


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("manifest")
    p.add_argument("--method", default="DOP853")
    p.add_argument("--rtol", type=float, nargs="+", required=True)
    p.add_argument("--atol-factor", type=float, default=1e-3, help="atol = rtol * this (default 1e-3)")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--budget-s", type=float, default=float("inf"),
                   help="fewer repeats (at least 1) once the repeats of one tolerance would take longer")
    p.add_argument("--cap-s", type=float, default=float("inf"), help="give up a solve that takes longer")
    a = p.parse_args()
    manifest, A0, B, F = load_system(a.manifest)
    system = Monodromy(A0, B, F, manifest["theta_rad_s"])
    period = manifest["period_s"]
    for rtol in a.rtol:
        atol = rtol * a.atol_factor
        times, cpu, rho, sol = [], [], None, None
        capped = False
        for k in range(a.repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            system.deadline = t0 + a.cap_s
            try:
                sol, rho = system.run(a.method, period, rtol, atol)
            except Capped:
                capped = True
            times.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
            if capped or sum(times) / len(times) * a.repeats > a.budget_s:
                break
        if capped:
            print(json.dumps({"manifest": a.manifest, "states": system.n, "method": a.method, "rtol": rtol,
                              "atol": atol, "capped": True, "cap_s": a.cap_s, "times_s": times}), flush=True)
            break
        print(json.dumps({"manifest": a.manifest, "states": system.n, "method": a.method, "rtol": rtol, "atol": atol,
                          "times_s": times, "median_s": statistics.median(times), "cpu_times_s": cpu,
                          "median_cpu_s": statistics.median(cpu), "max_abs_multiplier": rho,
                          "nfev": int(sol.nfev), "njev": int(sol.njev), "nlu": int(sol.nlu),
                          "success": bool(sol.success), "message": sol.message}), flush=True)


if __name__ == "__main__":
    sys.exit(main())
