#!/usr/bin/env bash
# Installs what is missing, builds sandtin, and starts it: the editor when a display is
# available, otherwise the default batch job.
set -euo pipefail
cd "$(dirname "$0")"

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"

if [[ -n "${DISPLAY:-}" || -n "${WAYLAND_DISPLAY:-}" ]]; then
  echo "run.sh: opening the editor on assets/scenes/default.sandtin"
  exec build/editor/app/sandtin-editor assets/scenes/default.sandtin "$@"
fi
echo "run.sh: no display (DISPLAY is not set), so no editor window. To see the editor without"
echo "a screen, render a scripted screenshot under a virtual X server, for example:"
echo "  xvfb-run -a -s '-screen 0 1280x720x24' build/editor/app/sandtin-editor \\"
echo "    assets/scenes/default.sandtin --script docs/scripts/sculpt.json --frames 30 \\"
echo "    --screenshot editor.png"
echo "run.sh: running the default batch job (sandtin demo)"
# The demo's result goes into build/ (ignored by git) unless the arguments name another -o.
demo_output=(-o build/sandtin-demo.sandtin)
for arg in "$@"; do
  [[ "$arg" == "-o" ]] && demo_output=()
done
exec build/editor/cli/sandtin demo "${demo_output[@]}" "$@"
