#!/usr/bin/env bash
# Sets up .venv and runs the crashlite demo on the bundled example deck.
set -euo pipefail
cd "$(dirname "$0")"
bash scripts/setup.sh
exec .venv/bin/python -m crashlite.demo "$@"
