#!/bin/sh
# Record the result of a quality gate (make fuzz, make sanitize, make valgrind) for the report:
#   gate-stamp.sh DIR GATE STATUS DETAIL
# writes DIR/GATE.json with the gate, "passed" or "FAILED" (STATUS is the gate's exit status), the
# date (UTC), the commit and whether the work tree had uncommitted changes, and DETAIL (one line).
set -eu
dir=$1 gate=$2 status=$3 detail=$4
mkdir -p "$dir"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
dirty=false
[ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ] && dirty=true
result=passed
[ "$status" -eq 0 ] || result=FAILED
detail=$(printf '%s' "$detail" | tr -d '\000-\037' | sed 's/\\/\\\\/g; s/"/\\"/g')
printf '{"gate": "%s", "result": "%s", "exit_status": %d, "date": "%s", "commit": "%s", "uncommitted_changes": %s, "detail": "%s"}\n' \
    "$gate" "$result" "$status" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$commit" "$dirty" "$detail" > "$dir/$gate.json.tmp"
mv "$dir/$gate.json.tmp" "$dir/$gate.json"
