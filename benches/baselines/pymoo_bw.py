"""Baseline for the Bouc-Wen identification benchmark (issue 3, item 10): pymoo 0.6.2's NSGA-II
with a numba RK4 model, on the 5-parameter example of thesis section 4.4.

The problem, which our side (`hyst fit`) must reproduce exactly:

* Model, thesis eqs (3.3)-(3.4) with A = nu = eta = h = 1 (plain Bouc-Wen), units kN, mm, s:
      u'' + 2 xi w0 u' + alpha w0^2 u + (1 - alpha) w0^2 z = F(t) / m
      z'  = u' - beta |u'| |z|^(n-1) z - gamma u' |z|^n
  m = 500 kg = 5e-4 kN s^2/mm, k = 6 kN/mm, w0^2 = k / m = 12,000 s^-2 (17.4 Hz),
  F(t) = t sin(2 pi t) kN, at rest at t = 0 (u = u' = z = 0).
* Integration: classic fourth-order Runge-Kutta, fixed step dt = 2 ms (500 Hz), t from 0 to
  10 s: 5,000 steps; F is evaluated at t, t + dt/2 and t + dt.
* "Measured" displacement: the model with the true parameters alpha = 0.2, beta = 2,
  gamma = -1, xi = 0.05, n = 1.2, sampled at every step (t = k dt, k = 1..5000), no noise.
  Written to bw_synthetic.csv (`time (s),force (kN),displacement (mm)`, 5,001 rows with t = 0)
  so both sides identify from the same numbers.
* Search box: 50 % to 150 % of each true value (the range of the thesis' starting guesses,
  Table 4.1): alpha [0.1, 0.3], beta [1, 3], gamma [-1.5, -0.5], xi [0.025, 0.075], n [0.6, 1.8].
* Constraints (thesis section 3.4): beta + gamma > 0 and beta - gamma > 0, as pymoo's G <= 0:
  G = (-(beta + gamma), -(beta - gamma)). Every candidate is simulated, feasible or not.
* One objective: the RMS displacement error over the 5,000 samples, in mm. A simulation that
  ends with a non-finite error (it can blow up when beta + gamma < 0) scores 1e30.
* Timing: wall time of `minimize` (and the process' CPU time, which a busy machine disturbs less).
* Optimiser: pymoo NSGA2 with its defaults (SBX eta 15, prob 0.9; PM eta 20; duplicates
  eliminated), population 100, 250 generations (the initial one included): 25,000 evaluations.
  The population is evaluated in one call to a numba function (one thread, or all cores with
  --parallel); numba's compilation is done before the clock starts.

    python benches/baselines/pymoo_bw.py [--seeds 1 2 3] [--parallel] [--csv PATH]
"""

import argparse
import math
import os
import time

import numba
import numpy as np
from numba import njit, prange
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.core.problem import Problem
from pymoo.optimize import minimize

MASS = 5.0e-4  # kN s^2 / mm (500 kg)
STIFFNESS = 6.0  # kN / mm
W0_SQ = STIFFNESS / MASS
W0 = math.sqrt(W0_SQ)
DT = 0.002  # s
STEPS = 5000  # 10 s
TRUE = np.array([0.2, 2.0, -1.0, 0.05, 1.2])  # alpha, beta, gamma, xi, n
NAMES = ["alpha", "beta", "gamma", "xi", "n"]
LOWER = np.array([0.1, 1.0, -1.5, 0.025, 0.6])
UPPER = np.array([0.3, 3.0, -0.5, 0.075, 1.8])
BLOWN_UP = 1.0e30


@njit(cache=False, fastmath=False)
def force(t):
    return t * math.sin(2.0 * math.pi * t)


@njit(cache=False, fastmath=False)
def rhs(t, u, v, z, alpha, beta, gamma, xi, n):
    """Derivatives of (u, u', z)."""
    az = abs(z)
    zn = az**n
    sign_z = 1.0 if z > 0.0 else (-1.0 if z < 0.0 else 0.0)
    du = v
    dv = force(t) / MASS - 2.0 * xi * W0 * v - alpha * W0_SQ * u - (1.0 - alpha) * W0_SQ * z
    dz = v - beta * abs(v) * sign_z * zn - gamma * v * zn
    return du, dv, dz


@njit(cache=False, fastmath=False)
def simulate(p, out, dt=DT):
    """Displacement at t = k dt, k = 0..len(out) - 1, into `out`."""
    alpha, beta, gamma, xi, n = p[0], p[1], p[2], p[3], p[4]
    u, v, z = 0.0, 0.0, 0.0
    out[0] = 0.0
    DT = dt
    for k in range(len(out) - 1):
        t = k * DT
        k1u, k1v, k1z = rhs(t, u, v, z, alpha, beta, gamma, xi, n)
        k2u, k2v, k2z = rhs(t + 0.5 * DT, u + 0.5 * DT * k1u, v + 0.5 * DT * k1v, z + 0.5 * DT * k1z, alpha, beta, gamma, xi, n)
        k3u, k3v, k3z = rhs(t + 0.5 * DT, u + 0.5 * DT * k2u, v + 0.5 * DT * k2v, z + 0.5 * DT * k2z, alpha, beta, gamma, xi, n)
        k4u, k4v, k4z = rhs(t + DT, u + DT * k3u, v + DT * k3v, z + DT * k3z, alpha, beta, gamma, xi, n)
        u += DT / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u)
        v += DT / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
        z += DT / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z)
        out[k + 1] = u


@njit(cache=False, fastmath=False)
def rms_error(p, measured):
    u = np.empty(STEPS + 1)
    simulate(p, u)
    acc = 0.0
    for k in range(1, STEPS + 1):
        d = u[k] - measured[k]
        acc += d * d
    e = math.sqrt(acc / STEPS)
    return e if math.isfinite(e) else BLOWN_UP


@njit(cache=False)
def evaluate_serial(x, measured, f):
    for i in range(x.shape[0]):
        f[i] = rms_error(x[i], measured)


@njit(cache=False, parallel=True)
def evaluate_parallel(x, measured, f):
    for i in prange(x.shape[0]):
        f[i] = rms_error(x[i], measured)


class BoucWenIdentification(Problem):
    def __init__(self, measured, parallel):
        super().__init__(n_var=5, n_obj=1, n_ieq_constr=2, xl=LOWER, xu=UPPER)
        self.measured = measured
        self.kernel = evaluate_parallel if parallel else evaluate_serial
        self.evaluations = 0

    def _evaluate(self, x, out, *args, **kwargs):
        x = np.ascontiguousarray(x, dtype=np.float64)
        f = np.empty(x.shape[0])
        self.kernel(x, self.measured, f)
        self.evaluations += x.shape[0]
        out["F"] = f[:, None]
        out["G"] = np.column_stack([-(x[:, 1] + x[:, 2]), -(x[:, 1] - x[:, 2])])


def write_record(path, measured):
    t = np.arange(STEPS + 1) * DT
    with open(path, "w") as fh:
        fh.write("# Bouc-Wen example of thesis section 4.4, synthetic (benches/baselines/pymoo_bw.py):\n")
        fh.write("# m = 500 kg, k = 6 kN/mm, F = t sin(2 pi t) kN, alpha 0.2, beta 2, gamma -1, xi 0.05, n 1.2,\n")
        fh.write("# RK4 with dt = 2 ms from rest; no noise.\n")
        fh.write("time (s),force (kN),displacement (mm)\n")
        for ti, ui in zip(t, measured):
            fh.write(f"{float(ti)!r},{float(ti) * math.sin(2 * math.pi * float(ti))!r},{float(ui)!r}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, nargs="*", default=[1, 2, 3], help="none: write the record only")
    parser.add_argument("--parallel", action="store_true", help="evaluate each population on all cores (numba prange)")
    parser.add_argument("--csv", default=os.path.join(os.path.dirname(__file__), "bw_synthetic.csv"))
    args = parser.parse_args()

    measured = np.empty(STEPS + 1)
    simulate(TRUE, measured)
    write_record(args.csv, measured)

    # Step-size check of the synthetic record itself: RK4 at dt/4 against dt.
    fine = np.empty(4 * STEPS + 1)
    simulate(TRUE, fine, DT / 4)
    step_error = np.abs(fine[::4] - measured).max()
    print(
        f"measured: peak |u| {np.abs(measured).max():.4f} mm, RMS {math.sqrt(np.mean(measured[1:] ** 2)):.4f} mm; "
        f"RK4 at 2 ms differs from 0.5 ms by at most {step_error:.2e} mm"
    )

    # Compile before timing, and time the model alone.
    f = np.empty(100)
    kernel = evaluate_parallel if args.parallel else evaluate_serial
    kernel(np.tile(TRUE, (100, 1)), measured, f)
    assert f[0] == 0.0, "the true parameters reproduce the record exactly"
    rng = np.random.default_rng(0)
    batch = LOWER + (UPPER - LOWER) * rng.random((2500, 5))
    fb = np.empty(len(batch))
    t0 = time.perf_counter()
    kernel(batch, measured, fb)
    model_rate = len(batch) / (time.perf_counter() - t0)
    threads = numba.get_num_threads() if args.parallel else 1
    print(f"model alone: {model_rate:,.0f} simulations/s ({threads} thread(s), 5,000 RK4 steps each)")

    for seed in args.seeds:
        problem = BoucWenIdentification(measured, args.parallel)
        algorithm = NSGA2(pop_size=100)
        t0, c0 = time.perf_counter(), time.process_time()
        res = minimize(problem, algorithm, ("n_gen", 250), seed=seed, verbose=False)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        n_eval = res.algorithm.evaluator.n_eval
        x = res.X if res.X.ndim == 1 else res.X[0]
        errors = ", ".join(f"{name} {100 * (xi - ti) / abs(ti):+.2f}%" for name, xi, ti in zip(NAMES, x, TRUE))
        print(
            f"seed {seed}: {wall:.2f} s wall ({cpu:.2f} s CPU), {n_eval} evaluations, {n_eval / wall:,.0f} evaluations/s, "
            f"RMS error {float(np.ravel(res.F)[0]):.3e} mm; parameters {errors}"
        )


if __name__ == "__main__":
    main()
