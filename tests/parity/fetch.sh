#!/usr/bin/env bash
# Clone the public repositories of the parity decks (not redistributed with
# crashlite: see README.md beside this script) into tests/parity/data/.
# Needs network access to github.com; run once.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
data="${CRASHLITE_PARITY_DATA:-$here/data}"
mkdir -p "$data"
fetch() {  # owner/name commit
  local dir="$data/${1/\//+}"
  if [ ! -d "$dir/.git" ]; then
    git clone --quiet "https://github.com/$1.git" "$dir"
  fi
  git -C "$dir" checkout --quiet "$2"
  echo "$1 @ $2 -> $dir"
}
fetch dbrizard/GSA-car-crash 477fb0578b764fb8dd630608b18d0b808b1fc12a
fetch scheckmate/test_fe_simulation c68038116845f02a3ba27f8d9bd378396140174d
fetch chiaraf10/uqpy_test 46f7206dd52c1d60e83e1abc8d81b9a2193bb3f4
fetch Renumics/mesh2vec 01f717ea5896da09dc6078d24e697e2836dfc315
