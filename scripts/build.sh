#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The quiet build of the Makefile: configures BUILD_DIR (cmake's own output
# kept in BUILD_DIR/configure.log) and builds the given targets (all when
# none), showing one progress line instead of make's ~500: on a terminal a
# line rewritten in place ("build: [ 87%] ..."), elsewhere nothing until the
# end. Compiler warnings and errors pass through whole; the full output is
# kept in BUILD_DIR/build.log. Fails with cmake's exit code.
# usage: scripts/build.sh BUILD_DIR JOBS "CMAKE_ARGS..." [TARGET...]
set -uo pipefail
dir=${1:?usage: scripts/build.sh BUILD_DIR JOBS "CMAKE_ARGS..." [TARGET...]}
jobs=${2:?JOBS}
read -r -a args <<< "${3:-}"
shift 3
what=${*:-everything}
mkdir -p "$dir"
if ! cmake -S . -B "$dir" "${args[@]}" > "$dir/configure.log" 2>&1; then
    cat "$dir/configure.log" >&2
    echo "build: cmake configure failed (log: $dir/configure.log)" >&2
    exit 1
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
tty=0
[ -t 2 ] && tty=1
start=$(date +%s)
# Make's chatter from a parent make (MAKEFLAGS carries -w into sub-makes).
export MAKEFLAGS="${MAKEFLAGS:-} --no-print-directory"
cmake --build "$dir" -j "$jobs" "${targets[@]}" 2>&1 | tee "$dir/build.log" | awk -v tty=$tty '
    /^\[ *[0-9]+%\]/ || /^Consolidate compiler generated dependencies/ || /^(g?make|ninja)(\[[0-9]+\])?: (Entering|Leaving) directory/ {
        if (tty) { printf "\r\033[Kbuild: %s", substr($0, 1, 100); fflush(); shown = 1 }
        next
    }
    { if (shown) { printf "\r\033[K"; shown = 0 } print; fflush() }
    END { if (shown) printf "\r\033[K" }' >&2
rc=${PIPESTATUS[0]}
if [ "$rc" -ne 0 ]; then
    echo "build: FAILED building $what in $dir (full log: $dir/build.log)" >&2
    exit "$rc"
fi
echo "build: $what in $dir: done ($(( $(date +%s) - start )) s; log: $dir/build.log)" >&2
