#!/usr/bin/env bash
# The embedding hooks hold for all of src/ (issue 17; include/granflow/core.h):
#   alloc  - every allocation goes through the core allocator (core/alloc.h:
#            gf_alloc/gf_free/gf_realloc, behind gf_set_allocator):
#            no call of the C library's allocator, nor of a libc function that
#            returns memory from it (getline, scandir, open_memstream,
#            realpath(p, NULL), ...). The C++ Voro++ wrapper may use `new`
#            inside Voro++.
#   assert - internal checks go through GF_ASSERT (the gf_set_assert_fn hook):
#            no assert.h, assert(), abort().
#   print  - the library never prints: warnings go to gf_warn (kept, passed to
#            gf_set_warning_fn), errors to gf_last_error(). No write to
#            stdout/stderr (a FILE * the caller passes is fine).
# Each rule lists the files allowed to break it, with the reason. Comments
# are ignored. Fails naming file, line and rule.
# Usage: check_hooks.sh SOURCE_DIR
set -euo pipefail
root=${1:-.}
cd "$root"

id='(^|[^A-Za-z0-9_.>])' # not part of a longer name, nor a member (gf_free, s.free, p->free)
declare -A rule=(
  [alloc]="$id(malloc|calloc|realloc|reallocarray|free|strdup|strndup|aligned_alloc|posix_memalign|memalign|valloc|getline|getdelim|scandir|open_memstream|open_wmemstream|asprintf|vasprintf|tempnam|get_current_dir_name|canonicalize_file_name)[[:space:]]*\\(|${id}realpath[[:space:]]*\\([^,]*,[[:space:]]*NULL"
  [assert]="#[[:space:]]*include[[:space:]]*<assert\\.h>|$id(assert|abort)[[:space:]]*\\("
  [print]="${id}(stdout|stderr)$id|$id(printf|vprintf|puts|putchar|perror)[[:space:]]*\\("
)
declare -A why=(
  [alloc]="calls the C library's allocator (use core/alloc.h)"
  [assert]="checks without the assert hook (use GF_ASSERT)"
  [print]="prints (use gf_warn or gf_error_set)"
)
# "rule:file" -> reason.
declare -A allowed=(
  [alloc:src/core/alloc.c]="the default allocator behind gf_set_allocator (aligned_alloc/free)"
  [assert:src/core/hooks.c]="the assert hook itself: the default aborts"
  [print:src/core/hooks.c]="the default assert hook prints the failed check before it aborts"
)

bad=0 files=0
while IFS= read -r file; do
  files=$((files + 1))
  # Line comments and one-line block comments dropped.
  text=$(sed -e 's://.*$::' -e 's:/\*.*\*/::g' "$file")
  for r in alloc assert print; do
    [ -n "${allowed[$r:$file]:-}" ] && continue
    hits=$(grep -nE "${rule[$r]}" <<< "$text" || true)
    [ -n "$hits" ] || continue
    while IFS= read -r h; do
      echo "$r: $file:${h%%:*}: ${why[$r]}: ${h#*:}"
    done <<< "$hits"
    bad=1
  done
done < <(find src -name '*.[ch]' -o -name '*.cc' | sort)

[ $bad -eq 0 ] || exit 1
echo "hooks hold in $files files of src/: allocation, assertions, no printing (${#allowed[@]} allowed exceptions)"
