#!/usr/bin/env bash
# Regenerates the editor screenshots in docs/ from the scripts in docs/scripts, under a virtual
# X server (so it works without a display), on the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
editor=build/editor/app/sandtin-editor
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
settings="$work/editor.json"  # defaults: the pictures do not depend on your own settings
# progress: an import held mid-way by the script (its "jobs" op), so the bar shows on any machine.
for name in sculpt wireframe slope help file-browser progress water-stream water-sediment water-rain; do
  xvfb-run -a -s '-screen 0 1280x720x24' "$editor" assets/scenes/default.sandtin \
    --settings "$settings" --script "docs/scripts/$name.json" --frames 3 \
    --screenshot "docs/editor-$name.png"
  echo "docs/editor-$name.png"
done
