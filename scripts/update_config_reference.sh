#!/usr/bin/env bash
# Rewrites config/default.yaml and docs/parameters.md from the parameter schemas (the catkin build's
# config_reference program). A test fails while the committed files differ from what it prints.
set -euo pipefail
source "$(dirname "$0")/common.sh"
tool="$WS/devel/lib/stocs_ros/config_reference"
[ -x "$tool" ] || { echo "no $tool: build first (scripts/build.sh)" >&2; exit 2; }
"$tool" --yaml > "$REPO/config/default.yaml"
"$tool" --markdown > "$REPO/docs/parameters.md"
echo "update_config_reference: wrote config/default.yaml and docs/parameters.md"
