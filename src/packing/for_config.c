// SPDX-License-Identifier: MIT
// The initial packing a config asks for: packing.file imported, else
// generated. Every path to a config's packing goes through here.
#include "granflow/packing.h"

#include "granflow/defs.h"

gf_status gf_packing_for_config(const gf_config *cfg, const gf_packing_opts *opts, gf_packing *out,
                                gf_packing_import_report *rep)
{
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    if (rep) *rep = (gf_packing_import_report){0};
    if (!pd.file[0]) return gf_packing_generate(cfg, opts, out);
    return gf_packing_import(cfg, out, rep);
}
