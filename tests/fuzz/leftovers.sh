#!/usr/bin/env bash
# The fuzz replays leave no scratch file behind (issue 26: every replay left
# gf-fuzz-PID.* files and a gf-fuzz-PID.d directory in /dev/shm): each replay
# binary given is run over its inputs with TMPDIR set to an empty directory,
# which must be empty again when it ends.
# usage: bash tests/fuzz/leftovers.sh REPLAY_BINARY INPUT_DIR [REPLAY_BINARY INPUT_DIR...]
set -u
tmp=$(mktemp -d "${TMPDIR:-/tmp}/gf-fuzz-leftovers.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
while [ $# -ge 2 ]; do
    bin=$1 inputs=$2
    shift 2
    TMPDIR=$tmp "$bin" "$inputs" >/dev/null || { echo "FAIL: $bin $inputs: exit code $?"; exit 1; }
    left=$(ls -A "$tmp")
    [ -z "$left" ] || { echo "FAIL: ${bin##*/} left in TMPDIR: $left"; exit 1; }
    echo "ok - ${bin##*/} over $inputs: nothing left in TMPDIR"
done
