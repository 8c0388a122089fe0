#!/usr/bin/env bash
# Set-up and default demo: installs what is missing, builds, and runs the 2D vesicle
# relaxation (demos/vesicle-relaxation), then plots it.
set -euo pipefail
cd "$(dirname "$0")/.."
.ci/setup.sh
./build/cellphase run demos/vesicle-relaxation/scene.yaml
/usr/bin/python3 python/plot_run.py output/vesicle-relaxation
