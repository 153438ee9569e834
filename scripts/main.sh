#!/usr/bin/env bash
# The main job: set up, then run the model validation against published values.
# (Until the dynamic model exists, this is `rollerdyn validate`; see README.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/rollerdyn validate "$@"
