"""Steps per second of openseespy's BoucWen and BWBN materials on the OpenSees
reference history, the same 3601 strain steps and parameters that
`cargo bench --bench bwbn` drives through our element (cases.json of
../shared/data/opensees-reference/).

Each case: define the material with testUniaxialMaterial, then for every
step setStrain(u) (which commits) and getStress(). The loop is timed whole,
best of --repeats runs; the Python call overhead is part of what a Python
user pays, so it is reported as is and, separately, the cost of the same
loop with a no-op in place of the two OpenSees calls.

    python3 benches/baselines/opensees_bwbn.py [--repeats 20]
"""

import argparse
import json
import pathlib
import time

import openseespy.opensees as ops

REF = pathlib.Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "opensees-reference"
CASES = ["BoucWen_plain", "BWBN_pinch", "BoucWen_degrade"]


def history():
    rows = (REF / "history.csv").read_text().splitlines()[1:]
    return [float(r.split(",")[1]) for r in rows if r.strip()]


def run_case(command, h):
    ops.wipe()
    args = [a if a != "<tag>" else 1 for a in command[1:]]
    ops.uniaxialMaterial(*args)
    ops.testUniaxialMaterial(1)
    set_strain, get_stress = ops.setStrain, ops.getStress
    start = time.perf_counter()
    peak = 0.0
    for u in h:
        set_strain(u)
        peak = max(peak, abs(get_stress()))
    return time.perf_counter() - start, peak


def empty_loop(h):
    def noop(*_):
        return 0.0

    start = time.perf_counter()
    peak = 0.0
    for u in h:
        noop(u)
        peak = max(peak, abs(noop()))
    return time.perf_counter() - start


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=20)
    args = ap.parse_args()
    cases = json.loads((REF / "cases.json").read_text())["cases"]
    h = history()
    overhead = min(empty_loop(h) for _ in range(args.repeats)) / len(h)
    print(f"openseespy: {len(h)} steps, best of {args.repeats}; python loop alone {overhead * 1e9:.0f} ns/step")
    for name in CASES:
        best, peak = min(run_case(cases[name]["command"], h) for _ in range(args.repeats))
        per = best / len(h)
        print(
            f"  {name:16} {per * 1e9:7.0f} ns/step  {1e-6 / per:6.2f} M steps/s"
            f"  (minus python loop {1e9 * (per - overhead):6.0f} ns/step)  peak {peak:.4f} kN"
        )


if __name__ == "__main__":
    main()
