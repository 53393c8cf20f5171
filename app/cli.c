// SPDX-License-Identifier: MIT
#include "cli.h"

#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static bool gf_cli_number(const char *cmd, const char *opt, const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end || !(v > 0)) {
        fprintf(stderr, "granflow %s: error: %s takes a positive number, not '%s'\n", cmd, opt, s);
        return false;
    }
    *out = v;
    return true;
}

// Option codes of the long-only options (after every char).
enum { GF_OPT_RESUME = 256, GF_OPT_JSON, GF_OPT_PARTICLES, GF_OPT_WARMUP, GF_OPT_WINDOW, GF_OPT_EVENT, GF_OPT_SPATIAL, GF_OPT_SWEEP,
       GF_OPT_NO_LARGE, GF_OPT_LGA_ONLY, GF_OPT_RUN, GF_OPT_DRAIN_ONLY, GF_OPT_CONTINUE };

// Every option of the commands that share gf_cli_parse; `cmds` lists those
// that take it (each command's --help lists the same).
static const struct gf_cli_opt {
    struct option o;
    const char *cmds;
} gf_cli_opts[] = {
    {{"output", required_argument, NULL, 'o'}, "run pack lga report dem"},
    {{"set", required_argument, NULL, 's'}, "run pack config bench lga dem"},
    {{"resume", required_argument, NULL, GF_OPT_RESUME}, "run"},
    {{"force", no_argument, NULL, 'f'}, "run lga dem"},
    {{"quiet", no_argument, NULL, 'q'}, "run pack lga report dem"},
    {{"json", no_argument, NULL, GF_OPT_JSON}, "bench"},
    {{"particles", required_argument, NULL, GF_OPT_PARTICLES}, "bench"},
    {{"warmup", required_argument, NULL, GF_OPT_WARMUP}, "bench"},
    {{"window", required_argument, NULL, GF_OPT_WINDOW}, "bench"},
    {{"event", no_argument, NULL, GF_OPT_EVENT}, "bench"},
    {{"spatial", no_argument, NULL, GF_OPT_SPATIAL}, "bench"},
    {{"sweep", no_argument, NULL, GF_OPT_SWEEP}, "bench"},
    {{"no-large", no_argument, NULL, GF_OPT_NO_LARGE}, "bench"},
    {{"lga-only", no_argument, NULL, GF_OPT_LGA_ONLY}, "bench"},
    {{"run", no_argument, NULL, GF_OPT_RUN}, "dem"},
    {{"drain-only", no_argument, NULL, GF_OPT_DRAIN_ONLY}, "dem"},
    {{"continue", no_argument, NULL, GF_OPT_CONTINUE}, "dem"},
    {{"help", no_argument, NULL, 'h'}, "run pack config bench lga report dem"},
};

static bool gf_cli_takes(const char *cmds, const char *cmd)
{
    size_t n = strlen(cmd);
    for (const char *p = cmds; (p = strstr(p, cmd)) != NULL; p += n)
        if ((p == cmds || p[-1] == ' ') && (p[n] == ' ' || !p[n])) return true;
    return false;
}

int gf_cli_getopt_error(const char *cmd, int c, char **argv)
{
    const char *arg = argv[optind - 1];
    if (c == ':') fprintf(stderr, "granflow %s: error: %s needs a value (see granflow %s --help)\n", cmd, arg, cmd);
    else if (optopt && !strncmp(arg, "--", 2)) // --force=1
        fprintf(stderr, "granflow %s: error: %.*s takes no value (see granflow %s --help)\n", cmd,
                (int)strcspn(arg, "="), arg, cmd);
    else if (optopt && optopt < 256 && arg[0] == '-' && arg[1] != '-')
        fprintf(stderr, "granflow %s: error: unknown option '-%c' (see granflow %s --help)\n", cmd, optopt, cmd);
    else fprintf(stderr, "granflow %s: error: unknown option '%s' (see granflow %s --help)\n", cmd, arg, cmd);
    return GF_EXIT_USAGE;
}

int gf_cli_help(const char *cmd)
{
    fputs(gf_cli_usage(cmd), stdout);
    return GF_EXIT_OK;
}

int gf_cli_parse(int argc, char **argv, const char *cmd, gf_cli *cli)
{
    memset(cli, 0, sizeof *cli);
    enum { N = sizeof gf_cli_opts / sizeof gf_cli_opts[0] };
    struct option longs[N + 1];
    char shorts[32] = ":"; // ':' first: a missing value is reported as ':'
    size_t nl = 0, ns = 1;
    for (size_t k = 0; k < N; k++) {
        if (!gf_cli_takes(gf_cli_opts[k].cmds, cmd)) continue;
        longs[nl++] = gf_cli_opts[k].o;
        int c = gf_cli_opts[k].o.val;
        if (c < 256) {
            shorts[ns++] = (char)c;
            if (gf_cli_opts[k].o.has_arg == required_argument) shorts[ns++] = ':';
        }
    }
    longs[nl] = (struct option){0};
    shorts[ns] = '\0';
    optind = 0; // a fresh scan (GNU: also resets getopt's state)
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, shorts, longs, NULL)) != -1) {
        switch (c) {
        case 'h': return gf_cli_help(cmd);
        case 'o': cli->out = optarg; break;
        case 's':
            if (cli->nsets == (int)(sizeof cli->sets / sizeof cli->sets[0])) {
                fprintf(stderr, "granflow %s: error: too many --set options\n", cmd);
                return GF_EXIT_USAGE;
            }
            cli->sets[cli->nsets++] = optarg;
            break;
        case GF_OPT_RESUME: cli->resume = optarg; break;
        case GF_OPT_JSON: cli->json = true; break;
        case 'f': cli->force = true; break;
        case 'q': cli->quiet = true; break;
        case GF_OPT_PARTICLES:
            if (!gf_cli_number(cmd, "--particles", optarg, &cli->bench_particles)) return GF_EXIT_USAGE;
            break;
        case GF_OPT_WARMUP:
            if (!gf_cli_number(cmd, "--warmup", optarg, &cli->bench_warmup)) return GF_EXIT_USAGE;
            break;
        case GF_OPT_WINDOW:
            if (!gf_cli_number(cmd, "--window", optarg, &cli->bench_window)) return GF_EXIT_USAGE;
            break;
        case GF_OPT_EVENT: cli->event = true; break;
        case GF_OPT_SPATIAL: cli->spatial = true; break;
        case GF_OPT_SWEEP: cli->sweep = true; break;
        case GF_OPT_NO_LARGE: cli->no_large = true; break;
        case GF_OPT_LGA_ONLY: cli->lga_only = true; break;
        case GF_OPT_RUN: cli->dem_run = true; break;
        case GF_OPT_DRAIN_ONLY: cli->drain_only = true; break;
        case GF_OPT_CONTINUE: cli->dem_continue = true; break;
        default: return gf_cli_getopt_error(cmd, c, argv);
        }
    }
    for (int i = optind; i < argc; i++) {
        if (!cli->config_path) {
            cli->config_path = argv[i];
        } else {
            fprintf(stderr, "granflow %s: error: unexpected argument '%s' (one %s at most; see granflow %s --help)\n",
                    cmd, argv[i], strcmp(cmd, "report") ? "CONFIG file" : "run directory", cmd);
            return GF_EXIT_USAGE;
        }
    }
    return GF_CLI_GO;
}

bool gf_cli_config(const gf_cli *cli, const char *base_path, gf_config *cfg)
{
    *cfg = gf_config_default();
    gf_status st = GF_OK;
    if (base_path) st = gf_config_load(cfg, base_path);
    if (st == GF_OK && cli->config_path && cli->config_path != base_path) st = gf_config_load(cfg, cli->config_path);
    for (int i = 0; st == GF_OK && i < cli->nsets; i++) st = gf_config_set(cfg, cli->sets[i], "--set");
    if (st == GF_OK) st = gf_config_validate(cfg);
    if (st != GF_OK) {
        fprintf(stderr, "granflow: error: %s\n", gf_last_error());
        return false;
    }
    return true;
}

int gf_cli_fail(const char *cmd, gf_status st)
{
    return gf_cli_fail_hint(cmd, st, NULL);
}

int gf_cli_fail_hint(const char *cmd, gf_status st, const char *hint)
{
    fprintf(stderr, "granflow %s: error: %s%s%s\n", cmd, *gf_last_error() ? gf_last_error() : gf_status_str(st),
            hint ? " " : "", hint ? hint : "");
    switch (st) {
    case GF_OK: return GF_EXIT_OK;
    case GF_ERR_PARAM:
    case GF_ERR_EXISTS: return GF_EXIT_USAGE;
    case GF_ERR_FORMAT: return GF_EXIT_DATA;
    case GF_ERR_INTERRUPTED: return GF_EXIT_INTERRUPTED;
    default: return GF_EXIT_FAIL;
    }
}

int gf_cli_interrupted(const char *cmd, const char *left)
{
    fprintf(stderr, "granflow %s: stopped by a signal (%s)%s%s\n", cmd,
            *gf_last_error() ? gf_last_error() : "interrupted", left ? "; " : "", left ? left : "");
    return GF_EXIT_INTERRUPTED;
}

static volatile sig_atomic_t gf_cli_stop;
static unsigned gf_cli_grace;

void gf_cli_stop_grace(unsigned seconds) { gf_cli_grace = seconds; }

static void gf_cli_on_signal(int sig)
{
    (void)sig;
    if (!gf_cli_stop && gf_cli_grace > 0) alarm(gf_cli_grace); // async-signal-safe
    gf_cli_stop = 1;
}

volatile sig_atomic_t *gf_cli_catch_stop(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = gf_cli_on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL); // a closed terminal: checkpoint like Ctrl-C
    return &gf_cli_stop;
}
