# The MPI tests' common part, sourced after ../cli/lib.bash with the MPIRUN
# argument: how mpirun is called (as root, oversubscribed, ranks yielding
# when idle), mpi NP ARGS... (granflow on NP ranks, its exit code in RC,
# output in $T/out and $T/err), and took (the words rank 0 took from the
# other ranks in the last run, from GF_MPI_STATS=1: > 0 when the others ran
# blocks and their changes were exchanged).
MPIRUN=${1:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
mpi() { # mpi NP ARGS...: granflow on NP ranks
    local np=$1
    shift
    LAST="mpirun -np $np granflow $*"
    "$MPIRUN" --oversubscribe -np "$np" "$GF" "$@" >"$T/out" 2>"$T/err"
    RC=$?
}
took() { sed -n 's/.*rank 0 took \([0-9]*\) words.*/\1/p' "$T/err"; }
