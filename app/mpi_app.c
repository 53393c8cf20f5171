// SPDX-License-Identifier: MIT
// The CLI's MPI side (GF_MPI=ON): see mpi_app.h.
#define _XOPEN_SOURCE 700
#include "mpi_app.h"

#include <inttypes.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/core.h"
#include "granflow/defs.h"

/// Every rank refused at the same point: MPI_Finalize, not MPI_Abort.
static bool gf_mpi_app_together;

int gf_mpi_app_init(int *argc, char ***argv)
{
    MPI_Init(argc, argv);
    return gf_mpi_app_rank();
}

int gf_mpi_app_rank(void)
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

static int gf_mpi_app_size(void)
{
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

int gf_mpi_app_ranks(void) { return gf_mpi_app_size(); }

int gf_mpi_app_end(int rc)
{
    if (rc != 0 && rc != 130 && gf_mpi_app_size() > 1 && !gf_mpi_app_together) MPI_Abort(MPI_COMM_WORLD, rc);
    MPI_Finalize();
    return rc;
}

int gf_mpi_app_check(const gf_config *cfg)
{
    gf_engine_defs ed;
    gf_config_engine_defs(cfg, &ed);
    if (gf_mpi_app_size() < 2 || (ed.spatial && ed.order != GF_ORDER_SWEEP)) return 0;
    if (gf_mpi_app_rank() == 0)
        fprintf(stderr, "granflow run: error: %d MPI ranks need run.mode = fixed and run.order = spatial or "
                        "domains (the engines split between ranks); run the others as one process\n",
                gf_mpi_app_size());
    gf_mpi_app_together = true;
    return 2;
}

// FNV-1a, 64 bits.
static uint64_t gf_mpi_app_hash(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

// "N bytes, hash H" of a whole file, or why it cannot be read.
static void gf_mpi_app_file(const char *path, char *out, size_t n)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(out, n, "unreadable");
        return;
    }
    uint64_t h = 0xcbf29ce484222325ull, size = 0;
    unsigned char buf[1 << 16];
    for (size_t k; (k = fread(buf, 1, sizeof buf, f)) > 0; size += k) h = gf_mpi_app_hash(h, buf, k);
    bool bad = ferror(f);
    fclose(f);
    if (bad) snprintf(out, n, "unreadable");
    else snprintf(out, n, "%" PRIu64 " bytes, FNV-1a %016" PRIx64, size, h);
}

// What every rank must agree on, one "name = value" line each: the version,
// every key of the configuration but run.threads (results do not depend on
// it), the checkpoint and the packing file read. malloc'ed, *len bytes.
static char *gf_mpi_app_settings(const gf_config *cfg, const char *resume_dir, size_t *len)
{
    char *ini = NULL, *text = NULL;
    size_t ilen = 0;
    FILE *f = open_memstream(&ini, &ilen);
    if (!f) return NULL;
    bool ok = gf_config_write(cfg, f) == GF_OK;
    if (fclose(f) != 0 || !ok) {
        free(ini);
        return NULL;
    }
    FILE *t = open_memstream(&text, len);
    if (!t) {
        free(ini);
        return NULL;
    }
    fprintf(t, "granflow version = %s\n", gf_version());
    char section[64] = "";
    for (char *line = strtok(ini, "\n"); line; line = strtok(NULL, "\n")) {
        if (line[0] == ';' || line[0] == '#') continue;
        if (line[0] == '[') {
            snprintf(section, sizeof section, "%.*s", (int)strcspn(line + 1, "]"), line + 1);
            continue;
        }
        if (!strcmp(section, "run") && !strncmp(line, "threads =", 9)) continue;
        fprintf(t, "%s.%s\n", section, line);
    }
    free(ini);
    char what[128], path[4200];
    if (resume_dir) {
        snprintf(path, sizeof path, "%s/checkpoint.bin", resume_dir);
        gf_mpi_app_file(path, what, sizeof what);
        fprintf(t, "checkpoint.bin = %s\n", what); // its path may differ (a directory per node)
    }
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    if (pd.file[0]) {
        gf_mpi_app_file(pd.file, what, sizeof what);
        fprintf(t, "packing.file contents = %s\n", what);
    }
    if (fclose(t) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

// A "name = value" line of n bytes split: the name's length (without the
// spaces before '='), and the value (after them) in *v, *vn.
static size_t gf_mpi_app_split(const char *line, size_t n, const char **v, int *vn)
{
    const char *eq = memchr(line, '=', n);
    size_t k = eq ? (size_t)(eq - line) : n, at = eq ? k + 1 : n;
    while (at < n && line[at] == ' ') at++;
    while (k > 0 && line[k - 1] == ' ') k--;
    *v = line + at;
    *vn = (int)(n - at);
    return k;
}

// The first line of `mine` that is not `ref`'s line at the same place, said
// as "NAME = VALUE where rank 0 has VALUE" in out (n bytes); empty when the
// texts agree.
static void gf_mpi_app_diff(const char *mine, const char *ref, char *out, size_t n)
{
    out[0] = '\0';
    while (*mine || *ref) {
        size_t a = strcspn(mine, "\n"), b = strcspn(ref, "\n");
        if (a != b || memcmp(mine, ref, a) != 0) {
            const char *va, *vb;
            int na, nb;
            size_t ka = gf_mpi_app_split(mine, a, &va, &na), kb = gf_mpi_app_split(ref, b, &vb, &nb);
            if (a && b && ka == kb && !memcmp(mine, ref, ka)) // the same key, another value
                snprintf(out, n, "%.*s = %.*s where rank 0 has %.*s", (int)ka, mine, na, va, nb, vb);
            else if (a && b)
                snprintf(out, n, "%.*s where rank 0 has %.*s", (int)a, mine, (int)b, ref);
            else if (a)
                snprintf(out, n, "%.*s where rank 0 has nothing", (int)a, mine);
            else
                snprintf(out, n, "nothing where rank 0 has %.*s", (int)b, ref);
            return;
        }
        mine += a + (mine[a] == '\n');
        ref += b + (ref[b] == '\n');
    }
}

int gf_mpi_app_agree(const gf_config *cfg, const char *resume_dir)
{
    const int R = gf_mpi_app_size(), me = gf_mpi_app_rank();
    if (R < 2) return 0;
    size_t len = 0;
    char *text = gf_mpi_app_settings(cfg, resume_dir, &len);
    // A rank that could not make its text takes part all the same (a hash no
    // text has), so that the others do not wait for it.
    uint64_t h = text ? gf_mpi_app_hash(0xcbf29ce484222325ull, text, len) : 0, mine[2] = {h, ~h}, most[2];
    MPI_Allreduce(mine, most, 2, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    if (most[0] == ~most[1] && text) {
        free(text);
        return 0;
    }
    // They differ: rank 0's text goes to every rank, each finds its first
    // difference, and rank 0 prints them all.
    enum { GF_LINE = 600 };
    unsigned long long rlen = me == 0 ? (unsigned long long)(text ? len : 0) : 0;
    MPI_Bcast(&rlen, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    char *ref = malloc(rlen + 1), line[GF_LINE] = "";
    char *all = me == 0 ? malloc((size_t)R * GF_LINE) : NULL;
    if (!ref || (me == 0 && !all)) {
        fprintf(stderr, "granflow run: error: rank %d: out of memory comparing the ranks' settings\n", me);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (me == 0 && rlen) memcpy(ref, text, rlen);
    MPI_Bcast(ref, (int)rlen, MPI_CHAR, 0, MPI_COMM_WORLD);
    ref[rlen] = '\0';
    if (!text) snprintf(line, sizeof line, "(out of memory making its settings)");
    else if (me > 0) gf_mpi_app_diff(text, ref, line, sizeof line);
    MPI_Gather(line, GF_LINE, MPI_CHAR, all, GF_LINE, MPI_CHAR, 0, MPI_COMM_WORLD);
    if (me == 0) {
        fprintf(stderr, "granflow run: error: the MPI ranks do not run the same settings (every rank needs the same "
                        "configuration, granflow version and checkpoint; only run.threads may differ):\n");
        for (int r = 1; r < R; r++)
            if (all[(size_t)r * GF_LINE])
                fprintf(stderr, "  rank %d has %.*s\n", r, GF_LINE, all + (size_t)r * GF_LINE);
    }
    free(all);
    free(ref);
    free(text);
    gf_mpi_app_together = true;
    return 2;
}
