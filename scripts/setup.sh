#!/usr/bin/env bash
# Creates .venv and installs rollerdyn (Rust core built by maturin, release mode) with its
# pinned Python dependencies. Idempotent; needs python3 (3.11+), cargo and the package
# registries (PyPI, crates.io). Says what it does: a fresh setup compiles the Rust core
# and takes several minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { echo "setup: $*"; }
if [ ! -x .venv/bin/python ]; then
  say "creating the Python environment .venv"
  python3 -m venv .venv
fi
say "updating pip"
.venv/bin/python -m pip install --quiet --upgrade pip
if .venv/bin/python -c "import rollerdyn._core" 2>/dev/null; then
  say "installing rollerdyn into .venv (rebuilding the Rust core if it changed)"
else
  say "installing the pinned Python dependencies and compiling the Rust core (release);"
  say "on a fresh machine this takes several minutes and prints nothing until it is done"
fi
start=$SECONDS
.venv/bin/python -m pip install --quiet -e ".[dev]"
say "rollerdyn installed in .venv ($((SECONDS - start)) s)"
