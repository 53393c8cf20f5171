#!/usr/bin/env bash
# CLI test: `make run` builds only the CLI (and the library it links), never
# a test executable (issue 25): its dry run (`make -n run`) builds through
# scripts/build.sh with the one target granflow_cli, and that target's
# dependency graph (cmake --graphviz) holds no test suite, fuzz replay or tool. The build shows progress, not make's directory chatter.
# usage: bash tests/cli/make_run.sh GRANFLOW_BINARY TESTS_DATA_DIR
# ctest: nosan (a check of the build rules: once, in the optimised pass)
NAME=make_run
source "$(dirname "$0")/lib.bash" "$@"
SRC=$(cd "$DATA/../.." && pwd)
[ -f "$SRC/Makefile" ] || fail "no Makefile in $SRC"

make -s -C "$SRC" -n run BUILD="$T/b" > run.n 2> run.err || fail "make -n run failed: $(head -3 run.err)"
builds=$(grep -c 'scripts/build\.sh' run.n)
[ "$builds" -eq 1 ] || fail "make -n run: $builds calls of scripts/build.sh, not one"
grep -q 'scripts/build\.sh '"$T"'/b [0-9]* "[^"]*" granflow_cli$' run.n ||
  fail "make -n run does not build the one target granflow_cli: $(grep build run.n)"
grep -E 'cmake +--build' run.n && fail "make -n run calls cmake --build directly (every target)"
grep -q 'granflow run ' run.n && grep -q 'granflow analyze ' run.n && grep -q 'granflow render ' run.n &&
  grep -q 'granflow report ' run.n || fail "make -n run no longer runs, analyses, draws and reports the silo"
grep -q 'scripts/deps\.sh' run.n || fail "make -n run no longer installs missing packages (scripts/deps.sh)"
ok "make -n run: deps, then scripts/build.sh of granflow_cli alone, then run, analyze, render, report"

# What granflow_cli needs: its dependency graph (cmake --graphviz) in a
# fresh build directory holds the library, never a test executable.
cmake -S "$SRC" -B "$T/b" -DCMAKE_BUILD_TYPE=Release --graphviz="$T/g/deps.dot" > configure.log 2>&1 ||
  fail "cmake configure failed: $(tail -3 configure.log)"
G=$T/g/deps.dot.granflow_cli
[ -s "$G" ] || fail "cmake --graphviz wrote no $G"
sed -n 's/.*label = "\([^"]*\)".*/\1/p' "$G" | sort -u > needs.txt
grep -qx granflow needs.txt || fail "granflow_cli does not depend on the library granflow: $(tr '\n' ' ' < needs.txt)"
# (the check can fail: the whole graph does hold the suites)
grep -q 'label = "test_json"' "$T/g/deps.dot" || fail "the full graph has no test_json"
tests=$(ls "$SRC"/tests/test_*.c "$SRC"/tests/tools/*.c | sed 's:.*/::; s:\.c$::' | tr '\n' '|')
hits=$(grep -Ex "(${tests}fuzz_replay_[a-z_]+|granflow_static)" needs.txt)
[ -z "$hits" ] || fail "building granflow_cli builds test executables: $hits"
ok "granflow_cli depends on the library only, no test executable ($(wc -l < needs.txt) nodes)"

# The quiet build: a failing configure shows cmake's message; the progress
# filter drops make's directory lines and keeps compiler diagnostics.
printf '[ 10%%] Building C object a.o\nmake[2]: Entering directory '"'"'/x'"'"'\nsrc/a.c:1:1: error: boom\n[ 20%%] Built target a\n' |
  awk -v tty=0 "$(sed -n "/^cmake --build/,/' >&2/p" "$SRC/scripts/build.sh" | sed -n "/awk -v tty=\$tty '/,\$p" |
                 sed "1s/.*awk -v tty=\$tty '//; \$s/' >&2\$//")" > filtered.txt
[ "$(cat filtered.txt)" = "src/a.c:1:1: error: boom" ] || fail "the progress filter keeps: $(cat filtered.txt)"
ok "scripts/build.sh shows compiler errors, not make's progress and directory lines"
echo "cli $NAME: $PASS passed"
