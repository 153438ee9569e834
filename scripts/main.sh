#!/usr/bin/env bash
# The main job: set up, check every model against published values, run the paper's whole
# study of bearing B1 (sect. 5, figs. 8-14: axial loads 0, 500, 1000, 2000 N with the point
# and the distributed end-flange law, the inner ring locked and free to tilt, both contact
# detectors, the runtime over dt_max) on all cores,
# check the paper's findings, and draw B1's own figures and report.
#   results/study/report.html     the study: every figure, the findings table, each run
#   results/study/runs/*.nc       one netCDF result per run (xarray; SI units in attributes)
#   results/study/figures/        figs. 8-14 (PNG and SVG); findings.csv, runs.csv
#   results/plots/, results/report.html   figs. 8-13 and the report of the B1 run itself
# Extra arguments go to `rollerdyn study paper` (e.g. `--t-end 0.55` for a short study,
# `--max-wall 300` for a tighter cap per run). A second invocation reuses finished runs and
# continues unfinished ones from their checkpoints. Time: see README.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/rollerdyn validate
status=0
.venv/bin/rollerdyn study paper examples/b1.toml -o results/study "$@" || status=$?
b1=results/study/runs/axial-1000N.nc
if [ -f "$b1" ]; then
  .venv/bin/rollerdyn plot "$b1" -o results/plots
  .venv/bin/rollerdyn report "$b1" -o results/report.html
fi
exit "$status"
