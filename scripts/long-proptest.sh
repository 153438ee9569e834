#!/usr/bin/env bash
# Long mode of the contact-detection property tests (docs/robustness.md).
#
#   bash scripts/long-proptest.sh                 # 10^6 cases per fast detection test
#   CASES=100000 REFERENCE_CASES=2000 bash scripts/long-proptest.sh
#   PROPTEST_RNG_SEED=7 bash scripts/long-proptest.sh   # reproducible cases
#
# Every proptest in rollerdyn-core honours PROPTEST_CASES: proptest 1.12 applies the
# environment to the configs the tests set explicitly (`contextualize_config`), so the
# CI counts are only defaults. The detection tests against the brute-force reference
# solver (~50 ms a case) get their own, smaller count REFERENCE_CASES. Without
# PROPTEST_RNG_SEED every run draws new cases; a failure is shrunk and saved under
# crates/rollerdyn-core/proptest-regressions/ (replayed first by every later run).
# Runs niced, one test at a time; prints each test's cases and wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
CASES="${CASES:-1000000}"
REFERENCE_CASES="${REFERENCE_CASES:-20000}"
FAST_TESTS=(
  contact::tests::composite_equals_the_deepest_of_all_pairings
  contact::tests::pruned_composite_equals_the_deepest_overlap
  contact::tests::pruning_misses_no_contact
  contact::tests::degenerate_poses_give_defined_answers
  contact::tests::gradient_matches_semi_analytical_where_it_converges
)
REFERENCE_TESTS=(contact::tests::semi_analytical_matches_reference)

# The test profile is optimised (Cargo.toml), so no --release (which would relink with LTO).
nice -n 19 cargo test -p rollerdyn-core --lib --no-run --quiet
run() {
  local cases="$1" test="$2" start end
  start=$(date +%s)
  # The pruning test discards poses deeper than its bound: allow rejects in proportion.
  PROPTEST_CASES="$cases" PROPTEST_MAX_GLOBAL_REJECTS="$cases" \
    nice -n 19 cargo test -p rollerdyn-core --lib --quiet -- --exact "$test" --test-threads=1
  end=$(date +%s)
  echo "long-proptest: $test: $cases cases passed in $((end - start)) s"
}
total=0
for t in "${FAST_TESTS[@]}"; do
  run "$CASES" "$t"
  total=$((total + CASES))
done
for t in "${REFERENCE_TESTS[@]}"; do
  run "$REFERENCE_CASES" "$t"
  total=$((total + REFERENCE_CASES))
done
echo "long-proptest: $total cases in total, all passed"
