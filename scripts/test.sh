#!/usr/bin/env bash
# Sets up and runs every test: formatting and lints, the Rust core's tests (unit and
# property tests), then the Python tests (which build and use the extension).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
cargo test --workspace --quiet
.venv/bin/ruff check python tests
.venv/bin/ruff format --check python tests
.venv/bin/python -m pytest -q
