#!/usr/bin/env bash
# The main job: set up, check every model against published values, run the B1
# simulation (paper sect. 4) and draw its figures.
#   results/b1.nc      the run (netCDF, xarray; SI units in every variable's attributes)
#   results/plots/     figs. 8-13 of the paper and the roller loads (PNG and SVG)
# Extra arguments go to `rollerdyn run` (e.g. --t-end 0.8 for a shorter run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/rollerdyn validate
mkdir -p results
status=0
.venv/bin/rollerdyn run examples/b1.toml -o results/b1.nc "$@" || status=$?
.venv/bin/rollerdyn plot results/b1.nc -o results/plots
exit "$status"
