// SPDX-License-Identifier: MIT
// A run directory's configuration and mesh copy (run/mesh_copy.h).
#include "run/mesh_copy.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "geom/container.h"
#include "geom/stl.h"

#define GF_RUN_MESH_NAME "container.stl"

static gf_status gf_run_copy_file(const char *from, const char *to)
{
    struct stat a, b;
    if (stat(from, &a) == 0 && stat(to, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino) return GF_OK;
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;
    gf_status st = gf_fs_read_all(from, GF_STL_MAX_BYTES, &data, &len, &cap);
    if (st != GF_OK) return st;
    char tmp[GF_PATH_MAX + 64];
    FILE *f;
    st = gf_atomic_open(to, tmp, sizeof tmp, &f);
    if (st == GF_OK) {
        if (fwrite(data, 1, len, f) != len) {
            gf_atomic_abort(f, tmp);
            st = gf_error_set(GF_ERR_IO, "%s: write error", to);
        } else {
            st = gf_atomic_commit(f, tmp, to);
        }
    }
    gf_free(data, cap);
    return st;
}

gf_status gf_run_save_config(const gf_config *cfg, const char *dir, const char *cfgpath)
{
    gf_container_defs d;
    gf_config_container_defs(cfg, &d);
    const gf_container box = gf_container_build(&d);
    if (!gf_container_reads_key(&box, "container.mesh")) return gf_config_save(cfg, cfgpath);
    char to[GF_PATH_MAX + 64];
    snprintf(to, sizeof to, "%s/%s", dir, GF_RUN_MESH_NAME);
    gf_status st = gf_run_copy_file(d.mesh, to);
    if (st != GF_OK) return st;
    gf_config c = *cfg;
    gf_config_set_mesh_path(&c, GF_RUN_MESH_NAME);
    return gf_config_save(&c, cfgpath);
}
