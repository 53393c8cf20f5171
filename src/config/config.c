// SPDX-License-Identifier: MIT
// gf_config: defaults from the key table, INI loading (libinih), `section.key=value`
// overrides, cross-key validation, and writing the effective values back out.
#include "granflow/config.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config/derive.h"
#include "config/keys.h"
#include "config/orifice.h"
#include "config/where.h"
#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/shape_check.h"
#include "core/textscan.h"

// "gfCF": marks a gf_config that came from gf_config_default().
#define GF_CONFIG_COOKIE 0x67664346u

// Longest line (without its newline) a non-comment INI line may have: libinih
// reads lines into a fixed buffer and needs room for "\r\n\0".
#define GF_CONFIG_MAX_LINE (INI_MAX_LINE - 3)

static gf_status gf_config_check(const gf_config *cfg, const char *fn)
{
    if (!cfg) return gf_error_set(GF_ERR_PARAM, "%s: cfg is NULL", fn);
    if (cfg->cookie_ != GF_CONFIG_COOKIE)
        return gf_error_set(GF_ERR_PARAM, "%s: config not made by gf_config_default", fn);
    return GF_OK;
}

// Strips leading and trailing white space in place.
static char *gf_config_trim(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

gf_config gf_config_default(void)
{
    gf_config cfg;
    memset(&cfg, 0, sizeof cfg);
    gf_keys_defaults(&gf_config_keys, &cfg);
    cfg.cookie_ = GF_CONFIG_COOKIE;
    return cfg;
}

// ---- loading -------------------------------------------------------------

// State shared by the line reader and the key handler of one gf_config_load.
typedef struct gf_config_loader {
    gf_config *cfg;
    gf_textscan ts; // the file (capped lines: a file without line ends is an error)
    const char *path;
    int line;          // number of the line last handed to libinih
    int err_line;      // line of the first error found here (message already set), 0: none
    gf_status err;     // status of that error
    gf_status read_st; // a failed read (message already set: too long a line, out of memory, I/O)
} gf_config_loader;

static void gf_config_fail(gf_config_loader *ld, gf_status st)
{
    ld->err_line = ld->line;
    ld->err = st;
}

// First of `chars` in `s` before an inline comment (';' after white space),
// exactly as libinih looks for '=', ':' and ']'; NULL if none.
static const char *gf_config_find(const char *s, const char *chars)
{
    bool was_space = false;
    for (; *s; s++) {
        if (strchr(chars, *s)) return s;
        if (was_space && *s == ';') return NULL;
        was_space = isspace((unsigned char)*s);
    }
    return NULL;
}

// Checks a section header or key line before libinih sees it, so that syntax
// errors and unknown (possibly empty) sections are reported with their line.
static bool gf_config_check_line(gf_config_loader *ld, const char *p)
{
    if (*p == '[') {
        const char *end = gf_config_find(p + 1, "]");
        if (!end) {
            gf_error_set(GF_ERR_PARAM, "%s:%d: syntax error: missing ']' after section name",
                         ld->path, ld->line);
            return false;
        }
        char name[64];
        size_t len = (size_t)(end - (p + 1));
        snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1),
                 p + 1);
        char *s = gf_config_trim(name);
        if (!gf_keys_section_known(&gf_config_keys, s)) {
            char list[128];
            gf_keys_list(&gf_config_keys, NULL, list, sizeof list);
            gf_error_set(GF_ERR_PARAM, "%s:%d: unknown section [%s] (known: %s)", ld->path,
                         ld->line, s, list);
            return false;
        }
        return true;
    }
    if (!gf_config_find(p, "=:")) {
        gf_error_set(GF_ERR_PARAM, "%s:%d: syntax error: expected 'key = value' or '[section]'",
                     ld->path, ld->line);
        return false;
    }
    return true;
}

// libinih reader: one whole line per call, so libinih's count and ours agree.
// Leading white space is removed (an indented line would otherwise continue
// the previous value), comments are blanked, and reading stops at our first error.
static char *gf_config_read_line(char *str, int num, void *stream)
{
    gf_config_loader *ld = stream;
    if (ld->err_line || ld->read_st != GF_OK) return NULL;
    char *p;
    size_t got;
    gf_status st;
    int r = gf_textscan_next(&ld->ts, &p, &got, &st);
    if (r < 0) ld->read_st = st; // never the end of the file: the defaults would run silently
    if (r <= 0) return NULL;
    ld->line++;
    // A NUL would end the line for every string function below: "radius =
    // 2\0junk" read as 2 (issue 26). A configuration file is text.
    const char *nul = memchr(p, '\0', got);
    if (nul) {
        gf_config_fail(ld, gf_error_set(GF_ERR_PARAM, "%s:%d: a NUL byte (\\0) at column %zu: a configuration "
                                                      "file is text",
                                        ld->path, ld->line, (size_t)(nul - p) + 1));
        return NULL;
    }
    if (ld->line == 1 && got >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3; // UTF-8 BOM
    p = gf_config_trim(p);
    if (*p == ';' || *p == '#' || *p == '\0') {
        str[0] = '\0'; // comment or blank: any length up to the reader's cap
        return str;
    }
    size_t len = strlen(p);
    if (len > (size_t)num - 3 || len > GF_CONFIG_MAX_LINE) {
        gf_config_fail(ld, gf_error_set(GF_ERR_PARAM,
                                        "%s:%d: line too long (%zu characters, at most %d)",
                                        ld->path, ld->line, len, GF_CONFIG_MAX_LINE));
        return NULL;
    }
    if (!gf_config_check_line(ld, p)) {
        gf_config_fail(ld, GF_ERR_PARAM);
        return NULL;
    }
    memcpy(str, p, len + 1);
    return str;
}

// container.mesh, relative, is read from the INI file's folder (a run
// directory's config.ini names its own copy, container.stl, so).
static gf_status gf_config_mesh_path(gf_config_loader *ld, const char *lead)
{
    char *mesh = ld->cfg->container_mesh;
    const char *slash = strrchr(ld->path, '/');
    if (!mesh[0] || mesh[0] == '/' || !slash) return GF_OK;
    char joined[2 * GF_PATH_MAX];
    int n = snprintf(joined, sizeof joined, "%.*s/%s", (int)(slash - ld->path), ld->path, mesh);
    if (n >= GF_PATH_MAX)
        return gf_error_set(GF_ERR_PARAM, "%s: container.mesh: path too long from the INI file's folder (%d bytes, at most %d)",
                            lead, n, GF_PATH_MAX - 1);
    memcpy(mesh, joined, (size_t)n + 1);
    return GF_OK;
}

// libinih handler: one `name = value` of `section` on line ld->line.
static int gf_config_on_pair(void *user, const char *section, const char *name, const char *value)
{
    gf_config_loader *ld = user;
    if (ld->err_line) return 0;
    char lead[GF_PATH_MAX + 32];
    snprintf(lead, sizeof lead, "%s:%d", ld->path, ld->line);
    char sec[64];
    snprintf(sec, sizeof sec, "%s", section);
    char *s = gf_config_trim(sec);
    gf_status st;
    if (!*s) {
        st = gf_error_set(GF_ERR_PARAM, "%s: key '%s' is outside any [section]", lead, name);
    } else {
        const gf_key *k;
        st = gf_keys_apply(&gf_config_keys, ld->cfg, lead, true, s, name, value ? value : "", &k);
        if (st == GF_OK && k->offset == offsetof(gf_config, container_mesh)) st = gf_config_mesh_path(ld, lead);
        if (st == GF_OK) gf_config_mark(ld->cfg, k, ld->path, ld->line);
    }
    if (st != GF_OK) {
        gf_config_fail(ld, st);
        return 0;
    }
    return 1;
}

gf_status gf_config_load(gf_config *cfg, const char *path)
{
    gf_status st = gf_config_check(cfg, "gf_config_load");
    if (st != GF_OK) return st;
    if (!path) return gf_error_set(GF_ERR_PARAM, "gf_config_load: path is NULL");
    gf_config_loader ld = {.cfg = cfg, .path = path};
    errno = 0;
    if (gf_textscan_open(&ld.ts, path) != GF_OK)
        return gf_error_set(errno ? GF_ERR_IO : GF_ERR_NOMEM, "cannot open config file '%s': %s", path,
                            errno ? strerror(errno) : "out of memory");
    ld.ts.max_line = GF_TEXTSCAN_MAX_SHORT_LINE;
    int ret = ini_parse_stream(gf_config_read_line, &ld, gf_config_on_pair, &ld);
    gf_textscan_close(&ld.ts);
    if (ld.read_st == GF_ERR_FORMAT) { // a line over the cap: a bad configuration (exit 2), same message
        char msg[1024];
        snprintf(msg, sizeof msg, "%s", gf_last_error());
        return gf_error_set(GF_ERR_PARAM, "%s", msg);
    }
    if (ld.read_st != GF_OK) return ld.read_st; // out of memory, I/O: the message names the file and line
    if (ld.err_line && (ret <= 0 || ret >= ld.err_line)) return ld.err;
    // libinih found an error our line checks did not anticipate.
    if (ret > 0) return gf_error_set(GF_ERR_PARAM, "%s:%d: syntax error", path, ret);
    if (ret == -2) return gf_error_set(GF_ERR_NOMEM, "%s: out of memory while parsing", path);
    return GF_OK;
}

// ---- overrides -----------------------------------------------------------

gf_status gf_config_set(gf_config *cfg, const char *assignment, const char *origin)
{
    gf_status st = gf_config_check(cfg, "gf_config_set");
    if (st != GF_OK) return st;
    if (!origin || !*origin) origin = "gf_config_set";
    const gf_key *k;
    st = gf_keys_set(&gf_config_keys, cfg, assignment, origin, &k);
    if (st == GF_OK) gf_config_mark(cfg, k, origin, 0);
    return st;
}

// ---- validation ----------------------------------------------------------

// At most GF_MAX_OUTPUTS outputs (`what`) of interval `key` per run.duration.
static gf_status gf_check_outputs(const gf_config *cfg, double dt, const char *key, const char *what,
                                  const char *or_else)
{
    if (cfg->run_duration / dt <= GF_MAX_OUTPUTS) return GF_OK;
    gf_config_msg m;
    gf_config_msg_make(&m, cfg, key, "run.duration");
    return gf_error_set(GF_ERR_PARAM,
                        "%s%s is too small for %s: at most %d %s per run (interval >= run.duration / %d%s)",
                        m.lead, m.key[0], m.key[1], GF_MAX_OUTPUTS, what, GF_MAX_OUTPUTS, or_else);
}

// A shape's own keys (a cylinder's radius, a wedge's slope, a mesh's file)
// are checked by that shape (its validate op in src/geom/, reached through
// core/shape_check.h: config cannot call geom), which also completes what
// they settle: the bounding box in container.width and depth, the outlet in
// container.orifice_shape and orifice_diameter. `wall_key` receives the key
// that bounds a spot's room across it (NULL: width or depth). A static
// link that leaves geom/shapes.c out has no check: an error, not a config
// passed unchecked (granflow_static and granflow.pc pull it in).
static gf_status gf_config_validate_shape(gf_config *cfg, const char **wall_key)
{
    *wall_key = NULL;
    gf_shape_validate_fn *check = gf_shape_validate_get();
    if (!check) {
        gf_config_msg m;
        gf_config_msg_make(&m, cfg, "container.shape", NULL);
        return gf_error_set(GF_ERR_STATE, "%s%s: the geometry library is not linked in (geom/shapes.c)", m.lead,
                            m.key[0]);
    }
    return check(cfg, wall_key);
}

gf_status gf_config_validate(gf_config *cfg)
{
    gf_status st = gf_config_check(cfg, "gf_config_validate");
    if (st != GF_OK) return st;
    gf_config_msg m;
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        char why[160], key[160];
        if (!gf_keys_check(k, cfg, why, sizeof why)) {
            snprintf(key, sizeof key, "%s.%s", k->section, k->name);
            gf_config_msg_make(&m, cfg, key, NULL);
            return gf_error_set(GF_ERR_PARAM, "%s%s: %s", m.lead, m.key[0], why);
        }
    }
    cfg->spot_insertion_margin = gf_config_insertion_margin(cfg);
    cfg->relax_radius = gf_config_r_e(cfg);
    cfg->dem_kt = gf_config_dem_kt(cfg);
    cfg->dem_gammat = gf_config_dem_gammat(cfg);

    const char *wall_key;
    if ((st = gf_config_validate_shape(cfg, &wall_key)) != GF_OK) return st;
    if (!(cfg->orifice_diameter < cfg->container_width)) {
        gf_config_msg_make(&m, cfg, "container.orifice_diameter", "container.width");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be less than %s", m.lead, m.key[0], m.key[1]);
    }
    if ((st = gf_config_check_orifice(cfg)) != GF_OK) return st;
    double room = fmin(cfg->container_width, cfg->container_depth);
    if (!(2.0 * cfg->spot_wall_distance < room)) {
        const char *wall = wall_key                                      ? wall_key
                           : cfg->container_depth < cfg->container_width ? "container.depth"
                                                                         : "container.width";
        gf_config_msg_make(&m, cfg, "spot.wall_distance", wall);
        char r[32];
        gf_keys_format_double(room, r, sizeof r);
        return gf_error_set(GF_ERR_PARAM,
                            "%s%s leaves spots no room: 2 * spot.wall_distance must be less than "
                            "min(container.width, container.depth) = %s (%s)",
                            m.lead, m.key[0], r, m.key[1]);
    }
    if (!(cfg->relax_radius >= cfg->spot_radius)) {
        gf_config_msg_make(&m, cfg, "relax.radius", "spot.radius");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be at least %s", m.lead, m.key[0], m.key[1]);
    }
    if (!(cfg->stress_wall_friction_angle <= cfg->stress_friction_angle)) {
        // A wall rougher than the material: the material shears inside, not on the wall.
        gf_config_msg_make(&m, cfg, "stress.wall_friction_angle", "stress.friction_angle");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be at most %s", m.lead, m.key[0], m.key[1]);
    }
    if (cfg->spot_flow_rule == GF_FLOW_SFR && cfg->container_shape == GF_SHAPE_CYLINDER &&
        cfg->inner_radius > 0.0) {
        // The stress solver has no annulus (docs/stress.md).
        gf_config_msg_make(&m, cfg, "spot.flow_rule", "container.inner_radius");
        return gf_error_set(GF_ERR_PARAM, "%sspot.flow_rule = sfr does not support a central column (%s > 0)",
                            m.lead, m.key[1]);
    }
    if (cfg->spot_flow_rule == GF_FLOW_SFR && !(cfg->spot_step_xy > 0.0)) {
        // The slip-line step's length is set by the lateral step (docs/stress.md).
        gf_config_msg_make(&m, cfg, "spot.flow_rule", "spot.step_xy");
        return gf_error_set(GF_ERR_PARAM, "%sspot.flow_rule = sfr needs %s > 0", m.lead, m.key[1]);
    }
    if (cfg->spot_flow_rule == GF_FLOW_SFR && cfg->run_mode == GF_MODE_FIXED &&
        (cfg->run_order == GF_ORDER_SPATIAL || cfg->run_order == GF_ORDER_DOMAINS)) {
        // Their blocks assume a spot moves up by step_z and across by step_xy; sfr steps go down too.
        gf_config_msg_make(&m, cfg, "spot.flow_rule", "run.order");
        return gf_error_set(GF_ERR_PARAM, "%sspot.flow_rule = sfr needs %s = random or newest", m.lead, m.key[1]);
    }
    if (cfg->run_mode == GF_MODE_FIXED && cfg->run_order == GF_ORDER_SWEEP && cfg->relax_method != GF_RELAX_FULL &&
        cfg->relax_method != GF_RELAX_NONE) {
        // Its relaxation is the window's sweeps over every particle its moves reached.
        gf_config_msg_make(&m, cfg, "run.order", "relax.method");
        return gf_error_set(GF_ERR_PARAM, "%s%s = sweep needs %s = full or none (the window's Jacobi sweeps are its "
                            "relaxation)", m.lead, m.key[0], m.key[1]);
    }
    // Output intervals: a bounded number per run (an interval below the
    // rounding of the time would never advance, and the run never end).
    st = gf_check_outputs(cfg, cfg->output_snapshot_interval, "output.snapshot_interval", "snapshots", "");
    if (st == GF_OK && cfg->run_checkpoint_interval > 0)
        st = gf_check_outputs(cfg, cfg->run_checkpoint_interval, "run.checkpoint_interval", "checkpoints",
                              ", or 0 for none");
    if (st != GF_OK) return st;
    if (!(cfg->spot_insertion_rate / cfg->spot_move_rate <= GF_MAX_SPOTS_PER_MOVE)) {
        gf_config_msg_make(&m, cfg, "spot.insertion_rate", "spot.move_rate");
        return gf_error_set(GF_ERR_PARAM,
                            "%s%s is too high for %s: at most %g spots born per move time (the papers use ~13)",
                            m.lead, m.key[0], m.key[1], GF_MAX_SPOTS_PER_MOVE);
    }
    if (cfg->run_reinsert == GF_REINSERT_ZONE && !isnan(cfg->run_reinsert_rmax) &&
        !(cfg->run_reinsert_rmin < cfg->run_reinsert_rmax)) {
        gf_config_msg_make(&m, cfg, "run.reinsert_rmin", "run.reinsert_rmax");
        return gf_error_set(GF_ERR_PARAM, "%s%s must be less than %s", m.lead, m.key[0], m.key[1]);
    }
    size_t ntypes;
    int32_t types[GF_PACKING_MAXTYPES];
    if (gf_packing_types_parse(cfg->packing_types, types, GF_PACKING_MAXTYPES, &ntypes) != GF_OK) {
        char why[256];
        snprintf(why, sizeof why, "%s", gf_last_error());
        gf_config_msg_make(&m, cfg, "packing.types", NULL);
        return gf_error_set(GF_ERR_PARAM, "%s%s: %s", m.lead, m.key[0], why);
    }
    // A Hooke contact of stiffness k_n between two unit masses lasts pi / sqrt(2 k_n)
    // tau; a Hertzian one is softer, so a fifth of that bounds the step safely.
    double dt_max = 0.2 * 3.14159265358979323846 / sqrt(2.0 * cfg->dem_kn);
    if (!(cfg->dem_timestep <= dt_max)) {
        gf_config_msg_make(&m, cfg, "dem.timestep", "dem.kn");
        char b[32];
        snprintf(b, sizeof b, "%.3g", dt_max);
        return gf_error_set(GF_ERR_PARAM, "%s%s is too long for %s: at most 0.2 pi / sqrt(2 kn) = %s tau", m.lead,
                            m.key[0], m.key[1], b);
    }
    return GF_OK;
}

// ---- writing -------------------------------------------------------------

// Why libinih would not read `path` back unchanged as the value of `key`, or NULL.
static const char *gf_config_unwritable(const char *key, const char *path)
{
    size_t len = strlen(path);
    if (strpbrk(path, "\r\n")) return "contains a line break";
    if (len > 0 && (isspace((unsigned char)path[0]) || isspace((unsigned char)path[len - 1])))
        return "starts or ends with white space";
    for (size_t i = 1; i < len; i++)
        if (path[i] == ';' && isspace((unsigned char)path[i - 1]))
            return "contains ';' after white space (an INI comment)";
    if (strlen(key) + 3 + len > GF_CONFIG_MAX_LINE) return "is too long for one INI line";
    return NULL;
}

gf_status gf_config_check_writable(const gf_config *cfg)
{
    gf_status st = gf_config_check(cfg, "gf_config_check_writable");
    if (st != GF_OK) return st;
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        if (k->type != GF_KEY_PATH) continue;
        const char *bad = gf_config_unwritable(k->name, (const char *)cfg + k->offset);
        if (!bad) continue;
        char key[160];
        snprintf(key, sizeof key, "%s.%s", k->section, k->name);
        gf_config_msg m;
        gf_config_msg_make(&m, cfg, key, NULL);
        return gf_error_set(GF_ERR_PARAM, "%s%s %s: config.ini could not hold it (rename the file, or move it)",
                            m.lead, m.key[0], bad);
    }
    return GF_OK;
}

gf_status gf_config_write(const gf_config *cfg, FILE *out)
{
    gf_status st = gf_config_check(cfg, "gf_config_write");
    if (st != GF_OK) return st;
    if (!out) return gf_error_set(GF_ERR_PARAM, "gf_config_write: out is NULL");
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        char why[160];
        if (!gf_keys_check(k, cfg, why, sizeof why))
            return gf_error_set(GF_ERR_PARAM, "gf_config_write: %s.%s: %s", k->section, k->name,
                                why);
        if (k->type != GF_KEY_PATH) continue;
        const char *path = (const char *)cfg + k->offset;
        const char *bad = gf_config_unwritable(k->name, path);
        if (bad)
            return gf_error_set(GF_ERR_PARAM, "gf_config_write: %s.%s '%s' %s", k->section, k->name,
                                path, bad);
    }

    fprintf(out, "# granflow configuration (effective values)\n");
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        if (i == 0 || strcmp(gf_keys[i - 1].section, k->section) != 0)
            fprintf(out, "\n[%s]\n", k->section);
        char value[GF_PATH_MAX];
        gf_keys_format(k, cfg, value, sizeof value);
        fprintf(out, "; %s%s%s%s, default %s\n", k->doc, *k->unit ? " [" : "", k->unit,
                *k->unit ? "]" : "", *k->def ? k->def : "empty");
        fprintf(out, "%s =%s%s\n", k->name, *value ? " " : "", value);
    }
    if (ferror(out)) return gf_error_set(GF_ERR_IO, "gf_config_write: write error");
    return GF_OK;
}

gf_status gf_config_save(const gf_config *cfg, const char *path)
{
    gf_status st = gf_config_check(cfg, "gf_config_save");
    if (st != GF_OK) return st;
    if (!path) return gf_error_set(GF_ERR_PARAM, "gf_config_save: path is NULL");
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    if ((st = gf_atomic_open(path, tmp, sizeof tmp, &f)) != GF_OK) return st;
    if ((st = gf_config_write(cfg, f)) != GF_OK) {
        gf_atomic_abort(f, tmp);
        return st;
    }
    return gf_atomic_commit(f, tmp, path);
}

