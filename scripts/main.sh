#!/usr/bin/env bash
# The main job: set up, check every model against published values, run the B1
# simulation (paper sect. 4) and draw its figures.
#   results/b1.nc      the run (netCDF, xarray; SI units in every variable's attributes)
#   results/plots/     figs. 8-13 of the paper and the roller loads (PNG and SVG)
#   results/report.html  one self-contained page: summary, interactive figures, animation
# Extra arguments go to `rollerdyn run` (e.g. `--t-end 0.55` for a short run). Without
# any, the whole job takes about 1.5 minutes on this 2-core machine (86 s measured; README).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/rollerdyn validate
mkdir -p results
status=0
.venv/bin/rollerdyn run examples/b1.toml -o results/b1.nc --overwrite "$@" || status=$?
.venv/bin/rollerdyn plot results/b1.nc -o results/plots
.venv/bin/rollerdyn report results/b1.nc -o results/report.html
exit "$status"
