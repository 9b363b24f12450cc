#!/usr/bin/env bash
# Our f64 BWBN element and openseespy's BoucWen/BWBN on the same reference
# history, one after the other in one run (docs/benchmarks.md). Needs
# openseespy 3.7.1.2 (pip install openseespy==3.7.1.2; on Debian its
# libraries need apt-get install libblas3 liblapack3).
set -euo pipefail
cd "$(dirname "$0")/.."
python3 benches/baselines/opensees_bwbn.py --repeats "${REPEATS:-20}" 2>&1 | grep -v '^Process 0 Terminating$' | grep -v '^$'
cargo bench -q --bench bwbn -- --noplot 2>&1 | grep -E '^bwbn|time:|thrpt:'
