# Issue 23 experiment helper, sourced: st LABEL CMD... runs CMD SEED for
# seeds 1-12 into LABEL.txt and prints the mean +- standard error of
# flow.c's out_per_tau and the mean relax_dz_per_move (docs/performance.md,
# "Exact moves, the relaxation at intervals"). Example, from the directory
# holding flow (scripts/exp23/run.sh builds it):
#   . scripts/exp23/st.sh; st event ./flow event; st ev_g1 env GLOBALK=1 ./flow event
st() {
    local l=$1
    shift
    for s in $(seq 1 12); do "$@" "$s"; done >"$l.txt" 2>&1
    awk -v l="$l" '{ for (i = 1; i <= NF; i++) { if ($i == "out_per_tau") v[NR] = $(i + 1); if ($i == "relax_dz_per_move") r += $(i + 1) } }
        END { for (i = 1; i <= NR; i++) m += v[i]; m /= NR; for (i = 1; i <= NR; i++) s += (v[i] - m)^2
              printf "%-28s n=%d out %.2f +- %.2f  relax_dz %.6f\n", l, NR, m, sqrt(s / (NR - 1) / NR), r / NR }' "$l.txt"
}
