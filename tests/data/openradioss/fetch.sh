#!/usr/bin/env bash
# Download two OpenRadioss time histories (T01) of its QA tests into this
# folder (not redistributed with crashlite: see README.md beside this script).
# Needs network access to github.com; run once. With OPENRADIOSS_GIT_DIR set
# to a clone of OpenRadioss/OpenRadioss, the files are taken from it instead.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
data="${CRASHLITE_OPENRADIOSS_DATA:-$here}"
commit=bd4557ba7503a277d3be5b50e1c64e8a12e0c53f
files=(
  qa-tests/miniqa/INTERF/INT_7/small_boule/reference/BOULE1V4T01
  qa-tests/miniqa/CRASH/crashsection/box1_42/reference/BOX1BLT01
)
mkdir -p "$data"
for f in "${files[@]}"; do
  out="$data/$(basename "$f")"
  if [ -n "${OPENRADIOSS_GIT_DIR:-}" ]; then
    git --git-dir="$OPENRADIOSS_GIT_DIR" show "$commit:$f" >"$out"
  else
    curl -fsSL "https://raw.githubusercontent.com/OpenRadioss/OpenRadioss/$commit/$f" -o "$out"
  fi
  echo "$f @ ${commit:0:9} -> $out"
done
