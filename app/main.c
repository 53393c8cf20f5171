// SPDX-License-Identifier: MIT
// granflow: the command line, a thin layer over libgranflow.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "mpi_app.h"

static const char gf_usage[] =
    "granflow %s: fast spot-model simulations of dense granular drainage\n"
    "\n"
    "usage: granflow COMMAND [CONFIG] [options]\n"
    "\n"
    "commands:\n"
    "  run [CONFIG] [-o DIR] [--set k=v]...  drain a silo into DIR (default runs/silo)\n"
    "  run --resume DIR [--set run.duration=T]  continue (or extend) a run from its checkpoint\n"
    "  pack [CONFIG] [--set k=v]... -o FILE  build the initial packing (.dump, .xyz or .csv)\n"
    "  config [CONFIG] [--set k=v]...        print the effective configuration as INI\n"
    "  bench [--json] [--particles N] [--warmup T] [--window T] [--event] [--no-large] [--lga-only]\n"
    "                                        time spot(), relax(), whole steps and LGA site updates\n"
    "  analyze [NAME] DIR [--set key=value]... [--timestep DT] [--config INI] [-o OUTDIR] [--no-plots] [--list]\n"
    "                                        the papers' statistics of a run: CSV, plots, summary.json\n"
    "  render DIR [--colour layer|phi|phi-raw] [--sheet] [--times T1,T2|--all] [--format png|svg|pdf]\n"
    "       [--scale PX] [-o OUTDIR]          pictures of a run's central slice (cairo)\n"
    "  dem [CONFIG] [--set k=v]... -o DIR [--run] [--drain-only]\n"
    "                                        LAMMPS inputs for a DEM run of the same silo (and run them)\n"
    "  calibrate DEM_DIR [--timestep DT] [--config INI] [--set k=v]... [--no-refine] -o PARAMS.ini\n"
    "                                        fit the five spot parameters to a DEM run (thesis Sec. 3.3),\n"
    "                                        then refine them with spot runs until flow and widths match\n"
    "  compare DEM_DIR SPOT_DIR [--timestep DT] [--config INI] [--set k=v]... [-o OUTDIR]\n"
    "                                        the two runs side by side: differences with uncertainties and\n"
    "                                        verdicts; CSV, plots, pictures, summary.md\n"
    "  lga [CONFIG] [--set lga.k=v]... [-o DIR] [--force]\n"
    "                                        the 2D lattice-gas automaton: pile, channel or silo (maps, CSV)\n"
    "  report DIR [-o FILE]                  one self-contained HTML page of a run (DIR/report.html)\n"
    "  help                                  this text\n"
    "\n"
    "options:\n"
    "  --set section.key=value   override one configuration key (repeatable)\n"
    "  -o PATH                   output directory (run) or file (pack)\n"
    "  --force                   let a fresh run overwrite a directory holding a run\n"
    "  -q, --quiet               no progress line\n"
    "  --config INI              (analyze, calibrate, compare) the container of the dumps, instead of DIR/config.ini\n"
    "  --timestep DT             (analyze, calibrate, compare) tau per LAMMPS step of dumps without ITEM: TIME\n"
    "\n"
    "exit codes: 0 ok, 1 failure (I/O, memory), 2 bad command line or configuration,\n"
    "            3 malformed data file, 130 interrupted (checkpoint written)\n"
    "SIGINT/SIGTERM/SIGHUP during a run write a checkpoint; resume with --resume DIR.\n"
    "A run holds a lock on DIR; --force first removes the old run's files from DIR.\n";

// The library never prints its warnings: the CLI does, naming the command.
static void gf_print_warning(void *ctx, const char *message)
{
    fprintf(stderr, "granflow %s: warning: %s\n", (const char *)ctx, message);
}

static int gf_main(int argc, char **argv)
{
    const char *cmd = argc > 1 ? argv[1] : "help";
    gf_set_warning_fn(gf_print_warning, (void *)cmd);
    if (!strcmp(cmd, "run")) return gf_cmd_run(argc - 2, argv + 2);
    if (!strcmp(cmd, "pack")) return gf_cmd_pack(argc - 2, argv + 2);
    if (!strcmp(cmd, "config")) return gf_cmd_config(argc - 2, argv + 2);
    if (!strcmp(cmd, "bench")) return gf_cmd_bench(argc - 2, argv + 2);
    if (!strcmp(cmd, "lga")) return gf_cmd_lga(argc - 2, argv + 2);
    if (!strcmp(cmd, "analyze") || !strcmp(cmd, "analyse")) return gf_cmd_analyze(argc - 2, argv + 2);
    if (!strcmp(cmd, "render")) return gf_cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "dem")) return gf_cmd_dem(argc - 2, argv + 2);
    if (!strcmp(cmd, "calibrate")) return gf_cmd_calibrate(argc - 2, argv + 2);
    if (!strcmp(cmd, "compare")) return gf_cmd_compare(argc - 2, argv + 2);
    if (!strcmp(cmd, "report")) return gf_cmd_report(argc - 2, argv + 2);
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        printf("granflow %s\n", gf_version());
        return GF_EXIT_OK;
    }
    if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
        printf(gf_usage, gf_version());
        return GF_EXIT_OK;
    }
    fprintf(stderr, "granflow: error: unknown command '%s'\n\n", cmd);
    fprintf(stderr, gf_usage, gf_version());
    return GF_EXIT_USAGE;
}

int main(int argc, char **argv)
{
#ifdef GF_MPI
    gf_mpi_app_init(&argc, &argv);
    // A rank that dies leaves the others blocked in a collective: mpirun's
    // SIGTERM then gives them this long to stop cleanly (a checkpoint is
    // written in well under it), and SIGALRM ends them after that.
    if (gf_mpi_app_ranks() > 1) gf_cli_stop_grace(GF_MPI_STOP_GRACE);
    return gf_mpi_app_end(gf_main(argc, argv));
#else
    return gf_main(argc, argv);
#endif
}
