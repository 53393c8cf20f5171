// SPDX-License-Identifier: MIT
// granflow: the command line, a thin layer over libgranflow.
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "mpi_app.h"

static const char gf_usage[] =
    "granflow %s: fast spot-model simulations of dense granular drainage\n"
    "\n"
    "usage: granflow COMMAND [ARGUMENTS] [OPTIONS]\n"
    "       granflow COMMAND --help    the command's synopsis and options\n"
    "       granflow help [COMMAND]\n"
    "\n"
    "commands:\n"
    "%s"
    "\n"
    "options:\n"
    "  -h, --help      this text\n"
    "      --version   granflow's version\n"
    "Options and arguments mix in any order; -- ends the options (a file named -x: -- -x).\n"
    "Units: lengths in particle diameters d, times in tau = sqrt(d/g).\n"
    "\n"
    "exit codes: 0 ok, 1 failure (I/O, memory), 2 bad command line or configuration,\n"
    "            3 malformed data file, 130 interrupted (checkpoint written)\n"
    "SIGINT/SIGTERM/SIGHUP during a run write a checkpoint; resume with run --resume DIR.\n"
    "A run holds a lock on DIR; --force first removes the old run's files from DIR.\n";

/// The commands, in the order `granflow help` lists them.
static const struct gf_command {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *what;
} gf_commands[] = {
    {"run", gf_cmd_run, "drain a silo into a run directory, or resume one from its checkpoint"},
    {"pack", gf_cmd_pack, "build (or convert) an initial packing: .dump, .xyz or .csv"},
    {"config", gf_cmd_config, "print the effective configuration as INI"},
    {"bench", gf_cmd_bench, "time spot(), relax(), whole steps and LGA site updates"},
    {"analyze", gf_cmd_analyze, "the papers' statistics of a run or of LAMMPS dumps: CSV, plots, summary.json"},
    {"render", gf_cmd_render, "pictures of a run's central slice (cairo)"},
    {"dem", gf_cmd_dem, "LAMMPS inputs for a DEM run of the same silo (and run them)"},
    {"calibrate", gf_cmd_calibrate, "fit the five spot parameters to a DEM run (thesis Sec. 3.3)"},
    {"compare", gf_cmd_compare, "a DEM run and a spot run side by side: differences and verdicts"},
    {"lga", gf_cmd_lga, "the 2D lattice-gas automaton: pile, channel or silo"},
    {"report", gf_cmd_report, "one self-contained HTML page of a run"},
    {"help", NULL, "this text, or a command's (help COMMAND)"},
};
enum { GF_NCOMMANDS = sizeof gf_commands / sizeof gf_commands[0] };

static void gf_print_usage(FILE *f)
{
    char list[2048] = "";
    size_t w = 0;
    for (size_t k = 0; k < GF_NCOMMANDS && w < sizeof list; k++)
        w += (size_t)snprintf(list + w, sizeof list - w, "  %-10s %s\n", gf_commands[k].name, gf_commands[k].what);
    fprintf(f, gf_usage, gf_version(), list);
}

static int gf_help(int argc, char **argv)
{
    if (argc < 2) {
        gf_print_usage(stdout);
        return GF_EXIT_OK;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) return gf_cli_help("help");
    const char *name = !strcmp(argv[1], "analyse") ? "analyze" : argv[1];
    if (argc > 2 || !gf_cli_usage(name)) {
        fprintf(stderr, "granflow help: error: %s '%s' (the commands: granflow help)\n",
                argc > 2 ? "one command at most, not" : "no such command", argv[argc > 2 ? 2 : 1]);
        return GF_EXIT_USAGE;
    }
    return gf_cli_help(name);
}

// The library never prints its warnings: the CLI does, naming the command.
static void gf_print_warning(void *ctx, const char *message)
{
    fprintf(stderr, "granflow %s: warning: %s\n", (const char *)ctx, message);
}

static int gf_main(int argc, char **argv)
{
    const char *cmd = argc > 1 ? argv[1] : "help";
    gf_set_warning_fn(gf_print_warning, (void *)cmd);
    if (!strcmp(cmd, "analyse")) cmd = "analyze";
    // Each command parses argv from its own name on (argv[0] for getopt_long).
    for (size_t k = 0; k < GF_NCOMMANDS; k++)
        if (gf_commands[k].fn && !strcmp(cmd, gf_commands[k].name)) return gf_commands[k].fn(argc - 1, argv + 1);
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        printf("granflow %s\n", gf_version());
        return GF_EXIT_OK;
    }
    if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h"))
        return gf_help(argc > 1 ? argc - 1 : 1, argc > 1 ? argv + 1 : argv);
    fprintf(stderr, "granflow: error: unknown command '%s'\n\n", cmd);
    gf_print_usage(stderr);
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
