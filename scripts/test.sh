#!/usr/bin/env bash
# Sets up and runs every test: formatting and lints, the Rust core's tests (unit and
# property tests), then the Python tests (which build and use the extension).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Headless Chromium for the HTML report's browser test (Debian's package; needs root there).
if ! command -v chromium >/dev/null; then
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null) \
    || echo "could not install chromium: the report's browser test needs it" >&2
fi
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
# The fuzz targets (fuzz/, a workspace of its own that only cargo-fuzz builds and runs) must
# keep compiling against the core: linted here, not run (docs/robustness.md).
cargo clippy --manifest-path fuzz/Cargo.toml --locked --bins --target-dir target --quiet -- -D warnings
# Property tests draw their cases from a fixed seed here, so that CI is deterministic;
# run `cargo test` without PROPTEST_RNG_SEED to explore new random cases.
PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20261122}" cargo test --workspace --quiet
.venv/bin/ruff check python tests
.venv/bin/ruff format --check python tests
# The core's type stubs (python/rollerdyn/_core.pyi) against the built extension.
.venv/bin/python -m mypy.stubtest rollerdyn._core
.venv/bin/python -m pytest -q
