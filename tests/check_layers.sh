#!/usr/bin/env bash
# The layering of the library (STYLE: one way down). Every folder of src/ (and
# app/) has a layer; every public header include/granflow/X.h belongs to the
# folder that implements it. A file may include
#   - headers of its own folder,
#   - headers (private "X/y.h" or public "granflow/x.h") of a folder on a LOWER layer,
#   - PUBLIC headers of a sibling on the same layer, as long as two siblings
#     do not use each other (no cycles).
# A private header of a sibling, or any header of a higher layer, fails the
# check unless listed in ALLOWED below with the issue that removes it. A
# file outside src/geom/ and src/config/ that names a shape constant
# (GF_SHAPE_*) fails it too, and so does a file of src/ or app/ outside
# src/config/ that reads or writes a field of gf_config (modules read their
# defs, granflow/defs.h, built by config/; issue 24).
# Usage: check_layers.sh SOURCE_DIR
set -euo pipefail
root=${1:-.}
cd "$root"

# Layers, bottom up (issue 17). `io` holds the file formats and the particle
# data type (granflow/particles.h); `run` is the run-directory driver
# (src/run/, granflow/run.h); `draw` is the cairo canvas (no model
# knowledge) that render and lga both draw on.
declare -A layer=(
  [core]=0
  [geom]=1 [config]=1 [draw]=1
  [io]=2 [stress]=2
  [packing]=3
  [spot]=4
  [run]=5
  [analysis]=6 [render]=6 [dem]=6 [lga]=6 [report]=6 [bench]=6
  [app]=7
)
# Owner folder of each public header.
declare -A owner=(
  [core.h]=core [version.h]=core [exit.h]=core
  [config.h]=config [defs.h]=config [draw.h]=draw
  [particles.h]=io
  [packing.h]=packing
  [sim.h]=spot
  [run.h]=run
  [analysis.h]=analysis [render.h]=render [dem.h]=dem [lga.h]=lga [report.h]=report [bench.h]=bench
  [granflow.h]=app
)

# Known violations, "file -> header", each with the issue that removes it.
# Empty since issue 17 moved the rooms; never add one without an issue.
ALLOWED=()

declare -A allowed=()
for a in "${ALLOWED[@]}"; do allowed[$a]=1; done
declare -A used=() edges=()
bad=0 checked=0

folder_of() { # path -> folder owning it, in $folder (no subshell: this runs per file)
  case $1 in
    src/*) folder=${1#src/}; folder=${folder%%/*} ;;
    app/*) folder=app ;;
    include/granflow/*) folder=${owner[${1##*/}]:-?} ;;
    *) folder= ;;
  esac
}

mapfile -t files < <(find src app include/granflow -name '*.[ch]' -o -name '*.cc' | sort)
for file in "${files[@]}"; do
  folder_of "$file"
  [ -n "${layer[$folder]+x}" ] || { echo "$file: folder '$folder' has no layer in $0"; bad=1; }
done
# Every file's quoted includes as "file<TAB>header", read by one awk (a sed
# per file cost ~250 processes a run).
while IFS=$'\t' read -r file inc; do
  folder_of "$file"
  from=$folder
  [ -n "${layer[$from]+x}" ] || continue
  case $inc in
    granflow/*) to=${owner[${inc#granflow/}]:-}; public=1 ;;
    */*) to=${inc%%/*}; public=0 ;;
    *) continue ;; # same-folder include ("cli.h", "step.h")
  esac
  if [ -z "$to" ] || [ -z "${layer[$to]+x}" ]; then
    echo "$file: includes \"$inc\", which belongs to no known folder"; bad=1; continue
  fi
  checked=$((checked + 1))
  [ "$to" = "$from" ] && continue
  why=""
  if [ "${layer[$to]}" -gt "${layer[$from]}" ]; then
    why="$to (layer ${layer[$to]}) is above $from (layer ${layer[$from]})"
  elif [ "${layer[$to]}" -eq "${layer[$from]}" ] && [ $public -eq 0 ]; then
    why="private header of the sibling folder $to"
  fi
  if [ -z "$why" ]; then edges[$from:$to]=1; continue; fi
  key="$file -> $inc"
  if [ -n "${allowed[$key]:-}" ]; then used[$key]=1; continue; fi
  echo "layering: $key: $why"; bad=1
done < <(awk '/^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]*"/ {
                sub(/^[^"]*"/, ""); sub(/".*/, ""); printf "%s\t%s\n", FILENAME, $0 }' "${files[@]}")

# Siblings may use each other's public headers, but not both ways (edges of
# the allowed violations are left out: they are already known to point up).
for e in "${!edges[@]}"; do
  a=${e%%:*} b=${e##*:}
  if [ -n "${edges[$b:$a]:-}" ] && [[ $a < $b ]]; then echo "layering: cycle between $a and $b"; bad=1; fi
done
# Shapes own their geometry (issue 24, docs/geometry.md "Adding a shape"):
# only geom/ (the shape table) and config/ (which parses container.shape)
# name a shape; everything else asks the container (src/geom/container.h).
while IFS= read -r hit; do
  echo "shapes: $hit: names a shape outside src/geom/ and src/config/; ask the container instead"; bad=1
done < <(grep -rn --include='*.c' --include='*.h' --include='*.cc' 'GF_SHAPE_[A-Z]' src app | grep -v '^src/geom/\|^src/config/' || true)
# Modules read their own small defs (granflow/defs.h, issue 24): only
# config/ reads or writes gf_config's fields; everything else calls config/
# (a defs builder, gf_config_set_key, a typed setter). Every member name of
# struct gf_config is looked for after `.` or `->` in code, string literals
# and comments blanked first (line numbers kept); no other struct of src/
# or app/ may reuse such a name (the check could not tell them apart).
cfg_fields=$(awk '/^typedef struct gf_config \{/{f=1;next} /^\} gf_config;/{f=0} f' include/granflow/config.h |
  sed 's|//.*||' | grep -oE '[A-Za-z_][A-Za-z0-9_]*(\[[^]]*\])*;' | sed 's/\[.*//; s/;//' | sort -u | paste -sd'|')
[ -n "$cfg_fields" ] || { echo "config fields: found no member of struct gf_config in include/granflow/config.h"; bad=1; }
command -v perl > /dev/null || { echo "config fields: the check needs perl"; bad=1; }
while IFS= read -r hit; do
  echo "config fields: $hit outside src/config/: read the module's defs (granflow/defs.h); edit a config through config/ (gf_config_set_key, a setter)"
  bad=1
done < <(find src app \( -name '*.[ch]' -o -name '*.cc' \) ! -path 'src/config/*' | sort |
  GF_FIELDS=$cfg_fields perl -ne '
    BEGIN { $/ = undef; $re = qr/(?:->|\.)\s*($ENV{GF_FIELDS})\b/ }
    chomp(my $file = $_);
    for my $f (split /\n/, $file) {
      open(my $h, "<", $f) or die "$f: $!"; my $t = <$h>; close $h;
      # string and character literals and comments blanked, their line breaks kept
      $t =~ s{("(?:[^"\\\n]|\\.)*")|(\x27(?:[^\x27\\\n]|\\.)*\x27)|(//[^\n]*)|(/\*.*?\*/)}{defined $1 ? q("") : defined $2 ? q(\x27\x27) : defined $3 ? "" : "\n" x ($4 =~ tr/\n//)}gse;
      my $n = 0;
      for my $line (split /\n/, $t, -1) { $n++; print "$f:$n: uses gf_config field $1\n" while $line =~ /$re/g }
    }')
# An allow-list entry that no longer matches is stale: the fix landed, drop it.
for a in "${ALLOWED[@]}"; do
  [ -n "${used[$a]:-}" ] || { echo "layering: allowed violation no longer present, remove it from $0: $a"; bad=1; }
done
[ $bad -eq 0 ] || exit 1
echo "layering holds: $checked includes checked, ${#ALLOWED[@]} known violations allowed"
