// SPDX-License-Identifier: MIT
// Closed-loop calibration: the thesis' relations (Sec. 3.3) give a first
// guess of the five spot parameters; short spot runs from the DEM's own first
// frame then adjust them until the spot model flows like the DEM (flow rate,
// widths of the v_z(x) profiles). Each update follows the relation that ties
// a parameter to what it controls:
//   Q = lambda p / w              -> lambda *= Q_dem / Q_spot (and follows w, r_s^3)
//   d Var / dz = 2 b_s ~ dx^2     -> step_xy *= sqrt(slope_dem / slope_spot), and r_s
//                                    moves the level (lines fitted over the heights;
//                                    r_s only when beta left it free)
//   b_p = b_s / w                 -> w *= b_p,spot / b_p,dem
//   dN = Q h / (mu dz)            -> mu *= dN_spot / dN_dem
//   beta = 0.72 r_s               -> r_s *= beta_dem / beta_spot (first run only)
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

/// How far a spot run is from the targets: the largest of |dQ| / (Q tol_Q)
/// and |dVar| / (Var tol_V) over the heights (below 1: matched).
static double gf_ref_score(const gf_dem_flowstats *d, const gf_dem_flowstats *s, double ftol, double vtol)
{
    double score = fabs(s->flow.value - d->flow.value) / (fabs(d->flow.value) * ftol);
    if (!isfinite(score)) return INFINITY;
    for (size_t z = 0; z < d->nz && z < s->nz; z++) {
        // A height the spot run never had steady (no Var) counts as unmatched.
        if (!gf_dem_flowstats_measured(d->var[z], vtol)) continue;
        double e = fabs(s->var[z].value - d->var[z].value) / (fabs(d->var[z].value) * vtol);
        score = fmax(score, isfinite(e) ? e : INFINITY);
    }
    return score;
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

/// Var_dem / Var_spot over the heights the DEM measured precisely enough
/// (gf_dem_flowstats_measured): the geometric mean, weighted by 1 / rel. err^2.
static double gf_ref_var_ratio(const gf_dem_flowstats *d, const gf_dem_flowstats *s, double vtol, double maxf)
{
    double sum = 0.0, wsum = 0.0;
    for (size_t z = 0; z < d->nz && z < s->nz; z++) {
        double a = d->var[z].value, b = s->var[z].value;
        if (!gf_dem_flowstats_measured(d->var[z], vtol) || !(b > 0) || !isfinite(b)) continue;
        double e = isfinite(d->var[z].err) ? fmax(d->var[z].err / a, 0.01) : 0.05;
        sum += log(a / b) / (e * e);
        wsum += 1.0 / (e * e);
    }
    double r = wsum > 0 ? exp(sum / wsum) : 1.0;
    return fmin(maxf, fmax(1.0 / maxf, r));
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

void gf_dem_refine_width(const gf_dem_flowstats *d, const gf_dem_flowstats *s, double vtol, bool rs_free,
                         double maxf, double *step_xy, double *r_s)
{
    gf_dem_var_lines l;
    gf_dem_var_lines_fit(d, s, vtol, &l);
    double a_d = l.slope[0].value, a_s = l.slope[1].value;
    // One knob when it is enough: the step alone scales every Var by k1;
    // the level moves r_s only when no such scale brings every measured
    // height within vtol (r_s and step_xy trade off over a short range of
    // heights, so r_s stays at the thesis' value unless it must move).
    double k1 = gf_ref_var_ratio(d, s, vtol, INFINITY); // unlimited: would it fit?
    bool one_knob = true;
    for (size_t z = 0; z < d->nz && z < s->nz; z++) {
        if (!gf_dem_flowstats_measured(d->var[z], vtol) || !(s->var[z].value > 0)) continue;
        if (fabs(k1 * s->var[z].value - d->var[z].value) > vtol * d->var[z].value) one_knob = false;
    }
    // With r_s fixed (by the correlation length), the slope alone would
    // leave the level wrong: the one factor is then the best dx can do.
    if (one_knob || !rs_free || l.n < 2 || !(a_d > 0) || !(a_s > 0)) {
        *step_xy *= sqrt(fmin(maxf, fmax(1.0 / maxf, k1)));
        return;
    }
    // The growth rate: b_s ~ dx^2.
    double ka = fmin(maxf * maxf, fmax(1.0 / (maxf * maxf), a_d / a_s));
    *step_xy *= sqrt(ka);
    // The level at zm, the spot's predicted after the step change: its
    // profiles widen in proportion (measured: the spot's Var(z) lines pass
    // close to the origin, the birth depth and the ball hardly show).
    double a_new = ka * a_s, m_new = ka * l.level[1].value;
    double dm = l.level[0].value - m_new;
    double em = hypot(l.level[0].err, l.level[1].err);
    if (!(fabs(dm) > 2.0 * em) || !isfinite(dm)) return;
    double r = *r_s + dm / (a_new + 0.4 * *r_s);
    r = fmin(*r_s * maxf, fmax(*r_s / maxf, r));
    *r_s = fmax(GF_REF_MIN_RS, r);
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
    double best_score = INFINITY;
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
        double score = gf_ref_score(&res->dem, &fs, ftol, vtol);
        bool match = score <= 1.0;
        if (ro->progress) ro->progress(ro->ctx, it, max_iter, &cur, &res->dem, &fs, match);
        if (score < best_score) {
            best_score = score;
            best = cur;
            res->last = fs;
        }
        if (match) break;
        // The updates (the relations in the header comment).
        gf_config next = cur;
        // r_s only from a correlation length the DEM's region can hold.
        bool beta_ok = res->dem.beta.value >= GF_DEM_BETA_MIN && res->dem.beta.value <= 0.5 * o->corr_size;
        double fr = it == 1 && beta_ok ? gf_ref_ratio(res->dem.beta, fs.beta) : 1.0;
        // The widths: step_xy for their growth with height, and r_s for
        // their level when the correlation length left r_s free.
        gf_spot_params sp;
        gf_config_spot_params(&cur, &sp);
        double rs = sp.radius, dx = sp.step_xy;
        gf_dem_refine_width(&res->dem, &fs, vtol, !beta_ok, GF_REF_MAXSTEP, &dx, &rs);
        if (!beta_ok) fr = rs / sp.radius;
        double fw = gf_ref_ratio(fs.bp, res->dem.bp);
        gf_dem_value qd = res->dem.flow, qs = fs.flow;
        qd.err = qs.err = 0.0; // the flow is the target: always follow it
        double fq = gf_ref_ratio(qd, qs);
        // The insertion margin and r_e go back to auto: they follow the radius.
        gf_config_set_spot_fit(&next, sp.radius * fr, sp.w * fw, sp.insertion_rate * fq * fw / (fr * fr * fr),
                               sp.move_rate * gf_ref_ratio(fs.drop, res->dem.drop), dx);
        if ((st = gf_config_validate(&next)) != GF_OK) return st;
        cur = next;
    }
    res->matched = best_score <= 1.0;
    *cfg = best;
    return GF_OK;
}
