// SPDX-License-Identifier: MIT
// The particles of a simulation driven by hand, written as the run
// directory writes its snapshots (gf_sim_write_snapshot, gf_sim_write_vtk;
// granflow/run.h). gf_sim_write_run_dir is in rundir.c, beside the writers
// of the other files of a run directory.
#include "granflow/run.h"

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "io/vtk.h"

typedef enum gf_sim_format { GF_SIM_DUMP, GF_SIM_VTK } gf_sim_format;

static gf_status gf_sim_write(const gf_sim *sim, const char *path, gf_sim_format fmt)
{
    if (!sim || !path) return gf_error_set(GF_ERR_PARAM, "gf_sim_write_%s: NULL argument", fmt ? "vtk" : "snapshot");
    const gf_config *cfg = gf_sim_config(sim);
    gf_packing pk = {0};
    int32_t *pass = NULL;
    size_t npass = 0;
    gf_status st = gf_sim_particles(sim, &pk);
    // The pass column exists only under recirculation, as in `granflow run`.
    gf_rundir_defs d;
    gf_config_rundir_defs(cfg, &d);
    if (st == GF_OK && d.recirculate && pk.n) {
        npass = pk.n;
        pass = GF_NEW(int32_t, npass);
        st = pass ? gf_sim_passes(sim, pass, npass) : gf_error_set(GF_ERR_NOMEM, "out of memory");
    }
    gf_sim_stats s = gf_sim_get_stats(sim);
    if (st == GF_OK)
        st = fmt == GF_SIM_DUMP ? gf_run_write_snapshot(path, cfg, &pk, pass, s.time, s.events)
                                : gf_vtk_write_particles(path, &pk, pass, s.time);
    GF_DELETE(pass, npass);
    gf_packing_free(&pk);
    return st;
}

gf_status gf_sim_write_snapshot(const gf_sim *sim, const char *path) { return gf_sim_write(sim, path, GF_SIM_DUMP); }

gf_status gf_sim_write_vtk(const gf_sim *sim, const char *path) { return gf_sim_write(sim, path, GF_SIM_VTK); }
