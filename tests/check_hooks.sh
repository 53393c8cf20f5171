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

# One perl for every file (a sed and three greps per file cost ~800
# processes a run): each line with its // comment and one-line /* */
# comments dropped (as sed 's://.*$::; s:/\*.*\*/::g' would), matched
# against each rule, in the order alloc, assert, print.
files=$(find src -name '*.[ch]' -o -name '*.cc' | sort | wc -l)
allowed_keys=$(printf '%s\n' "${!allowed[@]}")
out=$(find src -name '*.[ch]' -o -name '*.cc' | sort |
  GF_ALLOC=${rule[alloc]} GF_ASSERT=${rule[assert]} GF_PRINT=${rule[print]} GF_ALLOWED=$allowed_keys \
  GF_WHY_ALLOC=${why[alloc]} GF_WHY_ASSERT=${why[assert]} GF_WHY_PRINT=${why[print]} perl -e '
    my @rules = map { [$_, qr/$ENV{"GF_" . uc $_}/, $ENV{"GF_WHY_" . uc $_}] } qw(alloc assert print);
    my %allowed = map { $_ => 1 } split /\n/, $ENV{GF_ALLOWED};
    while (my $file = <STDIN>) {
      chomp $file;
      open(my $h, "<", $file) or die "$file: $!";
      my @lines = map { s{//.*$}{}; s{/\*.*\*/}{}g; $_ } map { chomp; $_ } <$h>;
      close $h;
      for my $r (@rules) {
        next if $allowed{"$r->[0]:$file"};
        for my $n (0 .. $#lines) {
          print "$r->[0]: $file:", $n + 1, ": $r->[2]: $lines[$n]\n" if $lines[$n] =~ $r->[1];
        }
      }
    }')
[ -z "$out" ] || { echo "$out"; exit 1; }
echo "hooks hold in $files files of src/: allocation, assertions, no printing (${#allowed[@]} allowed exceptions)"
