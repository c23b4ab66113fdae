#!/usr/bin/env bash
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (clang), and run
# under them: any memory error, leak or undefined behaviour fails the test it happens in.
# Usage: bash scripts/sanitize.sh [ctest arguments, e.g. -R PipelineConfig]
# Builds in build-sanitize/ (shared with scripts/fuzz.sh); on 2 cores the build takes about an
# hour from nothing, and the suite runs two to three times slower than the Release build's.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/sanitize_build.sh
configure_sanitize_build
cmake --build "$sanitize_build"
ctest --test-dir "$sanitize_build" --output-on-failure "$@"
