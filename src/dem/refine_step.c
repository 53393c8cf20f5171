// SPDX-License-Identifier: MIT
// The joint step of the closed-loop refinement (issue 27 item 3): the flow
// rate Q, and the slope and level of the line Var(z) through the heights the
// DEM measured, fitted together by three parameters, p = (ln(lambda / w),
// ln step_xy, r_s), on ln Q, ln(d Var / dz) and ln Var(zm). Their model starts from the thesis' relations (Sec. 3.3:
// Q = lambda p_ball / w with p_ball ~ r_s^3; d Var / dz = 2 b_s with b_s ~
// step_xy^2; Var(z) ~ 2 b_s (z + r_s) + r_s^2 / 5) and learns from each run
// (a Broyden update, row by row, only on changes the noise cannot explain);
// each step is the weighted least-squares solution of J dp = target - spot
// over the targets measured well enough, with the noise left out (a
// difference within twice its uncertainty is no reason to move).
#include <math.h>
#include <string.h>

#include "dem/dem_internal.h"

void gf_ref_targets_make(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double vtol, gf_ref_targets *t)
{
    memset(t, 0, sizeof *t);
    double qd = dem->flow.value, qs = spot->flow.value;
    if (qd > 0 && qs > 0 && isfinite(qd) && isfinite(qs)) {
        t->dem[GF_REF_FLOW] = log(qd);
        t->spot[GF_REF_FLOW] = log(qs);
        double ed = isfinite(dem->flow.err) ? dem->flow.err / qd : 0.0;
        double es = isfinite(spot->flow.err) ? spot->flow.err / qs : 0.0;
        t->sig[GF_REF_FLOW] = fmax(hypot(ed, es), 1e-3);
        t->ok[GF_REF_FLOW] = true;
    }
    gf_dem_var_lines_fit(dem, spot, vtol, &t->lines);
    const gf_dem_var_lines *l = &t->lines;
    gf_dem_value lv[2] = {l->level[0], l->level[1]};
    if (l->n == 1) // one height measured well enough: the level is Var there
        for (size_t z = 0; z < dem->nz && z < spot->nz; z++)
            if (gf_dem_flowstats_measured(dem->var[z], vtol)) {
                lv[0] = dem->var[z];
                lv[1] = spot->var[z];
            }
    if (l->n >= 1) { // the level: Var at zm, on a log scale
        double a = lv[0].value, b = lv[1].value;
        if (a > 0 && b > 0 && isfinite(a) && isfinite(b)) {
            t->dem[GF_REF_LEVEL] = log(a);
            t->spot[GF_REF_LEVEL] = log(b);
            double ea = isfinite(lv[0].err) ? lv[0].err / a : 0.05;
            double eb = isfinite(lv[1].err) ? lv[1].err / b : 0.0;
            t->sig[GF_REF_LEVEL] = fmax(hypot(ea, eb), 1e-3);
            t->ok[GF_REF_LEVEL] = true;
        }
    }
    if (l->n >= 2) { // the slope, on a log scale (b_s ~ step_xy^2)
        double a = l->slope[0].value, b = l->slope[1].value;
        if (a > 0 && b > 0 && isfinite(a) && isfinite(b)) {
            t->dem[GF_REF_SLOPE] = log(a);
            t->spot[GF_REF_SLOPE] = log(b);
            double ea = isfinite(l->slope[0].err) ? l->slope[0].err / a : 0.1;
            double eb = isfinite(l->slope[1].err) ? l->slope[1].err / b : 0.0;
            t->sig[GF_REF_SLOPE] = fmax(hypot(ea, eb), 1e-3);
            t->ok[GF_REF_SLOPE] = true;
        }
    }
}

// The column of target i's own parameter (flow: lambda, slope: step, level: r_s).
static int gf_ref_own(int i) { return i == GF_REF_FLOW ? GF_REF_LAMBDA : i == GF_REF_SLOPE ? GF_REF_STEP : GF_REF_RADIUS; }

void gf_ref_model_init(gf_ref_model *m, double r_s, double slope, double level)
{
    memset(m, 0, sizeof *m);
    // ln Q = ln(lambda / w) + 3 ln r_s + const
    m->J[GF_REF_FLOW][GF_REF_LAMBDA] = 1.0;
    m->J[GF_REF_FLOW][GF_REF_RADIUS] = 3.0 / r_s;
    // ln(d Var / dz) = 2 ln step_xy + const
    m->J[GF_REF_SLOPE][GF_REF_STEP] = 2.0;
    // ln Var(zm), Var ~ 2 b_s (zm + r_s) + r_s^2 / 5: scales as step_xy^2
    // (the spot's lines pass close to the origin), d Var / d r_s = 2 b_s +
    // 2 r_s / 5.
    m->J[GF_REF_LEVEL][GF_REF_STEP] = 2.0;
    m->J[GF_REF_LEVEL][GF_REF_RADIUS] = level > 0 ? (fmax(slope, 0.0) + 0.4 * r_s) / level : 0.0;
    for (int i = 0; i < 3; i++) m->diag0[i] = m->J[i][gf_ref_own(i)];
}

void gf_ref_model_update(gf_ref_model *m, const double dp[3], const double dy[3], const double sig[3],
                         const bool ok[3], double r_s)
{
    // Parameters compared on one scale: the logs as they are, r_s relative.
    const double scale[3] = {1.0, 1.0, 1.0 / (r_s * r_s)};
    double dd = 0.0;
    for (int j = 0; j < 3; j++) dd += scale[j] * dp[j] * dp[j];
    if (!(dd > 1e-12)) return;
    for (int i = 0; i < 3; i++) {
        if (!ok[i]) continue;
        double pred = 0.0;
        for (int j = 0; j < 3; j++) pred += m->J[i][j] * dp[j];
        // Learn only from what the noise cannot explain: an observed change,
        // or a predicted one that did not come, beyond twice the noise.
        if (!(fmax(fabs(dy[i]), fabs(pred)) > 2.0 * sig[i])) continue;
        double c = (dy[i] - pred) / dd;
        for (int j = 0; j < 3; j++) m->J[i][j] += c * scale[j] * dp[j];
        // Each target keeps following its own parameter, the way the
        // relations say, within a factor 4 of their slope.
        int o = gf_ref_own(i);
        double d0 = m->diag0[i];
        if (d0 > 0) m->J[i][o] = fmin(4.0 * d0, fmax(0.25 * d0, m->J[i][o]));
    }
}

// Solves the n x n system a x = b (Gaussian elimination, partial pivots);
// false when singular. `inv` (may be NULL) gets a's inverse.
static bool gf_ref_solve(int n, double a[3][3], double b[3], double x[3], double inv[3][3])
{
    double m[3][7];
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) m[i][j] = a[i][j];
        m[i][n] = b[i];
        for (int j = 0; j < n; j++) m[i][n + 1 + j] = i == j ? 1.0 : 0.0;
    }
    const int w = 2 * n + 1;
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(m[r][c]) > fabs(m[p][c])) p = r;
        if (!(fabs(m[p][c]) > 1e-300)) return false;
        if (p != c)
            for (int j = 0; j < w; j++) {
                double t = m[p][j];
                m[p][j] = m[c][j];
                m[c][j] = t;
            }
        for (int r = 0; r < n; r++) {
            if (r == c) continue;
            double f = m[r][c] / m[c][c];
            for (int j = c; j < w; j++) m[r][j] -= f * m[c][j];
        }
    }
    for (int i = 0; i < n; i++) {
        x[i] = m[i][n] / m[i][i];
        if (inv)
            for (int j = 0; j < n; j++) inv[i][j] = m[i][n + 1 + j] / m[i][i];
    }
    return true;
}

int gf_ref_step(const gf_ref_model *m, const double r[3], const double sig[3], const bool row[3], const bool col[3],
                double rs_prior, double dp[3], double cov[3][3])
{
    int idx[3], n = 0;
    for (int j = 0; j < 3; j++) {
        dp[j] = 0.0;
        for (int k = 0; k < 3; k++) cov[j][k] = 0.0;
        if (col[j]) idx[n++] = j;
    }
    int rows = 0;
    for (int i = 0; i < 3; i++) rows += row[i];
    if (n == 0 || rows == 0) return 0;
    // Normal equations of the rows weighted by 1 / sig^2.
    double a[3][3] = {{0}}, b[3] = {0}, x[3], inv[3][3];
    for (int i = 0; i < 3; i++) {
        if (!row[i]) continue;
        double wgt = 1.0 / (sig[i] * sig[i]);
        for (int p = 0; p < n; p++) {
            b[p] += wgt * m->J[i][idx[p]] * r[i];
            for (int q = 0; q < n; q++) a[p][q] += wgt * m->J[i][idx[p]] * m->J[i][idx[q]];
        }
    }
    // The covariance is the data's alone (the prior below steers the step,
    // it is no measurement); with fewer rows than free parameters it is
    // unbounded (infinite).
    double ad[3][3], xd[3];
    memcpy(ad, a, sizeof ad);
    bool known = rows >= n && gf_ref_solve(n, ad, b, xd, inv);
    // r_s stays where it is unless the targets ask for it: a move of
    // rs_prior costs as much as one standard error of a target. Without it,
    // a level off while the slope is within its noise (a few heights close
    // together) went wholly to r_s, the flow's r_s^3 chasing it (r_s 2.6 ->
    // 1.1 in 6 runs), where the relations say the step sets the widths.
    if (col[GF_REF_RADIUS] && rs_prior > 0)
        for (int p = 0; p < n; p++)
            if (idx[p] == GF_REF_RADIUS) a[p][p] += 1.0 / (rs_prior * rs_prior);
    double tr = 0.0;
    for (int p = 0; p < n; p++) tr += a[p][p];
    if (rows < n) // a small ridge keeps the parameters no row sees still
        for (int p = 0; p < n; p++) a[p][p] += 1e-3 * tr / n;
    double scratch[3][3];
    if (!gf_ref_solve(n, a, b, x, scratch)) return 0;
    for (int p = 0; p < n; p++) {
        dp[idx[p]] = x[p];
        for (int q = 0; q < n; q++) cov[idx[p]][idx[q]] = known ? inv[p][q] : (p == q ? INFINITY : 0.0);
    }
    return n;
}

gf_ref_score gf_ref_score_of(const gf_dem_flowstats *d, const gf_dem_flowstats *s, double ftol, double vtol)
{
    gf_ref_score r = {fabs(s->flow.value - d->flow.value) / (fabs(d->flow.value) * ftol), 0};
    if (!isfinite(r.worst)) r.worst = INFINITY;
    for (size_t z = 0; z < d->nz; z++) {
        if (!gf_dem_flowstats_measured(d->var[z], vtol)) continue;
        double e = z < s->nz ? fabs(s->var[z].value - d->var[z].value) / (fabs(d->var[z].value) * vtol) : NAN;
        if (isfinite(e))
            r.worst = fmax(r.worst, e);
        else
            r.unseen++;
    }
    return r;
}

bool gf_ref_score_better(gf_ref_score a, gf_ref_score b)
{
    if (a.unseen != b.unseen) return a.unseen < b.unseen;
    return a.worst < b.worst;
}

bool gf_ref_score_matched(gf_ref_score s) { return s.unseen == 0 && s.worst <= 1.0; }

double gf_ref_limit(double dp[3], double r_s, double maxf)
{
    // One factor on the whole step keeps its direction (the parameters trade
    // off): the logs by at most ln maxf, r_s by at most a factor maxf.
    double lim[3] = {log(maxf), log(maxf), r_s * (1.0 - 1.0 / maxf)}, s = 1.0;
    for (int j = 0; j < 3; j++)
        if (fabs(dp[j]) > lim[j]) s = fmin(s, lim[j] / fabs(dp[j]));
    for (int j = 0; j < 3; j++) dp[j] *= s;
    return s;
}
