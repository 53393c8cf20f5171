#!/usr/bin/env bash
# The source checks can fail: check_layers.sh and check_hooks.sh pass on a
# copy of the tree, then each violation below is planted in a fresh copy and
# the check must exit non-zero naming the planted file.
# Usage: check_checks.sh SOURCE_DIR
set -euo pipefail
src=$(cd "${1:-.}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

fresh() { # a clean copy of the folders the checks read, in $tmp/tree
  rm -rf "$tmp/tree"
  mkdir -p "$tmp/tree/include"
  cp -r "$src/src" "$src/app" "$tmp/tree/"
  cp -r "$src/include/granflow" "$tmp/tree/include/"
}

# expect_fail CHECK FILE WHAT: CHECK on the planted tree exits non-zero and
# its output names FILE (and WHAT, when given).
expect_fail() {
  local check=$1 file=$2 what=${3:-} out rc=0
  out=$(bash "$here/$check" "$tmp/tree" 2>&1) || rc=$?
  [ $rc -ne 0 ] || fail "$check passed with a planted violation in $file: $out"
  grep -qF "$file" <<< "$out" || fail "$check failed but did not name $file: $out"
  [ -z "$what" ] || grep -qF "$what" <<< "$out" || fail "$check did not say '$what': $out"
  echo "ok: $check fails on $file: $(head -n1 <<< "$out")"
}

# A clean tree passes both.
fresh
bash "$here/check_layers.sh" "$tmp/tree" || fail "check_layers.sh fails on a clean copy"
bash "$here/check_hooks.sh" "$tmp/tree" || fail "check_hooks.sh fails on a clean copy"

# Layering: a lower folder including a private header of a higher one.
fresh
sed -i '0,/^#include "core\/fs.h"/s//#include "core\/fs.h"\n#include "spot\/sim_internal.h"/' "$tmp/tree/src/core/fs.c"
grep -q 'spot/sim_internal.h' "$tmp/tree/src/core/fs.c" || fail "could not plant the include in core/fs.c"
expect_fail check_layers.sh src/core/fs.c "spot (layer 4) is above core (layer 0)"

# ... a public header of a higher folder (granflow/run.h belongs to run/).
fresh
printf '#include "granflow/run.h"\n' >> "$tmp/tree/src/geom/box.c"
expect_fail check_layers.sh src/geom/box.c "run (layer 5) is above geom (layer 1)"

# ... a private header of a sibling on the same layer.
fresh
printf '#include "analysis/motion.h"\n' >> "$tmp/tree/src/render/slice.c"
expect_fail check_layers.sh src/render/slice.c "private header of the sibling folder analysis"

# ... a public header including a higher one.
fresh
printf '#include "granflow/analysis.h"\n' >> "$tmp/tree/include/granflow/config.h"
expect_fail check_layers.sh include/granflow/config.h "analysis (layer 6) is above config (layer 1)"

# ... two siblings using each other's public headers (a cycle).
fresh
printf '#include "granflow/dem.h"\n' >> "$tmp/tree/src/render/slice.c"
printf '#include "granflow/render.h"\n' >> "$tmp/tree/src/dem/series.c"
out=$(bash "$here/check_layers.sh" "$tmp/tree" 2>&1) && fail "check_layers.sh passed with a dem <-> render cycle: $out"
grep -qF "cycle between dem and render" <<< "$out" || fail "check_layers.sh did not name the dem <-> render cycle: $out"
echo "ok: check_layers.sh fails on a cycle: $(grep cycle <<< "$out")"

# Shapes (issue 24): a module outside geom/ and config/ asking "cylinder, else box".
fresh
printf 'static int gf_planted(const gf_config *c) { return c->container_shape == GF_SHAPE_CYLINDER; }\n' >> "$tmp/tree/src/render/panel.c"
expect_fail check_layers.sh src/render/panel.c "names a shape outside src/geom/ and src/config/"
# ... but geom/ (the shape table) and config/ (which parses container.shape) may.
fresh
printf 'static int gf_planted(int s) { return s == GF_SHAPE_WEDGE; }\n' >> "$tmp/tree/src/geom/shapes.c"
printf 'static int gf_planted(int s) { return s == GF_SHAPE_WEDGE; }\n' >> "$tmp/tree/src/config/keys.c"
bash "$here/check_layers.sh" "$tmp/tree" > /dev/null || fail "check_layers.sh fails on a shape named in geom/ or config/"

# Config fields (issue 24): a module reading gf_config's fields instead of its defs ...
fresh
printf 'static double gf_planted(const gf_config *c) { return c->spot_radius; }\n' >> "$tmp/tree/src/spot/walk.c"
expect_fail check_layers.sh src/spot/walk.c:"$(wc -l < "$tmp/tree/src/spot/walk.c")" "uses gf_config field spot_radius outside src/config/"
# ... or the CLI writing one (a config is edited through config/).
fresh
printf 'static void gf_planted(gf_config *c) { c -> run_threads = 2; }\n' >> "$tmp/tree/app/cmd_run.c"
expect_fail check_layers.sh app/cmd_run.c "uses gf_config field run_threads"
# ... but config/ may, and a key's name in a string or a comment is no read.
fresh
printf 'static double gf_planted(const gf_config *c) { return c->spot_radius; }\n' >> "$tmp/tree/src/config/keys.c"
printf 'static const char *gf_planted = "spot.radius, c->spot_radius"; // c->run_seed\n/* s.exit_z\n */\n' >> "$tmp/tree/src/geom/box.c"
bash "$here/check_layers.sh" "$tmp/tree" > /dev/null || fail "check_layers.sh fails on a field read in config/ or a key named in a string or comment"

# Allocation: the C library's allocator outside core/alloc.c.
fresh
printf 'static void *gf_planted(void) { return malloc(8); }\n' >> "$tmp/tree/src/geom/box.c"
expect_fail check_hooks.sh src/geom/box.c "calls the C library's allocator"
fresh
printf 'static void gf_planted(FILE *f) { char *l = NULL; size_t n = 0; getline(&l, &n, f); }\n' >> "$tmp/tree/src/io/snapshot.c"
expect_fail check_hooks.sh src/io/snapshot.c "getline"
# Assertions outside the hook, and printing.
fresh
printf '#include <assert.h>\nstatic void gf_planted(int x) { assert(x > 0); }\n' >> "$tmp/tree/src/packing/generate.c"
expect_fail check_hooks.sh src/packing/generate.c "checks without the assert hook"
fresh
printf 'static void gf_planted(int x) { fprintf(stderr, "x = %%d\\n", x); }\n' >> "$tmp/tree/src/analysis/fit.c"
expect_fail check_hooks.sh src/analysis/fit.c "prints"
# ... but not in a comment, nor as part of a longer name.
fresh
printf '// malloc(8), printf("x") in a comment\nstatic void gf_planted(void *p, FILE *f) { gf_free(p, 8); fprintf(f, "x"); }\n' >> "$tmp/tree/src/geom/box.c"
bash "$here/check_hooks.sh" "$tmp/tree" > /dev/null || fail "check_hooks.sh fails on a comment, gf_free or fprintf to a caller's FILE"
echo "both checks pass on a clean tree and fail on every planted violation"
