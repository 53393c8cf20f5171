// SPDX-License-Identifier: MIT
// The benchmark's report: one JSON object on a line (core/json), or text.
#include <stdio.h>

#include "core/json.h"
#include "granflow/bench.h"

static double gf_bench_ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

static double gf_bench_busy(const gf_par_profile *f)
{
    return f->colour_phases ? (double)f->blocks_run / (double)f->colour_phases : 0.0;
}

// The spatial step's decomposition and projected speedups as members named
// prefix + name (prefix "" or "large_"): work over the sum of each colour
// phase's makespan on T threads, the blocks' times measured on one thread.
static void gf_bench_blocks_json(gf_json *j, const char *prefix, const gf_par_profile *f)
{
    if (f->blocks == 0) return;
    char key[96];
#define GF_KEY(name) (snprintf(key, sizeof key, "%s%s", prefix, name), key)
    gf_json_uint(j, GF_KEY("blocks"), f->blocks);
    gf_json_array_begin(j, GF_KEY("blocks_along_xyz"));
    for (int k = 0; k < 3; k++) gf_json_int(j, NULL, f->blocks_along[k]);
    gf_json_end(j);
    gf_json_int(j, GF_KEY("colours"), f->colours);
    gf_json_int(j, GF_KEY("phases"), f->phases);
    gf_json_fixed(j, GF_KEY("blocks_per_colour"), (double)f->blocks / f->colours, 2);
    gf_json_fixed(j, GF_KEY("busy_blocks_per_colour_phase"), gf_bench_busy(f), 2);
    gf_json_fixed(j, GF_KEY("work_over_span"), gf_bench_ratio(f->work_seconds, f->span_seconds), 2);
    if (f->domains > 0) { // the domain engine
        gf_json_uint(j, GF_KEY("domains"), f->domains);
        gf_json_int(j, GF_KEY("sectors"), f->colours);
        gf_json_general(j, GF_KEY("parallel_window_tau"), f->window, 6);
        gf_json_fixed(j, GF_KEY("barriers_per_tau"), gf_bench_ratio((double)f->barriers, f->profiled_tau), 1);
        gf_json_fixed(j, GF_KEY("exchange_bytes_per_phase_per_domain"),
                      gf_bench_ratio(f->exchange_bytes, (double)f->blocks_run), 0);
        gf_json_fixed(j, GF_KEY("exchange_messages_per_phase_per_domain"),
                      gf_bench_ratio((double)f->exchange_messages, (double)f->blocks_run), 1);
        // Where the work lies up the container: each layer of sectors' share.
        int nl = f->blocks_along[2] < GF_PAR_LAYERS ? f->blocks_along[2] : GF_PAR_LAYERS;
        gf_json_array_begin(j, GF_KEY("work_fraction_along_z"));
        for (int k = 0; k < nl; k++) gf_json_fixed(j, NULL, gf_bench_ratio(f->layer_seconds[k], f->work_seconds), 4);
        gf_json_end(j);
    }
    if (f->serial_seconds > 0) { // the sweep engine: its one-thread bookkeeping, in every makespan
        gf_json_general(j, GF_KEY("parallel_window_tau"), f->window, 6);
        gf_json_fixed(j, GF_KEY("barriers_per_tau"), gf_bench_ratio((double)f->barriers, f->profiled_tau), 1);
        gf_json_fixed(j, GF_KEY("serial_fraction"), gf_bench_ratio(f->serial_seconds, f->work_seconds), 4);
        gf_json_fixed(j, GF_KEY("walk_fraction"), gf_bench_ratio(f->part_seconds[0], f->work_seconds), 4);
        gf_json_fixed(j, GF_KEY("gather_fraction"), gf_bench_ratio(f->part_seconds[1], f->work_seconds), 4);
        gf_json_fixed(j, GF_KEY("sweeps_fraction"), gf_bench_ratio(f->part_seconds[2], f->work_seconds), 4);
        gf_json_fixed(j, GF_KEY("lists_fraction"), gf_bench_ratio(f->part_seconds[3], f->work_seconds), 4);
    }
    for (int i = 0; i < GF_PAR_NPROJ; i++) {
        char name[48];
        snprintf(name, sizeof name, "projected_speedup_%d", f->proj_threads[i]);
        gf_json_fixed(j, GF_KEY(name), gf_bench_ratio(f->work_seconds, f->makespan_seconds[i]), 2);
    }
#undef GF_KEY
}

static void gf_bench_json(FILE *out, const gf_bench_report *r)
{
    gf_json j = gf_json_start(out, false);
    gf_json_object_begin(&j, NULL);
    const gf_bench_lga *l = &r->lga;
    if (r->lga_only) {
        gf_json_fixed(&j, "lga_site_updates_per_second", l->site_updates_per_second, 0);
        gf_json_int(&j, "lga_sites", l->sites);
        gf_json_int(&j, "lga_particles", l->particles);
        gf_json_int(&j, "lga_iterations", l->iterations);
        gf_json_fixed(&j, "lga_seconds", l->seconds, 3);
        gf_json_end(&j);
        return;
    }
    const gf_bench_spot *s = &r->silo, *g = &r->big;
    gf_json_string(&j, "engine", r->engine);
    gf_json_uint(&j, "particles", s->particles);
    gf_json_int(&j, "threads", s->threads);
    gf_json_general(&j, "warmup_tau", r->warmup, 6);
    gf_json_general(&j, "window_tau", r->window, 6);
    gf_json_fixed(&j, "spot_us", s->spot_us, 4);
    gf_json_fixed(&j, "relax_us", s->relax_us, 4);
    gf_json_fixed(&j, "step_us", r->step_us, 4);
    gf_json_fixed(&j, "steps_per_second", s->sps_all, 1);
    gf_json_fixed(&j, "steps_per_second_1thread", s->sps_one, 1);
    gf_json_fixed(&j, "parallel_efficiency", r->efficiency, 3);
    gf_json_uint(&j, "spots_active", s->spots);
    gf_json_fixed(&j, "flow_rate", s->flow, 2);
    gf_json_fixed(&j, "moves_per_tau", s->moves_per_tau, 0);
    gf_json_fixed(&j, "memory_bytes_per_particle", s->bytes_per_particle, 1);
    gf_json_fixed(&j, "peak_rss_bytes_per_particle", r->peak_rss_bytes / (double)s->particles, 1);
    gf_json_fixed(&j, "peak_rss_bytes", r->peak_rss_bytes, 0);
    gf_json_int(&j, "ranks", s->ranks);
    const int nr = s->ranks < GF_BENCH_RANKS ? s->ranks : GF_BENCH_RANKS;
    gf_json_array_begin(&j, "rank_peak_rss_bytes");
    for (int k = 0; k < nr; k++) gf_json_fixed(&j, NULL, s->rank_peak_rss_bytes[k], 0);
    gf_json_end(&j);
    gf_json_array_begin(&j, "rank_exchange_bytes_per_phase");
    for (int k = 0; k < nr; k++) gf_json_fixed(&j, NULL, s->rank_exchange_bytes_per_phase[k], 0);
    gf_json_end(&j);
    gf_json_array_begin(&j, "rank_region_particles");
    for (int k = 0; k < nr; k++) gf_json_fixed(&j, NULL, s->rank_region_particles[k], 0);
    gf_json_end(&j);
    gf_json_array_begin(&j, "rank_slab_particles");
    for (int k = 0; k < nr; k++) gf_json_fixed(&j, NULL, s->rank_slab_particles[k], 0);
    gf_json_end(&j);
    gf_json_array_begin(&j, "rank_held_particles");
    for (int k = 0; k < nr; k++) gf_json_fixed(&j, NULL, s->rank_held_particles[k], 0);
    gf_json_end(&j);
    gf_json_fixed(&j, "projected_drain_seconds", s->drain_s, 0);
    gf_json_fixed(&j, "pack_seconds", s->pack_s, 2);
    gf_json_fixed(&j, "warmup_seconds", s->warm_s, 2);
    gf_bench_blocks_json(&j, "", &s->prof);
    if (r->large) {
        gf_bench_blocks_json(&j, "large_", &g->prof);
        gf_json_uint(&j, "large_particles", g->particles);
        gf_json_fixed(&j, "large_step_us", g->sps_one > 0 ? 1e6 / g->sps_one : 0, 4);
        gf_json_fixed(&j, "large_steps_per_second", g->sps_all, 1);
        gf_json_fixed(&j, "large_steps_per_second_1thread", g->sps_one, 1);
        gf_json_fixed(&j, "large_memory_bytes_per_particle", g->bytes_per_particle, 1);
        gf_json_fixed(&j, "large_spot_us", g->spot_us, 4);
        gf_json_fixed(&j, "large_relax_us", g->relax_us, 4);
    }
    gf_json_fixed(&j, "lga_site_updates_per_second", l->site_updates_per_second, 0);
    gf_json_int(&j, "lga_sites", l->sites);
    gf_json_int(&j, "lga_iterations", l->iterations);
    gf_json_end(&j);
}

static void gf_bench_blocks_text(FILE *out, const char *what, const gf_par_profile *f)
{
    if (f->blocks == 0) return;
    fprintf(out, "  blocks   %8zu (%d x %d x %d), %d colours x %d phases, %.1f busy per colour phase (%s)\n", f->blocks,
            f->blocks_along[0], f->blocks_along[1], f->blocks_along[2], f->colours, f->phases, gf_bench_busy(f), what);
    fprintf(out, "  projected speedup");
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        fprintf(out, " %.1fx on %d threads%s", gf_bench_ratio(f->work_seconds, f->makespan_seconds[i]),
                f->proj_threads[i], i + 1 < GF_PAR_NPROJ ? "," : "");
    fprintf(out, " (work/span %.1f)\n", gf_bench_ratio(f->work_seconds, f->span_seconds));
    if (f->domains > 0)
        fprintf(out, "  domains  %8zu, %d sectors, window %.3g tau: %.1f barriers per tau, %.0f bytes exchanged per "
                     "phase per domain (modelled)\n",
                f->domains, f->colours, f->window, gf_bench_ratio((double)f->barriers, f->profiled_tau),
                gf_bench_ratio(f->exchange_bytes, (double)f->blocks_run));
}

static void gf_bench_lga_text(FILE *out, const gf_bench_lga *b)
{
    fprintf(out, "  lga     %8.1f M site updates/s (channel, %lld particles on %lld sites, %lld iterations in %.2f s)\n",
            b->site_updates_per_second / 1e6, (long long)b->particles, (long long)b->sites, (long long)b->iterations,
            b->seconds);
}

static void gf_bench_text(FILE *out, const gf_bench_report *r)
{
    if (r->lga_only) {
        fprintf(out, "granflow bench: the lattice-gas automaton only\n");
        gf_bench_lga_text(out, &r->lga);
        return;
    }
    const gf_bench_spot *s = &r->silo, *g = &r->big;
    fprintf(out, "granflow bench: %zu particles, %s engine, steady flow after %.3g tau (%zu spots active)\n", s->particles,
            r->engine, r->warmup, s->spots);
    fprintf(out, "  spot()   %8.3f us per call, one thread   (2009 paper: 7.15 us)\n", s->spot_us);
    fprintf(out, "  relax()  %8.3f us per call, one thread   (2009 paper: 115 us)\n", s->relax_us);
    fprintf(out, "  step     %8.3f us per spot move on one thread: %.0f steps/s\n", r->step_us, s->sps_one);
    fprintf(out, "  threads  %8d: %.0f steps/s, parallel efficiency %.2f\n", s->threads, s->sps_all, r->efficiency);
    fprintf(out, "  flow     %8.2f particles per tau; %.0f spot moves per tau\n", s->flow, s->moves_per_tau);
    fprintf(out, "  drainage %8.1f min projected for the %zu particles left (all threads)\n", s->drain_s / 60.0,
            s->remaining);
    fprintf(out, "  memory   %8.1f bytes per particle allocated by the engine; peak RSS %.1f bytes per particle\n",
            s->bytes_per_particle, r->peak_rss_bytes / (double)s->particles);
    if (s->ranks > 1) {
        fprintf(out, "  ranks    %8d: peak RSS (MB), bytes sent per phase, particles in region / slab / held, rank by rank:",
                s->ranks);
        for (int k = 0; k < s->ranks && k < GF_BENCH_RANKS; k++)
            fprintf(out, " %.1f, %.0f, %.0f / %.0f / %.0f;", s->rank_peak_rss_bytes[k] / 1e6,
                    s->rank_exchange_bytes_per_phase[k], s->rank_region_particles[k], s->rank_slab_particles[k],
                    s->rank_held_particles[k]);
        fprintf(out, "\n");
    }
    gf_bench_blocks_text(out, "papers' silo", &s->prof);
    if (r->large) {
        fprintf(out,
                "  10x silo %8.3f us per step on one thread (%.2f x the papers' silo), %.0f steps/s on %d threads, "
                "%.1f bytes per particle (%zu particles)\n",
                g->sps_one > 0 ? 1e6 / g->sps_one : 0, s->sps_one > 0 && g->sps_one > 0 ? s->sps_one / g->sps_one : 0,
                g->sps_all, g->threads, g->bytes_per_particle, g->particles);
        gf_bench_blocks_text(out, "10x silo", &g->prof);
    }
    fprintf(out, "  packing %.1f s, warm-up %.1f s\n", s->pack_s, s->warm_s);
    gf_bench_lga_text(out, &r->lga);
}

void gf_bench_write(FILE *out, const gf_bench_report *r, bool json)
{
    if (json) gf_bench_json(out, r);
    else gf_bench_text(out, r);
}
