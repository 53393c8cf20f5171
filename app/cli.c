// SPDX-License-Identifier: MIT
#include "cli.h"

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

bool gf_cli_parse(int argc, char **argv, const char *cmd, gf_cli *cli)
{
    memset(cli, 0, sizeof *cli);
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
#define GF_NEED_VALUE()                                                                 \
    do {                                                                                \
        if (!val) {                                                                     \
            fprintf(stderr, "granflow %s: error: %s needs a value\n", cmd, a);         \
            return false;                                                               \
        }                                                                               \
        i++;                                                                            \
    } while (0)
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            GF_NEED_VALUE();
            cli->out = val;
        } else if (!strcmp(a, "--set") || !strcmp(a, "-s")) {
            GF_NEED_VALUE();
            if (cli->nsets == (int)(sizeof cli->sets / sizeof cli->sets[0])) {
                fprintf(stderr, "granflow %s: error: too many --set options\n", cmd);
                return false;
            }
            cli->sets[cli->nsets++] = val;
        } else if (!strncmp(a, "--set=", 6)) {
            if (cli->nsets == (int)(sizeof cli->sets / sizeof cli->sets[0])) {
                fprintf(stderr, "granflow %s: error: too many --set options\n", cmd);
                return false;
            }
            cli->sets[cli->nsets++] = a + 6;
        } else if (!strcmp(a, "--resume")) {
            GF_NEED_VALUE();
            cli->resume = val;
        } else if (!strcmp(a, "--json")) {
            cli->json = true;
        } else if (!strcmp(a, "--force") || !strcmp(a, "-f")) {
            cli->force = true;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            cli->quiet = true;
        } else if (!strcmp(a, "--particles")) {
            GF_NEED_VALUE();
            if (!gf_cli_number(cmd, a, val, &cli->bench_particles)) return false;
        } else if (!strcmp(a, "--warmup")) {
            GF_NEED_VALUE();
            if (!gf_cli_number(cmd, a, val, &cli->bench_warmup)) return false;
        } else if (!strcmp(a, "--window")) {
            GF_NEED_VALUE();
            if (!gf_cli_number(cmd, a, val, &cli->bench_window)) return false;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "granflow %s: error: unknown option '%s' (see granflow help)\n", cmd, a);
            return false;
        } else if (!cli->config_path) {
            cli->config_path = a;
        } else {
            fprintf(stderr, "granflow %s: error: unexpected argument '%s' (one CONFIG file at most; "
                            "see granflow help)\n", cmd, a);
            return false;
        }
#undef GF_NEED_VALUE
    }
    return true;
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
