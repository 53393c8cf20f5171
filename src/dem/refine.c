// SPDX-License-Identifier: MIT
// Closed-loop calibration: the thesis' relations (Sec. 3.3) give a first
// guess of the five spot parameters; short spot runs from the DEM's own first
// frame then adjust them until the spot model flows like the DEM (flow rate,
// widths of the v_z(x) profiles). The flow rate and the line Var(z) through
// the measured heights (slope and level) are fitted together by lambda / w,
// step_xy and r_s (refine_step.c: a least-squares step on a model that
// starts from Q = lambda p / w, p ~ r_s^3, d Var / dz = 2 b_s ~ dx^2 and
// learns from the runs; issue 27 item 3). The others follow the relation
// that ties a parameter to what it controls:
//   b_p = b_s / w                 -> w *= b_p,spot / b_p,dem
//   dN = Q h / (mu dz)            -> mu *= dN_spot / dN_dem
//   beta = 0.72 r_s               -> r_s *= beta_dem / beta_spot (first run only; r_s
//                                    then stays out of the joint step)
#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "dem/dem_internal.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "granflow/sim.h"

#define GF_REF_MAXSTEP 1.5 // no parameter changes by more than this factor per run
#define GF_REF_MIN_RS 1.0  // the width fit never makes a spot smaller than a particle
#define GF_REF_RS_PRIOR 0.25 // r_s moves by this fraction at the cost of one target's standard error

/// Snapshots of a spot run kept in memory as a series.
typedef struct gf_ref_capture {
    gf_series *s;
    size_t cap;
    double t_first; ///< the DEM's first frame time: spot time 0
} gf_ref_capture;

static gf_status gf_ref_snapshot(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    (void)index;
    gf_ref_capture *c = ctx;
    gf_series *s = c->s;
    if (s->nframes == c->cap) {
        size_t nc = c->cap ? 2 * c->cap : 64;
        gf_frame *nf = gf_realloc(s->frames, c->cap * sizeof *nf, nc * sizeof *nf);
        if (!nf) return gf_error_set(GF_ERR_NOMEM, "refine: out of memory for %zu snapshots", nc);
        memset(nf + c->cap, 0, (nc - c->cap) * sizeof *nf);
        s->frames = nf;
        c->cap = nc;
    }
    gf_frame *f = &s->frames[s->nframes];
    f->time = c->t_first + time;
    gf_status st = gf_sim_particles(sim, &f->pk);
    if (st == GF_OK) s->nframes++;
    return st;
}

/// Runs the spot model of `cfg` from the DEM's first frame until `until`
/// (DEM time) and returns its snapshots as a series (counted from the
/// snapshots, as the DEM's are).
static gf_status gf_ref_run(const gf_series *dem, const gf_packing *start, const gf_config *cfg, double until,
                            volatile sig_atomic_t *stop, gf_series *out)
{
    memset(out, 0, sizeof *out);
    gf_sim *sim;
    gf_status st = gf_sim_create(cfg, start, &sim);
    if (st != GF_OK) return st;
    gf_ref_capture cap = {.s = out, .t_first = dem->frames[0].time};
    gf_sim_hooks h = {.ctx = &cap, .snapshot = gf_ref_snapshot, .stop = stop};
    st = gf_sim_run(sim, until - dem->frames[0].time, &h);
    // The exits too, as a run directory's exits.csv: the outflow is then
    // measured exactly as on `granflow run`'s output.
    size_t ne = 0;
    const gf_exit *ex = st == GF_OK ? gf_sim_exits(sim, &ne) : NULL;
    if (ne > 0) {
        out->exits = GF_NEW(gf_exit, ne);
        if (!out->exits) {
            st = gf_error_set(GF_ERR_NOMEM, "refine: out of memory for %zu exits", ne);
        } else {
            for (size_t k = 0; k < ne; k++) {
                out->exits[k] = ex[k];
                out->exits[k].time += dem->frames[0].time;
            }
            out->nexits = ne;
            out->has_exits = true;
        }
    }
    gf_sim_destroy(sim);
    // gf_series_free wants the frames array of exactly nframes elements.
    if (cap.cap > out->nframes) {
        gf_frame *nf = out->nframes ? gf_realloc(out->frames, cap.cap * sizeof *nf, out->nframes * sizeof *nf) : NULL;
        if (out->nframes && !nf) {
            st = gf_error_set(GF_ERR_NOMEM, "refine: out of memory");
            for (size_t k = 0; k < out->nframes; k++) gf_packing_free(&out->frames[k].pk);
            gf_free(out->frames, cap.cap * sizeof *nf);
            memset(out, 0, sizeof *out);
            return st;
        }
        if (!out->nframes && out->frames) gf_free(out->frames, cap.cap * sizeof *nf);
        out->frames = nf;
    }
    out->n_initial = start->n;
    out->cfg = *cfg;
    if (st != GF_OK) gf_series_free(out);
    return st;
}

/// a / b limited to [1 / GF_REF_MAXSTEP, GF_REF_MAXSTEP]; 1 when either is
/// not a positive number, or when they agree within twice their combined
/// uncertainty (noise is no reason to move a parameter).
static double gf_ref_ratio(gf_dem_value a, gf_dem_value b)
{
    double r = a.value / b.value;
    if (!isfinite(r) || !(a.value > 0) || !(b.value > 0)) return 1.0;
    double ea = isfinite(a.err) ? a.err / a.value : 0.0, eb = isfinite(b.err) ? b.err / b.value : 0.0;
    if (fabs(r - 1.0) <= 2.0 * hypot(ea, eb)) return 1.0;
    return fmin(GF_REF_MAXSTEP, fmax(1.0 / GF_REF_MAXSTEP, r));
}

void gf_dem_var_lines_fit(const gf_dem_flowstats *d, const gf_dem_flowstats *s, double vtol, gf_dem_var_lines *l)
{
    memset(l, 0, sizeof *l);
    double w[GF_DEM_FS_MAXZ] = {0}, sw = 0.0, swz = 0.0;
    size_t nz = d->nz < s->nz ? d->nz : s->nz;
    for (size_t z = 0; z < nz; z++) {
        double a = d->var[z].value, b = s->var[z].value;
        if (!gf_dem_flowstats_measured(d->var[z], vtol) || !(b > 0) || !isfinite(b)) continue;
        double e = isfinite(d->var[z].err) ? fmax(d->var[z].err, 0.01 * a) : 0.05 * a;
        w[z] = 1.0 / (e * e);
        sw += w[z];
        swz += w[z] * d->z[z];
        l->n++;
    }
    if (l->n == 0) return;
    l->zm = swz / sw;
    double sxx = 0.0;
    for (size_t z = 0; z < nz; z++) sxx += w[z] * (d->z[z] - l->zm) * (d->z[z] - l->zm);
    if (l->n < 2 || !(sxx > 1e-12 * sw)) {
        l->n = l->n < 2 ? l->n : 1; // all at one height: no line
        return;
    }
    const gf_dem_flowstats *run[2] = {d, s};
    for (int r = 0; r < 2; r++) {
        double sl = 0.0, lv = 0.0, vsl = 0.0, vlv = 0.0;
        for (size_t z = 0; z < nz; z++) {
            if (w[z] == 0.0) continue;
            double g = w[z] * (d->z[z] - l->zm) / sxx, c = w[z] / sw;
            double y = run[r]->var[z].value, e = isfinite(run[r]->var[z].err) ? run[r]->var[z].err : 0.0;
            sl += g * y;
            lv += c * y;
            vsl += g * g * e * e;
            vlv += c * c * e * e;
        }
        l->slope[r] = (gf_dem_value){sl, sqrt(vsl)};
        l->level[r] = (gf_dem_value){lv, sqrt(vlv)};
    }
}

/// res->unreached: which targets the kept run missed and why (empty when it
/// met them all).
static void gf_ref_explain(gf_dem_refine_result *res, const gf_ref_targets *t, const bool col[3], double scale,
                           double r_s, double ftol, double vtol, int max_iter)
{
    char *o = res->unreached;
    size_t cap = sizeof res->unreached, n = 0;
    o[0] = '\0';
#define GF_REF_SAY(...)                                                                  \
    do {                                                                                 \
        if (n < cap) n += (size_t)snprintf(o + n, cap - n, __VA_ARGS__);               \
    } while (0)
    const gf_dem_flowstats *d = &res->dem, *s = &res->last;
    double dq = (s->flow.value - d->flow.value) / d->flow.value;
    if (!(fabs(dq) <= ftol)) {
        if (!col[GF_REF_LAMBDA])
            GF_REF_SAY("flow rate: no outflow to fit in the spot run. ");
        else
            GF_REF_SAY("flow rate %+.1f%%: %s. ", 100.0 * dq,
                       scale < 1.0 ? "the last step was cut to a factor 1.5; more runs would go on"
                                   : "the model's step did not get there in the runs allowed");
    }
    char hs[160] = "";
    size_t nh = 0, off = 0;
    for (size_t z = 0; z < d->nz && z < s->nz; z++) {
        if (!gf_dem_flowstats_measured(d->var[z], vtol)) continue;
        double e = (s->var[z].value - d->var[z].value) / d->var[z].value;
        if (fabs(e) <= vtol) continue;
        nh++;
        if (off >= sizeof hs) continue;
        if (isfinite(e))
            off += (size_t)snprintf(hs + off, sizeof hs - off, "%s%.3g (%+.0f%%)", nh > 1 ? ", " : "", d->z[z], 100.0 * e);
        else // the spot run had no steady frames there
            off += (size_t)snprintf(hs + off, sizeof hs - off, "%s%.3g (not steady)", nh > 1 ? ", " : "", d->z[z]);
    }
    if (nh > 0) {
        bool line_ok = true;
        for (int k = GF_REF_SLOPE; k <= GF_REF_LEVEL; k++)
            if (t->ok[k] && fabs(t->dem[k] - t->spot[k]) > 2.0 * t->sig[k]) line_ok = false;
        GF_REF_SAY("Var at z = %s: ", hs);
        if (line_ok && t->ok[GF_REF_SLOPE])
            GF_REF_SAY("the line through the heights matches (slope and level within twice their noise), the "
                       "heights about it do not: Var(z) is not straight the same way in both, which lambda, "
                       "step_xy and r_s (they set the line) cannot change. ");
        else if (!t->ok[GF_REF_SLOPE])
            GF_REF_SAY("fewer than two heights measured well enough to fit a slope: only one factor on the widths. ");
        else if (col[GF_REF_RADIUS] && r_s <= GF_REF_MIN_RS + 1e-12)
            GF_REF_SAY("spot.radius is at its floor of 1 d and the level is still too %s. ",
                       t->spot[GF_REF_LEVEL] > t->dem[GF_REF_LEVEL] ? "high" : "low");
        else if (!col[GF_REF_RADIUS])
            GF_REF_SAY("spot.radius is fixed by the DEM's correlation length, so step_xy alone sets slope and level. ");
        else
            GF_REF_SAY("%d runs were not enough (each step is limited to a factor 1.5). ", max_iter);
    }
    if (n > 0 && o[n - 1] == ' ') o[n - 1] = '\0';
#undef GF_REF_SAY
}

gf_dem_refine_opts gf_dem_refine_opts_default(void) { return (gf_dem_refine_opts){.max_iter = 0}; }

gf_status gf_dem_refine(const gf_series *dem, const gf_analysis_opts *o, gf_config *cfg, const gf_dem_refine_opts *ro,
                        gf_dem_refine_result *res)
{
    memset(res, 0, sizeof *res);
    gf_dem_refine_opts def = gf_dem_refine_opts_default();
    if (!ro) ro = &def;
    int max_iter = ro->max_iter > 0 ? ro->max_iter : 6;
    double ftol = ro->flow_tol > 0 ? ro->flow_tol : GF_DEM_FLOW_TOL;
    double vtol = ro->var_tol > 0 ? ro->var_tol : GF_DEM_VAR_TOL;
    if (dem->nframes < 3) return gf_error_set(GF_ERR_PARAM, "refine: the DEM run has %zu snapshots", dem->nframes);
    gf_status st = gf_dem_flowstats_measure(dem, o, true, &res->dem);
    if (st != GF_OK) return st;
    if (!(res->dem.flow.value > 0))
        return gf_error_set(GF_ERR_PARAM, "refine: the DEM run has no outflow in its window %g..%g tau",
                            res->dem.t0, res->dem.t1);
    gf_config cur = *cfg, best = *cfg;
    gf_ref_score best_score = {.worst = INFINITY, .unseen = INT_MAX};
    gf_ref_model model;
    gf_ref_targets prev_t = {0}, best_t = {0};
    double prev_p[3] = {0}, best_cov[3][3] = {{0}}, best_scale = 1.0;
    bool best_col[3] = {false, false, false};
    for (int it = 1; it <= max_iter; it++) {
        if (ro->stop && *ro->stop) return gf_error_set(GF_ERR_INTERRUPTED, "refine: interrupted");
        gf_series spot;
        const gf_packing *start = ro->start ? ro->start : &dem->frames[0].pk;
        st = gf_ref_run(dem, start, &cur, res->dem.t1, ro->stop, &spot);
        if (st == GF_ERR_INTERRUPTED) return gf_error_set(st, "refine: interrupted in spot run %d", it);
        if (st != GF_OK) return st;
        gf_dem_flowstats fs;
        st = gf_dem_flowstats_measure(&spot, o, it == 1, &fs);
        gf_series_free(&spot);
        if (st != GF_OK) return st;
        res->runs = it;
        if (it == 1) res->first = fs;
        gf_ref_score score = gf_ref_score_of(&res->dem, &fs, ftol, vtol);
        bool match = gf_ref_score_matched(score);
        if (ro->progress) ro->progress(ro->ctx, it, max_iter, &cur, &res->dem, &fs, match);
        // The targets and what this run says of the model (issue 27 item 3).
        gf_ref_targets t;
        gf_ref_targets_make(&res->dem, &fs, vtol, &t);
        gf_spot_params sp;
        gf_config_spot_params(&cur, &sp);
        const double p[3] = {log(sp.insertion_rate / sp.w), log(sp.step_xy), sp.radius};
        if (it == 1) {
            gf_ref_model_init(&model, sp.radius, t.ok[GF_REF_SLOPE] ? exp(t.spot[GF_REF_SLOPE]) : 0.0,
                              t.ok[GF_REF_LEVEL] ? exp(t.spot[GF_REF_LEVEL]) : 0.0);
        } else {
            double dp[3], dy[3], sig[3];
            bool ok[3];
            for (int k = 0; k < 3; k++) {
                dp[k] = p[k] - prev_p[k];
                dy[k] = t.spot[k] - prev_t.spot[k];
                ok[k] = t.ok[k] && prev_t.ok[k];
                sig[k] = t.sig[k];
            }
            gf_ref_model_update(&model, dp, dy, sig, ok, sp.radius);
        }
        prev_t = t;
        memcpy(prev_p, p, sizeof prev_p);
        // The next parameters: r_s from the correlation length when the
        // DEM's region can hold it (first run only), else free; lambda / w,
        // step_xy and r_s by the joint step; then w and mu by their own
        // relations.
        gf_config next = cur;
        bool beta_ok = res->dem.beta.value >= GF_DEM_BETA_MIN && res->dem.beta.value <= 0.5 * o->corr_size;
        double fr = it == 1 && beta_ok ? gf_ref_ratio(res->dem.beta, fs.beta) : 1.0;
        double r[3], dp[3], cov[3][3];
        bool row[3], col[3] = {t.ok[GF_REF_FLOW], t.ok[GF_REF_SLOPE] || t.ok[GF_REF_LEVEL],
                               !beta_ok && t.ok[GF_REF_SLOPE] && t.ok[GF_REF_LEVEL]};
        double drs = sp.radius * (fr - 1.0); // imposed by beta
        for (int k = 0; k < 3; k++) {
            row[k] = t.ok[k];
            r[k] = t.dem[k] - t.spot[k] - model.J[k][GF_REF_RADIUS] * drs;
            // The widths follow only a difference beyond their noise; the
            // flow, the target, always.
            if (k != GF_REF_FLOW && fabs(t.dem[k] - t.spot[k]) <= 2.0 * t.sig[k]) r[k] = 0.0;
        }
        gf_ref_step(&model, r, t.sig, row, col, GF_REF_RS_PRIOR * sp.radius, dp, cov);
        double scale = gf_ref_limit(dp, sp.radius, GF_REF_MAXSTEP);
        if (gf_ref_score_better(score, best_score)) {
            best_score = score;
            best = cur;
            res->last = fs;
            best_t = t;
            memcpy(best_cov, cov, sizeof best_cov);
            memcpy(best_col, col, sizeof best_col);
            best_scale = scale;
        }
        if (match) break;
        double rs = fmax(GF_REF_MIN_RS, sp.radius + drs + dp[GF_REF_RADIUS]);
        double dx = sp.step_xy * exp(dp[GF_REF_STEP]);
        // w and mu by their relations, but only from a run that already flows
        // as the DEM does (mu: the drop dN ~ Q / mu) and whose widths grow as
        // the DEM's (w: b_p = b_s / w, b_s ~ step_xy^2): compared at another
        // flow or step, the particles' diffusion and the drop move for those
        // reasons too, and w and mu ran off (measured: w 399 -> 177 on a
        // reference made with w = 399, issue 27).
        bool flow_ok = fabs(fs.flow.value - res->dem.flow.value) <= ftol * res->dem.flow.value;
        bool growth_ok = !t.ok[GF_REF_SLOPE] || fabs(t.dem[GF_REF_SLOPE] - t.spot[GF_REF_SLOPE]) <=
                                                    fmax(2.0 * t.sig[GF_REF_SLOPE], log(1.0 + vtol));
        double w = flow_ok && growth_ok ? sp.w * gf_ref_ratio(fs.bp, res->dem.bp) : sp.w;
        double mu = flow_ok ? sp.move_rate * gf_ref_ratio(fs.drop, res->dem.drop) : sp.move_rate;
        // The insertion margin and r_e go back to auto: they follow the radius.
        gf_config_set_spot_fit(&next, rs, w, w * exp(p[GF_REF_LAMBDA] + dp[GF_REF_LAMBDA]), mu, dx);
        if ((st = gf_config_validate(&next)) != GF_OK) return st;
        cur = next;
    }
    // The kept parameters with their standard errors: the noise of the kept
    // run's targets carried through the model (cov = (J^T W J)^-1).
    gf_spot_params bp;
    gf_config_spot_params(&best, &bp);
    res->insertion_rate = (gf_dem_value){bp.insertion_rate, best_col[GF_REF_LAMBDA] ? bp.insertion_rate * sqrt(best_cov[0][0]) : NAN};
    res->step_xy = (gf_dem_value){bp.step_xy, best_col[GF_REF_STEP] ? bp.step_xy * sqrt(best_cov[1][1]) : NAN};
    res->radius = (gf_dem_value){bp.radius, best_col[GF_REF_RADIUS] ? sqrt(best_cov[2][2]) : NAN};
    gf_ref_explain(res, &best_t, best_col, best_scale, bp.radius, ftol, vtol, max_iter);
    res->matched = gf_ref_score_matched(best_score);
    *cfg = best;
    return GF_OK;
}

// One "name = value +- err" (or "(held)" without an error).
static void gf_ref_print_value(FILE *out, const char *name, gf_dem_value v, const char *sep)
{
    if (isfinite(v.err))
        fprintf(out, "%s = %.4g +- %.2g%s", name, v.value, v.err, sep);
    else
        fprintf(out, "%s = %.4g (held)%s", name, v.value, sep);
}

void gf_dem_refine_print(const gf_dem_refine_result *res, FILE *out)
{
    fprintf(out, "fitted together (flow rate, Var(z) slope and level): ");
    gf_ref_print_value(out, "spot.insertion_rate", res->insertion_rate, ", ");
    gf_ref_print_value(out, "spot.step_xy", res->step_xy, ", ");
    gf_ref_print_value(out, "spot.radius", res->radius, "\n");
    if (res->unreached[0]) fprintf(out, "not reached: %s\n", res->unreached);
}
