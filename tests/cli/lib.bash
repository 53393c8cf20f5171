# Shared plumbing of the CLI tests (sourced, not a test itself: CTest runs *.sh).
# The caller sets NAME and calls: source lib.bash "$@". Gives $GF (the binary),
# $DATA (tests/data), $T (a temporary directory, the working directory, removed
# at exit by `cleanup`, which a script may redefine), and the helpers below.
set -u
GF=${1:?usage: $0 GRANFLOW_BINARY TESTS_DATA_DIR}
DATA=${2:?usage: $0 GRANFLOW_BINARY TESTS_DATA_DIR}
case $GF in /*) ;; *) GF=$PWD/$GF ;; esac
case $DATA in /*) ;; *) DATA=$PWD/$DATA ;; esac
[ -x "$GF" ] || { echo "cli $NAME: $GF is not an executable"; exit 1; }

T=$(mktemp -d "${TMPDIR:-/tmp}/gf-cli-$NAME.XXXXXX") || exit 1
BGPID=
cleanup() {
    if [ -n "$BGPID" ]; then kill -KILL "$BGPID" 2>/dev/null; wait "$BGPID" 2>/dev/null; fi
    rm -rf "$T"
}
trap cleanup EXIT
cd "$T" || exit 1

PASS=0
# fail MESSAGE: report the first failure (with the last command's output) and stop.
fail() {
    echo "FAIL: $*"
    if [ -n "${LAST:-}" ]; then
        echo "  command: $LAST"
        echo "  exit code: ${RC:-?}"
        echo "  --- stderr ---"
        sed 's/^/  | /' "$T/err" 2>/dev/null | head -n 20
    fi
    echo "cli $NAME: $PASS passed, 1 failed"
    exit 1
}
ok() {
    PASS=$((PASS + 1))
    echo "ok $PASS - $*"
}
# gf ARGS...: runs granflow, stdout -> $T/out, stderr -> $T/err, exit code -> RC.
gf() {
    LAST="granflow $*"
    "$GF" "$@" >"$T/out" 2>"$T/err"
    RC=$?
}
expect_rc() { [ "$RC" -eq "$1" ] || fail "$2: expected exit code $1, got $RC"; }
# expect_err TEXT WHAT: stderr must contain TEXT (fixed string).
expect_err() { grep -qF -- "$1" "$T/err" || fail "$2: stderr does not mention '$1'"; }
# start ARGS...: granflow in the background (stderr -> $T/bgerr), pid in BGPID.
start() { "$GF" "$@" >/dev/null 2>"$T/bgerr" & BGPID=$!; }
# finish SECONDS: waits at most SECONDS for the background run; its exit code in RC (999: still running, killed).
finish() {
    local i
    for ((i = 0; i < $1 * 10; i++)); do
        kill -0 "$BGPID" 2>/dev/null || break
        sleep 0.1
    done
    if kill -0 "$BGPID" 2>/dev/null; then
        kill -KILL "$BGPID"; wait "$BGPID" 2>/dev/null; RC=999
    else
        wait "$BGPID"; RC=$?
    fi
    BGPID=
    cp "$T/bgerr" "$T/err"
}
