// SPDX-License-Identifier: MIT
// The CLI's shared pieces: option parsing into a config, exit codes, messages.
#ifndef GF_APP_CLI_H
#define GF_APP_CLI_H

#include <signal.h>
#include <stdbool.h>

#include "granflow/granflow.h"
#include "granflow/dem.h"

/// Exit codes of every subcommand (listed in `granflow help` and the README).
enum {
    GF_EXIT_OK = 0,          ///< success
    GF_EXIT_FAIL = 1,        ///< the run failed (I/O error, out of memory, ...)
    GF_EXIT_USAGE = 2,       ///< bad command line or configuration
    GF_EXIT_DATA = 3,        ///< a data file (packing, checkpoint) is malformed
    GF_EXIT_INTERRUPTED = 130, ///< stopped by SIGINT/SIGTERM/SIGHUP; a checkpoint was written (run)
};

/// Options common to the subcommands.
typedef struct gf_cli {
    const char *config_path; ///< positional CONFIG (report: DIR), or NULL
    const char *out;         ///< -o
    const char *resume;      ///< --resume DIR
    bool json, force, quiet;
    const char *sets[256];   ///< --set assignments, applied after the file
    int nsets;
    double bench_particles, bench_warmup, bench_window; ///< bench options (0 = default)
    bool event, spatial, sweep, no_large, lga_only; ///< bench --event, --spatial, --sweep, --no-large, --lga-only
    bool dem_run, drain_only, dem_continue; ///< dem --run, --drain-only, --continue
} gf_cli;

/// gf_cli_parse's "go on" (any other value is the exit code to return now).
enum { GF_CLI_GO = -1 };

/// Parses the options of `cmd` (run, pack, config, bench, lga, report, dem)
/// with getopt_long: argv[0] is the command's name; options and positionals
/// mix; `--` ends the options; -h/--help prints the command's usage. Returns
/// GF_CLI_GO, or the exit code after printing the usage or an error.
int gf_cli_parse(int argc, char **argv, const char *cmd, gf_cli *cli);

/// The usage text of `cmd` (`granflow CMD --help`; main.c's table), or NULL.
const char *gf_cli_usage(const char *cmd);
/// Prints the usage of `cmd` on stdout; returns GF_EXIT_OK.
int gf_cli_help(const char *cmd);
/// The message of a getopt_long error `c` ('?' unknown option, ':' missing
/// value) naming the option; returns GF_EXIT_USAGE. argv as given to getopt_long.
int gf_cli_getopt_error(const char *cmd, int c, char **argv);

/// Default config, then the CONFIG file, then the --set overrides, validated.
/// Prints the error and returns false on failure.
bool gf_cli_config(const gf_cli *cli, const char *base_path, gf_config *cfg);

/// Makes SIGINT, SIGTERM and SIGHUP set a flag instead of killing the process; the
/// returned flag is what a run polls to stop cleanly (writing a checkpoint).
volatile sig_atomic_t *gf_cli_catch_stop(void);
/// Seconds a caught signal leaves the process to stop cleanly before
/// SIGALRM ends it (0, the default: no limit). With several MPI ranks a rank
/// that died leaves the others blocked in a collective, and mpirun's SIGTERM
/// would only set the flag: the limit makes them exit within seconds.
void gf_cli_stop_grace(unsigned seconds);

/// After GF_ERR_INTERRUPTED (the flag of gf_cli_catch_stop): prints one line,
/// `granflow CMD: stopped by a signal (WHAT STOPPED); LEFT`, and returns
/// GF_EXIT_INTERRUPTED. `left` says what is (not) on disk; may be NULL.
int gf_cli_interrupted(const char *cmd, const char *left);

/// Maps a status to the exit code and prints `granflow CMD: error: ...`.
int gf_cli_fail(const char *cmd, gf_status st);
/// gf_cli_fail with `hint` (the flags that answer the situation; NULL: none)
/// after the library's message, which never names CLI flags.
int gf_cli_fail_hint(const char *cmd, gf_status st, const char *hint);

int gf_cmd_run(int argc, char **argv);
int gf_cmd_pack(int argc, char **argv);
int gf_cmd_config(int argc, char **argv);
int gf_cmd_bench(int argc, char **argv);
int gf_cmd_analyze(int argc, char **argv);
int gf_cmd_render(int argc, char **argv);
int gf_cmd_lga(int argc, char **argv);
int gf_cmd_report(int argc, char **argv);
/// Options shared by calibrate and compare: the DEM source and analysis options.
typedef struct gf_demargs {
    const char *pos[4];
    int npos;
    const char *out, *config;
    const char *sets[64];
    size_t nsets;
    gf_analysis_opts opts;
    bool quiet, plots, refine; ///< -q; not compare --no-plots; not calibrate --no-refine
    int runs;                  ///< calibrate --runs N: the refinement's spot runs at most (0: its default, 6)
} gf_demargs;

/// Parses the options of calibrate and compare with getopt_long (argv[0] the
/// command's name; positionals, -o, --timestep, --config, --set: config keys
/// go to `sets`, the others to `opts`). Returns GF_CLI_GO or the exit code.
int gf_demargs_parse(const char *cmd, int argc, char **argv, gf_demargs *a);
/// Loads a run with gf_dem_series_load (`dem`: with --config/--set) and reports it.
gf_status gf_demargs_load(const char *cmd, const gf_demargs *a, const char *path, bool dem, gf_series *s);

int gf_cmd_dem(int argc, char **argv);
int gf_cmd_calibrate(int argc, char **argv);
int gf_cmd_compare(int argc, char **argv);

#endif
