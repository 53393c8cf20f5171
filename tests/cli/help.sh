#!/usr/bin/env bash
# CLI test: every command answers --help (issue 25). The commands are listed
# from `granflow help` (a command missing from this test's list, or a listed
# one without --help, fails): `granflow CMD --help`, `-h` and `granflow help
# CMD` print the same synopsis and options on stdout and exit 0; every option
# a help text names is one its parser knows; an unknown option exits 2 naming
# it; `--` ends the options (getopt_long). The man page (help2man, in the
# build directory) has a section for every command, the bash completion
# offers the commands, each command's options, --set's configuration keys and
# analyze's measurements, and `cmake --install` installs both. The README's
# command list names every command.
# ctest: nosan (help texts, man page, completion, install: nothing for the
# sanitizers to see that the other CLI tests' option parsing does not show them;
# ~300 granflow processes at ~0.15 s each under ASan)
# usage: bash tests/cli/help.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=help
source "$(dirname "$0")/lib.bash" "$@"
SRC=$(cd "$DATA/../.." && pwd)
BUILD=$(dirname "$GF")

gf help
expect_rc 0 "granflow help"
cmds=$(sed -n '/^commands:/,/^$/s/^  \([a-z]\+\) .*/\1/p' "$T/out")
known="run pack config bench analyze render dem calibrate compare lga report help"
for c in $known; do
    grep -qx "$c" <<< "$cmds" || fail "granflow help does not list '$c'"
done
[ "$(wc -w <<< "$cmds")" -eq "$(wc -w <<< "$known")" ] ||
  fail "granflow help lists commands this test does not know: $(tr '\n' ' ' <<< "$cmds") (add them)"
gf --help
expect_rc 0 "granflow --help"
grep -q '^commands:' "$T/out" || fail "granflow --help lists no commands"
ok "granflow help lists the $(wc -w <<< "$cmds") commands"

for c in $cmds; do
    gf "$c" --help
    expect_rc 0 "granflow $c --help"
    cp "$T/out" "$T/help.$c"
    [ -s "$T/err" ] && fail "granflow $c --help wrote to stderr: $(head -2 "$T/err")"
    head -1 "$T/help.$c" | grep -q "^usage: granflow $c" || fail "granflow $c --help does not start with its synopsis"
    grep -q -- '-h, --help' "$T/help.$c" || fail "granflow $c --help does not list -h, --help"
    gf "$c" -h
    expect_rc 0 "granflow $c -h"
    cmp -s "$T/out" "$T/help.$c" || fail "granflow $c -h differs from --help"
    gf help "$c"
    expect_rc 0 "granflow help $c"
    cmp -s "$T/out" "$T/help.$c" || fail "granflow help $c differs from granflow $c --help"
done
ok "granflow CMD --help, -h and help CMD: the synopsis and options, exit 0, for every command"

# The synopsis and options lines of a help text (not its prose, which may say "-y").
optlines() { awk 'BEGIN { head = 1 } head && (NR == 1 || /^[ \t]/ || /^usage:/) { print; next } { head = 0 } /^options:/ { o = 1 } o' "$1"; }

# Every option of a help text is known to the command's parser ("OPT 1 --help":
# an option taking a value takes 1; none may be refused as unknown).
for c in $cmds; do
    [ "$c" = help ] && continue
    opts=$(optlines "$T/help.$c" | grep -oE -- '(^|[ ,[|(])--?[a-zA-Z][a-z-]*' | sed 's/^[ ,[|(]//' | sort -u)
    [ -n "$opts" ] || fail "granflow $c --help names no option"
    for o in $opts; do
        gf "$c" "$o" 1 --help
        grep -q "unknown option" "$T/err" && fail "granflow $c --help names $o, which its parser refuses"
    done
    gf "$c" --no-such-option
    expect_rc 2 "granflow $c --no-such-option"
    expect_err "unknown option '--no-such-option'"
    expect_err "granflow $c --help"
done
gf run -o
expect_rc 2 "run -o without a value"
expect_err "-o needs a value"
gf run --force=yes
expect_rc 2 "run --force=yes"
expect_err "--force takes no value"
ok "every option in a help text is known to its parser; unknown ones exit 2 naming them"

# `--` ends the options: a run directory and a config file named like options.
mkdir -- -dir
gf report -- -dir
expect_rc 2 "report -- -dir"
grep -q "unknown option" "$T/err" && fail "report -- -dir: -dir taken for an option"
expect_err "-dir: not a run directory"
gf config -- -x.ini
expect_rc 2 "config -- -x.ini"
expect_err "-x.ini"
grep -q "unknown option" "$T/err" && fail "config -- -x.ini: -x.ini taken for an option"
gf config --set spot.radius=2.5 -- --set
expect_rc 2 "config -- --set"
expect_err "--set"
ok "-- ends the options (report -- -dir, config -- -x.ini)"

# Options and arguments mix, values may start with '-'.
gf config --set container.orifice_diameter=6 --set=spot.radius=2.25
expect_rc 0 "config --set K=V --set=K=V"
grep -q '^radius = 2.25$' "$T/out" && grep -q '^orifice_diameter = 6$' "$T/out" || fail "config --set=K=V not applied"
ok "--set K=V and --set=K=V"

# The man page: every command has its section.
M=$BUILD/granflow.1
[ -s "$M" ] || fail "no man page $M (help2man: scripts/deps.sh installs it)"
for c in $cmds; do grep -q "^\.SS $c\$" "$M" || fail "the man page has no section for $c"; done
grep -q '^\.SH "EXIT STATUS"\|^\.SH EXIT STATUS' "$M" || fail "the man page has no EXIT STATUS"
if command -v groff > /dev/null; then
    groff -man -Tutf8 "$M" > man.txt 2> man.err || fail "groff cannot format $M"
    grep -q "granflow run \[CONFIG\]" man.txt || fail "the formatted man page lacks run's synopsis"
fi
ok "man page: a section per command and the exit status"

# The bash completion.
C=$SRC/scripts/granflow-completion.bash
complete_words() { # WORD... -> the completions of the last word, one per line
    bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _granflow; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$C" "$GF" "$@" 2> /dev/null
}
got=$(complete_words "")
for c in $cmds; do grep -qx "$c" <<< "$got" || fail "completion of 'granflow ' lacks $c"; done
for c in $cmds; do
    [ "$c" = help ] && continue
    got=$(complete_words "$c" --)
    for o in $(optlines "$T/help.$c" | grep -oE -- '(^|[ ,[|(])--[a-z][a-z-]*' | sed 's/^[ ,[|(]//' | sort -u); do
        grep -qx -- "$o" <<< "$got" || fail "completion of 'granflow $c --' lacks $o"
    done
done
complete_words run --set spot.rad | grep -qx 'spot.radius=' || fail "completion of --set spot.rad lacks spot.radius="
complete_words analyze velo | grep -qx velocity || fail "completion of 'analyze velo' lacks velocity"
complete_words render run --colour p | grep -qx phi-raw || fail "completion of --colour p lacks phi-raw"
ok "bash completion: commands, each command's options, --set keys, analyze's measurements"

# cmake --install puts both in place.
cmake --install "$BUILD" --prefix "$T/prefix" > install.log 2>&1 || fail "cmake --install failed: $(tail -3 install.log)"
[ -s "$T/prefix/share/man/man1/granflow.1" ] || fail "no share/man/man1/granflow.1 installed"
[ -s "$T/prefix/share/bash-completion/completions/granflow" ] || fail "no bash completion installed"
ok "cmake --install: share/man/man1/granflow.1, share/bash-completion/completions/granflow"

# The README's command list names every command.
for c in $cmds; do
    [ "$c" = help ] && continue
    sed -n '/^## Command line/,/^## /p' "$SRC/README.md" | grep -q "^granflow $c" ||
      fail "README.md's command line section does not list granflow $c"
done
ok "README.md lists every command"
echo "cli $NAME: $PASS passed"
