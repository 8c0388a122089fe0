#!/usr/bin/env bash
# Set-up and the whole test suite: installs what is missing, builds, then runs the C++
# tests and the Python tests through ctest (which ends with its summary line).
set -euo pipefail
cd "$(dirname "$0")/.."
.ci/setup.sh
cd build
ctest --output-on-failure --timeout 1800 "$@"
