// SPDX-License-Identifier: MIT
// `granflow report DIR`: one self-contained HTML page of a run (DIR/report.html).
#include <stdio.h>

#include "cli.h"

int gf_cmd_report(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "report", &cli);
    if (rc != GF_CLI_GO) return rc;
    if (!cli.config_path) {
        fprintf(stderr, "granflow report: error: give one run directory\n"
                        "usage: granflow report DIR [-o FILE] [-q]\n");
        return GF_EXIT_USAGE;
    }
    gf_report_opts o = gf_report_opts_default();
    o.out = cli.out;
    gf_report_info info;
    gf_status st = gf_report_write(cli.config_path, &o, &info);
    if (st != GF_OK) return gf_cli_fail("report", st);
    if (!cli.quiet)
        fprintf(stderr, "granflow report: wrote %s%s (%zu pictures%s, %.1f MB)\n", cli.out ? cli.out : cli.config_path,
                cli.out ? "" : "/report.html", info.images, info.compared ? ", DEM comparison" : "",
                (double)info.bytes / 1e6);
    return GF_EXIT_OK;
}
