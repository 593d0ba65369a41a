#!/usr/bin/env bash
# Create .venv (once) and install crashlite into it with the given extras.
# Usage: source scripts/setup.sh [extras]   e.g. "test"
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
py="${PYTHON:-python3}"
if [ ! -x "$root/.venv/bin/python" ]; then
  "$py" -m venv "$root/.venv"
fi
extras="${1:-}"
spec="$root"
[ -n "$extras" ] && spec="$root[$extras]"
stamp="$root/.venv/.installed-${extras:-base}"
if [ ! -f "$stamp" ] || [ "$root/pyproject.toml" -nt "$stamp" ]; then
  echo "setting up $root/.venv (crashlite${extras:+ with $extras})..." >&2
  "$root/.venv/bin/python" -m pip install --quiet --upgrade pip >/dev/null 2>&1 || true
  log="$root/.venv/pip-install.log"
  if ! "$root/.venv/bin/python" -m pip install -e "$spec" >"$log" 2>&1; then
    cat "$log" >&2
    echo "pip install failed (log above)" >&2
    exit 1
  fi
  touch "$stamp"
fi
