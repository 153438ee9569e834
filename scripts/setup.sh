#!/usr/bin/env bash
# Creates .venv and installs rollerdyn (Rust core built by maturin, release mode) with its
# pinned Python dependencies. Idempotent; needs python3 (3.11+), cargo and the package
# registries (PyPI, crates.io).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[dev]"
