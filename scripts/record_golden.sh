#!/usr/bin/env bash
# Re-records tests/golden/*.json from the current build (see CONTRIBUTING.md, "Golden outputs"):
# only for an intended change, listed in the commit message. Needs build/bin/inertest_tests.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
INERTEST_RECORD_GOLDEN=1 "$BUILD_DIR/bin/inertest_tests" --gtest_filter='GoldenOutputs.*'
git --no-pager diff --stat -- tests/golden
