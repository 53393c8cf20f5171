// SPDX-License-Identifier: MIT
// `granflow config`: the effective configuration, as a valid INI file.
#include <stdio.h>

#include "cli.h"

int gf_cmd_config(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "config", &cli);
    if (rc != GF_CLI_GO) return rc;
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    gf_status st = gf_config_write(&cfg, stdout);
    return st == GF_OK ? GF_EXIT_OK : gf_cli_fail("config", st);
}
