#!/bin/sh
# Print the fingerprints (final state / switches) of every shipped scene, one line each, as `gomboc run`
# computes them: a refactor that moves code without changing physics leaves every line as it was.
#   scripts/fingerprints.sh [GOMBOC] [OUTDIR]      (defaults: build/gomboc, a new temporary directory)
set -eu
bin=${1:-build/gomboc}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
mkdir -p "$out/siconos" "$out/bodies"
for scene in cases/*.ini cases/siconos/*.ini cases/bodies/*.ini; do
    name=$(basename "$scene" .ini)
    # cases/siconos/table1-gomboc-I.ini shares its name with cases/table1-gomboc-I.ini: its own directory
    dir=$out; case "$scene" in cases/siconos/*) dir=$out/siconos; name=siconos/$name ;;
                               cases/bodies/*) dir=$out/bodies; name=bodies/$name ;; esac
    if "$bin" run "$scene" --out "$dir" --json > "$out/$name.json" 2> "$out/$name.log"; then
        /usr/bin/python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))["fingerprint"]
print(sys.argv[2], d["final_state"], d["switches"])' "$out/$name.json" "$name"
    else
        echo "$name failed: $(tail -n 1 "$out/$name.log")"
    fi
done
