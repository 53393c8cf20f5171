// SPDX-License-Identifier: MIT
// The help texts: `granflow help` and `granflow CMD --help` (also the man
// page, generated from them by help2man at build time, and the options the
// bash completion offers). Each lists exactly the options its parser takes.
#include <stdio.h>
#include <string.h>

#include "cli.h"

#define GF_HELP_LINE "  -h, --help             this text\n"
#define GF_SET_LINE                                                                                                    \
    "  -s, --set KEY=VALUE    override one configuration key (section.key, after CONFIG;\n"                              \
    "                         repeatable; every key: granflow config, docs/config.md)\n"

static const struct gf_usage {
    const char *cmd, *text;
} gf_usages[] = {
    {"run",
     "usage: granflow run [CONFIG] [-o DIR] [--set KEY=VALUE]... [--force] [-q]\n"
     "       granflow run --resume DIR [--set run.duration=T]... [-q]\n"
     "Drains a silo into the run directory DIR: the initial packing, snapshots,\n"
     "exits.csv, summary.json and a checkpoint. CONFIG is an INI file; without it\n"
     "and --set, the papers' silo. SIGINT, SIGTERM or SIGHUP writes a checkpoint and\n"
     "exits 130; --resume continues from it, byte for byte as if never stopped.\n"
     "\n"
     "options:\n"
     "  -o, --output DIR       the run directory (default runs/silo)\n" GF_SET_LINE
     "      --resume DIR       continue the run in DIR from its checkpoint, with its\n"
     "                         config.ini (--set run.duration=T extends a finished run)\n"
     "  -f, --force            let a fresh run replace a run in DIR (its files removed first)\n"
     "  -q, --quiet            no progress line\n" GF_HELP_LINE},
    {"pack",
     "usage: granflow pack [CONFIG] [--set KEY=VALUE]... -o FILE [-q]\n"
     "Builds the initial packing of the configuration (or imports packing.file and\n"
     "re-tags it) and writes it as FILE: LAMMPS dump (.dump), .xyz or .csv by its suffix.\n"
     "\n"
     "options:\n"
     "  -o, --output FILE      the packing file (required)\n" GF_SET_LINE
     "  -q, --quiet            no progress lines\n" GF_HELP_LINE},
    {"config",
     "usage: granflow config [CONFIG] [--set KEY=VALUE]...\n"
     "Prints the effective configuration (the defaults, then CONFIG, then the --set\n"
     "overrides, validated) as an INI file that granflow reads back.\n"
     "\n"
     "options:\n" GF_SET_LINE GF_HELP_LINE},
    {"bench",
     "usage: granflow bench [CONFIG] [--set KEY=VALUE]... [--json] [--particles N] [--warmup T]\n"
     "                      [--window T] [--event | --spatial | --sweep] [--no-large] [--lga-only]\n"
     "Times the spot engine (the domain engine unless --event, --spatial or --sweep) on the\n"
     "papers' silo in steady flow (spot(), relax(), whole steps on one thread and on\n"
     "all, memory per particle), the same silo ten times larger, and the lattice-gas\n"
     "automaton's site updates.\n"
     "\n"
     "options:\n" GF_SET_LINE
     "      --json             the figures as JSON on stdout\n"
     "      --particles N      particles in the silo (default: packing.particles)\n"
     "      --warmup T         tau of flow before the timed windows (default 40)\n"
     "      --window T         tau of each timed window (default 1)\n"
     "      --event            the event-driven engine (one thread), not the domain engine\n"
     "      --spatial          the spatial fixed step, not the domain engine\n"
     "      --sweep            the sweep engine (run.order = sweep), not the domain engine\n"
     "      --no-large         skip the silo ten times larger\n"
     "      --lga-only         time only the lattice-gas automaton\n" GF_HELP_LINE},
    {"analyze",
     "usage: granflow analyze [NAME] DIR [--set KEY=VALUE]... [--timestep DT] [--config INI]\n"
     "                        [-o OUTDIR] [--no-plots] [-q]\n"
     "       granflow analyze --list\n"
     "Measures a run the papers' way: flow rate, velocity profiles, diffusion,\n"
     "correlations, g(r), g3, packing fraction, residence times; one CSV file and one\n"
     "plot each, headline numbers in summary.json. DIR is a run directory, a\n"
     "directory of LAMMPS dumps or one dump. NAME: only that measurement (the others'\n"
     "numbers in summary.json are kept).\n"
     "\n"
     "options:\n"
     "  -s, --set KEY=VALUE    an analysis option (window.t0=24, velocity.heights=10,30;\n"
     "                         docs/analysis.md) or a configuration key of the run\n"
     "                         (container.width=50 for dumps without config.ini); repeatable\n"
     "      --timestep DT      tau per LAMMPS step, for dumps without ITEM: TIME\n"
     "      --config INI       the run's configuration (its container), not DIR/config.ini\n"
     "  -o, --output OUTDIR    where the results go (default DIR/analysis)\n"
     "      --no-plots         CSV files and summary.json only\n"
     "      --list             list the measurements (NAME) and exit\n"
     "  -q, --quiet            no progress lines\n" GF_HELP_LINE},
    {"render",
    "usage: granflow render DIR [--colour layer|phi|phi-raw] [--sheet] [--times T1,T2,...|--all]\n"
    "                       [--panels N] [--format png|svg|pdf] [--scale PX] [-o OUTDIR] [-q]\n"
    "Draws the central slice (y > 0, seen from -y) of a run's snapshots.\n"
    "By default: DIR/render/slice_NNNNNN.png for the first, middle and last snapshots\n"
    "coloured by initial layer, slice_NNNNNN_phi.png for the last one coloured by\n"
    "local packing fraction (averaged within 2.2 d), and sheet.png, a contact sheet\n"
    "of the run over time.\n"
    "NNNNNN is the snapshot's index in time order. DIR may also be a directory of\n"
    "LAMMPS dumps or one dump file (then the pictures go to render/ beside it).\n"
    "\n"
    "options:\n"
    "  --colour layer|phi|phi-raw  (or --color)\n"
    "                         colour by initial layer (default), by the local packing\n"
    "                         fraction averaged over the bulk particles within 2.2 d\n"
    "                         (phi: the 2009 paper's Fig. 4; files *_phi.*), or by each\n"
    "                         particle's volume over its Voronoi cell's volume\n"
    "                         (phi-raw: the paper's Fig. 6; files *_phi_raw.*)\n"
    "  --times T1,T2,...      the snapshots nearest these times (tau)\n"
    "  --all                  every snapshot\n"
    "  --sheet                the contact sheet (only it, unless --times or --all)\n"
    "  --panels N             snapshots on the contact sheet, evenly spaced (default 8)\n"
    "  --format png|svg|pdf   file format (default png)\n"
    "  --scale PX             pixels per particle diameter (default 10; the sheet uses half)\n"
    "  -o, --output OUTDIR    where the pictures go (default DIR/render)\n"
    "  -q, --quiet            do not list the files written\n"
    GF_HELP_LINE},
    {"dem",
     "usage: granflow dem [CONFIG] [--set KEY=VALUE]... -o DIR [--run | --drain-only] [--force] [-q]\n"
     "       granflow dem -o DIR --continue [--set run.duration=T] [--set dem.mpi_ranks=N] [--force] [-q]\n"
     "Writes the LAMMPS inputs of a DEM run of the same silo (DIR/in.fill: pour or\n"
     "settle the packing; DIR/in.drain: open the orifice), and with --run runs them\n"
     "(lmp; dem.mpi_ranks under mpirun) with a progress line. The drain writes a\n"
     "restart file every dem.restart_interval tau; --continue goes on from it after\n"
     "an interruption (snapshots after it are removed and written again).\n"
     "\n"
     "options:\n"
     "  -o, --output DIR       where the inputs and the run go (required)\n" GF_SET_LINE
     "      --run              run LAMMPS: fill, settle, then drain\n"
     "      --drain-only       run the drainage again from DIR/settled.restart\n"
     "      --continue         continue an interrupted drainage from the newer of\n"
     "                         DIR/drain.a.restart and drain.b.restart\n"
     "  -f, --force            replace a DEM run in DIR; --continue: even if the drain\n"
     "                         wrote files in the last 2 minutes (its LAMMPS gone)\n"
     "  -q, --quiet            no progress lines\n" GF_HELP_LINE},
    {"calibrate",
     "usage: granflow calibrate DEM_DIR -o PARAMS.ini [--timestep DT] [--config INI]\n"
     "                          [--set KEY=VALUE]... [--no-refine | --runs N] [-q]\n"
     "Fits the five spot parameters to a DEM run as the thesis does (Sec. 3.3), then\n"
     "refines them with spot runs from the DEM's first snapshot until the flow rate is\n"
     "within 5% and Var(z) within 10% at every height. Writes PARAMS.ini, a\n"
     "configuration granflow run takes, and its packing PARAMS.ini.packing.dump.\n"
     "\n"
     "options:\n"
     "  -o, --output FILE      the parameters file (required)\n"
     "  -s, --set KEY=VALUE    an analysis option or a configuration key of the DEM run\n"
     "                         (its container, packing.types); repeatable\n"
     "      --timestep DT      tau per LAMMPS step, for dumps without ITEM: TIME\n"
     "      --config INI       the DEM run's configuration, not DEM_DIR/config.ini\n"
     "      --no-refine        the thesis relations only, no spot runs\n"
     "      --runs N           the refinement's spot runs at most, 1-100 (default 6;\n"
     "                         each step moves a parameter by a factor 1.5 at most)\n"
     "  -q, --quiet            no progress lines\n" GF_HELP_LINE},
    {"compare",
     "usage: granflow compare DEM_DIR SPOT_DIR [--timestep DT] [--config INI] [--set KEY=VALUE]...\n"
     "                        [-o OUTDIR] [--no-plots] [-q]\n"
     "Puts a DEM run and a spot run side by side (thesis Sec. 3.5): flow rate, velocity\n"
     "profiles, diffusion, g(r), g3, density drop, residence times and central slices\n"
     "at the same times; differences with uncertainties and verdicts. The exit code\n"
     "does not depend on the verdicts.\n"
     "\n"
     "options:\n"
     "  -o, --output OUTDIR    where the results go (default SPOT_DIR/compare)\n"
     "  -s, --set KEY=VALUE    an analysis option or a configuration key of the DEM run; repeatable\n"
     "      --timestep DT      tau per LAMMPS step, for dumps without ITEM: TIME\n"
     "      --config INI       the DEM run's configuration, not DEM_DIR/config.ini\n"
     "      --no-plots         CSV files and summary.md only\n"
     "  -q, --quiet            no progress lines\n" GF_HELP_LINE},
    {"lga",
     "usage: granflow lga [CONFIG] [--set lga.KEY=VALUE]... [-o DIR] [--force] [-q]\n"
     "Runs the 2D lattice-gas automaton (lga.scenario: pile, channel or silo) into DIR:\n"
     "density maps, a contact sheet, CSV series and summary.json (docs/lga.md).\n"
     "\n"
     "options:\n"
     "  -o, --output DIR       the run directory (default runs/lga)\n" GF_SET_LINE
     "  -f, --force            replace a run in DIR\n"
     "  -q, --quiet            no progress line\n" GF_HELP_LINE},
    {"report",
     "usage: granflow report DIR [-o FILE] [-q]\n"
     "Writes one self-contained HTML page of a run directory (spot or LGA): its\n"
     "summary, the analysis, every picture inlined, a DEM comparison, config.ini.\n"
     "\n"
     "options:\n"
     "  -o, --output FILE      the page (default DIR/report.html)\n"
     "  -q, --quiet            do not say what was written\n" GF_HELP_LINE},
    {"help",
     "usage: granflow help [COMMAND]\n"
     "Lists the commands, or prints COMMAND's usage (as granflow COMMAND --help).\n"
     "\n"
     "options:\n" GF_HELP_LINE},
};

const char *gf_cli_usage(const char *cmd)
{
    for (size_t k = 0; k < sizeof gf_usages / sizeof gf_usages[0]; k++)
        if (!strcmp(gf_usages[k].cmd, cmd)) return gf_usages[k].text;
    return NULL;
}
