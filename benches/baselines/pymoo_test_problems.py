"""IGD and GD of pymoo 0.6.2's NSGA-II on the test problems of `hyst::fit::nsga2::test_problems`.

The reference for the thresholds in `host-tools/tests/nsga2.rs`: what an independent, widely used
NSGA-II reaches with the same population (100) and generations (250, the initial one included),
measured with the same sampled fronts (1,000 points, or the non-dominated points of a fine grid)
and the same distances (IGD: mean over the front of the distance to the nearest found point;
GD: mean over the found points of the distance to the nearest front point).

    python benches/baselines/pymoo_test_problems.py [--seeds 5]
"""

import argparse

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.core.problem import ElementwiseProblem
from pymoo.optimize import minimize
from pymoo.problems import get_problem


def non_dominated_2d(points):
    points = points[np.lexsort((points[:, 1], points[:, 0]))]
    front = []
    for p in points:
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return np.array(front)


def zdt_front(kind, samples=1000):
    f1 = np.linspace(0.0, 1.0, samples)
    if kind == "zdt1":
        return np.column_stack([f1, 1 - np.sqrt(f1)])
    if kind == "zdt2":
        return np.column_stack([f1, 1 - f1**2])
    f2 = 1 - np.sqrt(f1) - f1 * np.sin(10 * np.pi * f1)
    return non_dominated_2d(np.column_stack([f1, f2]))


def constr_front(samples=1000):
    f1 = np.linspace(7 / 18, 1.0, samples)
    f2 = np.where(f1 <= 2 / 3, (7 - 9 * f1) / f1, 1 / f1)
    return np.column_stack([f1, f2])


def tnk_front(samples=20001):
    phi = np.linspace(0, np.pi / 2, samples)
    r = np.sqrt(1 + 0.1 * np.cos(16 * phi))
    p = np.column_stack([r * np.sin(phi), r * np.cos(phi)])
    p = p[(p[:, 0] - 0.5) ** 2 + (p[:, 1] - 0.5) ** 2 <= 0.5]
    return non_dominated_2d(p)


class Constr(ElementwiseProblem):
    """Deb's CONSTR, as in test_problems.rs."""

    def __init__(self):
        super().__init__(n_var=2, n_obj=2, n_ieq_constr=2, xl=[0.1, 0.0], xu=[1.0, 5.0])

    def _evaluate(self, x, out, *args, **kwargs):
        out["F"] = [x[0], (1 + x[1]) / x[0]]
        out["G"] = [6 - x[1] - 9 * x[0], 1 + x[1] - 9 * x[0]]


class Tnk(ElementwiseProblem):
    """Tanaka's TNK, as in test_problems.rs."""

    def __init__(self):
        super().__init__(n_var=2, n_obj=2, n_ieq_constr=2, xl=[0.0, 0.0], xu=[np.pi, np.pi])

    def _evaluate(self, x, out, *args, **kwargs):
        out["F"] = [x[0], x[1]]
        out["G"] = [
            1 + 0.1 * np.cos(16 * np.arctan2(x[0], x[1])) - x[0] ** 2 - x[1] ** 2,
            (x[0] - 0.5) ** 2 + (x[1] - 0.5) ** 2 - 0.5,
        ]


def igd(found, reference):
    d = np.linalg.norm(reference[:, None, :] - found[None, :, :], axis=2)
    return d.min(axis=1).mean()


def gd(found, reference):
    return igd(reference, found)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seeds", type=int, default=5)
    args = parser.parse_args()
    cases = [
        ("ZDT1", get_problem("zdt1", n_var=30), zdt_front("zdt1")),
        ("ZDT2", get_problem("zdt2", n_var=30), zdt_front("zdt2")),
        ("ZDT3", get_problem("zdt3", n_var=30), zdt_front("zdt3")),
        ("CONSTR", Constr(), constr_front()),
        ("TNK", Tnk(), tnk_front()),
    ]
    for name, problem, reference in cases:
        igds, gds = [], []
        for seed in range(1, args.seeds + 1):
            res = minimize(problem, NSGA2(pop_size=100), ("n_gen", 250), seed=seed, verbose=False)
            igds.append(igd(res.F, reference))
            gds.append(gd(res.F, reference))
        print(
            f"{name}: IGD min {min(igds):.5f} mean {np.mean(igds):.5f} max {max(igds):.5f}; "
            f"GD min {min(gds):.5f} mean {np.mean(gds):.5f} max {max(gds):.5f} over {args.seeds} seeds"
        )


if __name__ == "__main__":
    main()
