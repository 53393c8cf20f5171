#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# granflow.1 from the CLI's own help (help2man, at build time: cmake target
# granflow_man): NAME and SYNOPSIS from `granflow --help`, then a COMMANDS
# section with every command's `granflow CMD --help`, EXIT STATUS, FILES and
# SEE ALSO. The page stays as true as the help texts.
# usage: scripts/manpage.sh GRANFLOW_BINARY OUTPUT.1
set -euo pipefail
gf=${1:?usage: scripts/manpage.sh GRANFLOW_BINARY OUTPUT.1}
out=${2:?OUTPUT.1}
inc=$(mktemp)
trap 'rm -f "$inc"' EXIT
roff() { sed -e 's/\\/\\e/g' -e 's/^\([.'"'"']\)/\\\&\1/'; }
{
    # help2man finds no synopsis in a lowercase "usage:"; the usage lines of `granflow --help`.
    echo "[SYNOPSIS]"
    echo ".B granflow"
    echo "\\fICOMMAND\\fR [\\fIARGUMENTS\\fR] [\\fIOPTIONS\\fR]"
    echo ".br"
    echo ".B granflow"
    echo "\\fICOMMAND\\fR \\fB\\-\\-help\\fR"
    echo ".br"
    echo ".B granflow help"
    echo "\\fR[\\fICOMMAND\\fR]" # (a line opening with [ would start a section)
    echo "[COMMANDS]"
    for c in $("$gf" help | sed -n '/^commands:/,/^$/s/^  \([a-z]\+\) .*/\1/p'); do
        echo ".SS $c"
        echo ".nf"
        "$gf" "$c" --help | roff
        echo ".fi"
    done
    echo "[EXIT STATUS]"
    echo "0 ok; 1 failure (I/O, memory); 2 bad command line or configuration;"
    echo "3 malformed data file (packing, checkpoint, summary.json); 130 interrupted"
    echo "(SIGINT, SIGTERM or SIGHUP: a run writes its checkpoint; resume with"
    echo ".B granflow run --resume DIR\\fR)."
    echo "[FILES]"
    echo "A run directory holds config.ini, the initial packing, snapshots/, exits.csv,"
    echo "summary.json, checkpoint.bin, and after"
    echo ".B analyze\\fR, \\fBrender\\fR and \\fBreport\\fR: analysis/, render/ and report.html."
    echo "[SEE ALSO]"
    echo "The README and docs/ of the granflow sources (docs/config.md: every"
    echo "configuration key). The models: C. H. Rycroft, Y. L. Wong, M. Z. Bazant,"
    echo "Powder Technology 200 (2010) 1\\(en11; C. H. Rycroft, PhD thesis, MIT (2007), ch. 3;"
    echo "J. Kozicki, J. Tejchman (2005), lattice-gas automaton. Citing: CITATION.cff."
} > "$inc"
help2man --no-info --no-discard-stderr --section=1 --name="spot-model and lattice-gas simulations of dense granular drainage" \
    --include="$inc" --output="$out" "$gf"
