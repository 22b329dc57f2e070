#!/usr/bin/env bash
# Installs what is missing, builds sandtin, and starts it: the editor when a display is
# available, otherwise the default batch job.
set -euo pipefail
cd "$(dirname "$0")"

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"

echo "run.sh: running the default batch job (sandtin demo)"
exec build/editor/cli/sandtin demo "$@"
