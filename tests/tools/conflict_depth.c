// conflict_depth: how many spot moves of one fixed step could run at once
// (issue 15 item 2, a measurement; not part of the engine).
//
// Builds the papers' silo (or the 10x silo of `granflow bench`: --large),
// drains it with the spatial fixed step for --warm tau, then takes the spots
// of the state (one step moves each of them once) and schedules them exactly:
// a random order of the spots; two spots conflict when their reach balls
// overlap (centres closer than 2 reach); level(k) = 1 + the largest level of
// the earlier spots it conflicts with. The number of levels is the step's
// dependency depth, spots / levels the parallelism an exact conflict-graph
// schedule would give (unit work per move). Printed for the engine's reach
// (gf_par_reach's formula, parallel.c) and for the reaches given with --reach.
// Also a greedy colouring in the same order (colours(): spots / colours is
// what a schedule free to reorder the step could run at once).
//
//   conflict_depth [--large] [--warm TAU] [--threads N] [--orders K] [--reach R]...
#include "spot/sim_internal.h"

#include "core/limits.h"

#include <granflow/granflow.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_REACH 8

// splitmix64: the tool's own random order (the engine's stream is untouched).
static uint64_t mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// Levels of an exact schedule of the n spots (x, y, z) in the order ord.
static int depth(const double *x, const double *y, const double *z, const size_t *ord, size_t n, double reach,
                 int *level)
{
    double lim2 = 4.0 * reach * reach;
    int top = 0;
    for (size_t k = 0; k < n; k++) {
        size_t a = ord[k];
        int lv = 0;
        for (size_t j = 0; j < k; j++) {
            size_t b = ord[j];
            double dx = x[a] - x[b], dy = y[a] - y[b], dz = z[a] - z[b];
            if (level[j] > lv && dx * dx + dy * dy + dz * dz < lim2) lv = level[j];
        }
        level[k] = lv + 1;
        if (level[k] > top) top = level[k];
    }
    return top;
}

// Colours of a greedy colouring in the same order: colour(k) = the smallest
// colour no earlier linked spot has. Spots of one colour never conflict, so a
// schedule free to choose its order runs the colours one after another.
static int colours(const double *x, const double *y, const double *z, const size_t *ord, size_t n, double reach,
                   int *col, unsigned char *used)
{
    double lim2 = 4.0 * reach * reach;
    int top = 0;
    for (size_t k = 0; k < n; k++) {
        size_t a = ord[k];
        memset(used, 0, (size_t)top + 1);
        for (size_t j = 0; j < k; j++) {
            size_t b = ord[j];
            double dx = x[a] - x[b], dy = y[a] - y[b], dz = z[a] - z[b];
            if (dx * dx + dy * dy + dz * dz < lim2) used[col[j]] = 1;
        }
        int c = 0;
        while (used[c]) c++;
        col[k] = c;
        if (c + 1 > top) top = c + 1;
    }
    return top;
}

int main(int argc, char **argv)
{
    int large = 0, threads = 2, orders = 3, nreach = 0;
    double warm = 20.0, reach[MAX_REACH];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--large")) large = 1;
        else if (!strcmp(argv[i], "--warm") && i + 1 < argc) warm = atof(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--orders") && i + 1 < argc) orders = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reach") && i + 1 < argc && nreach < MAX_REACH - 1) reach[++nreach] = atof(argv[++i]);
        else {
            fprintf(stderr, "usage: conflict_depth [--large] [--warm TAU] [--threads N] [--orders K] [--reach R]...\n");
            return 2;
        }
    }
    gf_config cfg = gf_config_default();
    cfg.run_mode = GF_MODE_FIXED;
    cfg.run_order = GF_ORDER_SPATIAL;
    cfg.run_checkpoint_interval = 0;
    if (large) {
        double f = sqrt(10.0);
        cfg.container_width *= f;
        cfg.container_depth *= f;
        cfg.packing_particles *= 10;
    }
    gf_sim *sim = NULL;
    gf_status st = gf_config_validate(&cfg);
    if (st == GF_OK) st = gf_sim_create_from_config(&cfg, NULL, &sim);
    if (st != GF_OK) {
        fprintf(stderr, "conflict_depth: cannot build the silo (%d)\n", (int)st);
        return 1;
    }
    gf_sim_set_threads(sim, threads);
    if ((st = gf_sim_run(sim, warm, NULL)) != GF_OK) {
        fprintf(stderr, "conflict_depth: run failed (%d)\n", (int)st);
        gf_sim_destroy(sim);
        return 1;
    }
    // The engine's reach (parallel.c, gf_par_reach) and its parts.
    const gf_config *c = &sim->cfg;
    double step = sqrt(2.0 * c->spot_step_xy * c->spot_step_xy + c->spot_step_z * c->spot_step_z);
    double h = fmax(sim->hmax, GF_SKIN);
    double list = h + GF_SKIN_SLACK + sqrt(3.0) * (2.0 * sim->rmax + 3.0 * h + GF_SKIN_SLACK);
    reach[0] = step + fmax(sim->re + list, sqrt(3.0) * sim->rs) + 0.5;
    printf("silo: %zu particles, t = %.2f tau, %zu spots; reach parts: step %.3f, r_e %.3f, list box %.3f "
           "(h %.3f, r_max %.3f), sqrt3 r_s %.3f, margin 0.5\n",
           gf_sim_particle_count(sim), sim->t, sim->ns, step, sim->re, list, h, sim->rmax, sqrt(3.0) * sim->rs);

    size_t n = sim->ns;
    size_t *ord = malloc((n ? n : 1) * sizeof *ord);
    int *level = malloc((n ? n : 1) * sizeof *level);
    unsigned char *used = malloc(n + 2);
    if (!ord || !level || !used) return 1;
    uint64_t seed = 12345;
    for (int r = 0; r <= nreach; r++) {
        double sum = 0, lo = 1e300, hi = 0, csum = 0;
        for (int o = 0; o < orders; o++) {
            for (size_t k = 0; k < n; k++) ord[k] = k;
            for (size_t k = n; k > 1; k--) {
                size_t j = (size_t)(mix(&seed) % k), t = ord[k - 1];
                ord[k - 1] = ord[j];
                ord[j] = t;
            }
            int lv = depth(sim->sx, sim->sy, sim->sz, ord, n, reach[r], level);
            double par = lv ? (double)n / lv : 0;
            sum += par;
            lo = fmin(lo, par);
            hi = fmax(hi, par);
            int nc = colours(sim->sx, sim->sy, sim->sz, ord, n, reach[r], level, used);
            csum += nc ? (double)n / nc : 0;
            printf("reach %.3f d: order %d: %d levels, %d greedy colours\n", reach[r], o, lv, nc);
        }
        printf("reach %.3f d%s: spots %zu, parallelism spots/levels %.1f (min %.1f, max %.1f over %d orders), "
               "spots/colours %.1f\n",
               reach[r], r == 0 ? " (engine)" : "", n, sum / orders, lo, hi, orders, csum / orders);
    }
    free(ord);
    free(level);
    free(used);
    gf_sim_destroy(sim);
    return 0;
}
