// SPDX-License-Identifier: MIT
// Internal: the simulation state behind the opaque gf_sim handle, shared by
// the engine files (sim.c lifecycle, drivers.c time drivers, parallel.c spatial
// step, walk.c step kernel, mechanism.c spot()/relax(), particles.c bookkeeping,
// nlist.c, checkpoint.c) and the tests.
#ifndef GF_SPOT_SIM_INTERNAL_H
#define GF_SPOT_SIM_INTERNAL_H

#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/rng.h"
#include "geom/container.h"
#include "geom/grid.h"
#include "spot/slabs.h"
#include "granflow/defs.h"
#include "granflow/sim.h"
#include "spot/sfr.h"
#include "stress/stress.h"

/// Particle positions and radius packed in one 32-byte record: spot and relax
/// touch particles in random order, and one cache line then brings all four.
typedef struct gf_pos {
    double x, y, z, r;
} gf_pos;

/// A particle's neighbour-list reference: where it was when its row was last
/// made, and its skin h. Single precision (half the bytes of a gf_pos): it
/// only decides which pairs are listed and when a row is redone, and every
/// such test reads these stored values, so the rule holds exactly as written.
typedef struct gf_ref {
    float x, y, z, h;
} gf_ref;

/// Where a particle's current pass began (recirculation; cold, read at exits).
typedef struct gf_hist {
    double t_entry; ///< time it entered: 0, or when it was put back on the surface
    double r_entry; ///< its distance from the axis x = y = 0 then
    int32_t pass;   ///< 1 for the initial packing, + 1 at each re-insertion
    int32_t pad_;
} gf_hist;

/// What a worker's moves changed in the shared state, logged for the MPI
/// exchange (par_mpi.c) when its `log` flag is set: particles whose whole
/// record (position, list reference, alive, cell, slot) may differ (exits,
/// list refreshes), particles only moved (their position; a change of cell
/// shows in the cells' records), particles whose neighbour-list row may
/// differ, grid cells whose count or slots may differ, the spots moved and
/// the blocks run. Entries may repeat. Nothing is logged in a build without
/// GF_MPI.
enum { GF_TOUCH_PARTICLE, GF_TOUCH_MOVED, GF_TOUCH_ROW, GF_TOUCH_CELL, GF_TOUCH_SPOT, GF_TOUCH_BLOCK, GF_TOUCH_KINDS };
typedef struct gf_touch {
    uint32_t *v;
    size_t n, cap;
} gf_touch;

/// What one thread needs to run spot steps: scratch for one gather, the
/// random stream and the counters the steps draw on and add to, and, in the
/// parallel step, the exits it found (merged after each phase).
typedef struct gf_work {
    uint32_t *inside;   ///< particles within r_e of the step centre
    uint8_t *in_ball;   ///< per inside entry: 1 if moved this step (within r_s, or by relax)
    double (*disp)[3];  ///< relax displacements of the inside particles
    uint32_t *cross;    ///< particles that went past their skin this step
    gf_pos *ip;         ///< per inside entry: its position (after spot())
    size_t scratch_cap;
    size_t scratch_used; ///< entries of inside[] filled by the last gather

    gf_rng *rng;          ///< the stream walks and relax.method = random draw on
    gf_sim_stats *st;     ///< where the step's counters go
    const double *coltop; ///< per grid column: its top z when the step began (NULL: ask the grid)
    /// The domain engine in one process: per grid column, the highest cell
    /// layer a particle entered during the cycle (-1: none), so that the
    /// column tops are settled from below that (else NULL).
    int32_t *colmax;
    bool defer_exits;     ///< exits go to exits[] below, not into the sim
    bool exit_failed;     ///< exits[] could not grow (out of memory)
    gf_exit *exits;
    uint32_t *exit_slot; ///< per exits[] entry: the particle's index, when it is to be put back (else UINT32_MAX)
    size_t nexit, exit_cap;
    bool timed;      ///< exits take the time t below (the domain engine's moves each have their own)
    double t;        ///< time of the move being made, when timed
    bool log;        ///< log what the moves change into touched[] (MPI ranks)
    /// The domain engine's slabs across MPI ranks (slabs.h), else NULL: a
    /// particle moved into or out of a rank's region is logged whole, with its row.
    const struct gf_slabs *slabs;
    bool log_failed; ///< a log could not grow (out of memory)
    gf_touch touched[GF_TOUCH_KINDS];
} gf_work;

/// Grows a log by half (walk.c); false when out of memory.
bool gf_touch_grow(gf_touch *t);
/// Logs entry v of kind `kind` (GF_TOUCH_*) when the worker logs.
static inline void gf_work_touch(gf_work *w, int kind, uint32_t v)
{
#ifdef GF_MPI
    if (!w->log) return;
    gf_touch *t = &w->touched[kind];
    if (t->n == t->cap && !gf_touch_grow(t)) {
        w->log_failed = true;
        return;
    }
    t->v[t->n++] = v;
#else
    (void)w;
    (void)kind;
    (void)v;
#endif
}

struct gf_sim {
    gf_config cfg;       ///< kept to save and hand to config/ (checkpoints, gf_sim_config); read d
    gf_engine_defs d;    ///< what the engine reads (gf_config_engine_defs of cfg)
    gf_container box;

    // Particles. Entries [0, n) are live or parked (exited, awaiting compaction).
    size_t n, cap;
    gf_pos *p;        ///< hot: position and radius
    gf_ref *p0;       ///< neighbour-list reference position and skin
    int64_t *id;      ///< cold: stable id
    int32_t *layer;   ///< cold: initial-layer tag
    uint8_t *alive;   ///< 1 while in the container
    gf_hist *hist;    ///< cold: where the current pass began, and its number
    size_t n_alive, n_initial;
    double rmax;      ///< largest radius
    // An MPI rank of the domain engine that read only its region of
    // packing.file (window.c, issue 23 item 3): it holds the records of the
    // particles [win_lo, win_hi) (its region, a margin, and what its
    // neighbours send it), the others' pages were never written; loops over
    // the particles outside the phases keep to the window. False once a
    // gather made the state whole (par_mpi_slabs.c) and in one process.
    bool part;
    size_t win_lo, win_hi;
    double rmin_all;  ///< part: the smallest radius of the particles in the container (creation, re-sort)
    double rmax_all;  ///< part: the largest
    bool keep_part;   ///< part: gf_sim_run leaves the state as it is at its end (the bench reads counters only)
    double contact2;  ///< (2 r)^2 when every live particle has radius r, else 0 (derived at every list build)

    gf_grid grid;
    double grid_ztop; ///< top of the grid, fixed at creation (cell order depends on it)

    // Neighbour lists, one fixed-capacity row per particle: row i is
    // nl[i * GF_NL_CAP ...], its count in slot 0, then the neighbours sorted
    // by index, so that sums over overlaps do not depend on when a row was
    // made (exact resume). A row lists exactly the live j with
    // |p0_i - p0_j| < r_i + r_j + h_i + h_j (gf_nlist_listed), so the lists
    // are a function of p0 alone and a resume rebuilds them bit for bit.
    uint32_t *nl;
    unsigned nl_shift;    ///< a row has 1 << nl_shift slots (GF_NL_CAP for equal radii; gf_nlist_slots)
    double hmax;          ///< largest skin (derived at every full build)
    uint64_t nl_built_at; ///< event count at the last full (re-sorting) rebuild

    // Spots (SoA).
    size_t ns, ns_cap;
    double *sx, *sy, *sz;
    uint64_t *sbirth; ///< insertion serial number
    uint32_t *scount; ///< moves since the spot's last relax() (relax.method = counter)
    double *snext;    ///< time of the spot's next move (run.order = domains, sweep; unused by the other engines)
    uint64_t next_birth;
    uint64_t fstep;     ///< fixed mode: steps done (time = fstep / mu)

    // Clock and randomness.
    double t;          ///< time of the last event, tau
    double t_reached;  ///< time up to which the state is known to be current
    double t_pending;  ///< time of the next event, when pending
    bool pending;
    gf_rng rng;
    uint64_t next_snap;  ///< index of the next snapshot
    double next_ckpt;    ///< time of the next periodic checkpoint

    // Exits.
    gf_exit *exits;
    size_t nexit, exit_cap;
    // Recirculation: particles that exited and are to be put back on the
    // surface at the end of the current event or step (recirculate.c).
    uint32_t *reins;
    size_t nreins, reins_cap;

    // The serial engine's worker (event mode, fixed random/newest): draws on
    // rng and counts into st.
    gf_work w0;
    uint32_t *mark;     ///< per particle: 1 + its position in its worker's inside[], 0 if in none
    // The spatial fixed step's state (parallel.c), made on its first step.
    struct gf_par *par;
    // The domain engine's state (domains.c), made on its first cycle.
    struct gf_dom *dom;
    // The sweep engine's state (sweep.c), made on its first window.
    struct gf_sweep *sweep;

    // Derived parameters.
    double rs, rs2, re, re2, alpha, inv_w, ball_frac;
    double spot_ins_r;  ///< radius (circle) or half-width (slit) where spots are born
    double spot_birth_z;
    // The stochastic flow rule (spot.flow_rule = sfr; docs/stress.md): the
    // container's stress field, solved once when the engine is made.
    bool sfr;
    gf_stress_field stress;
    gf_sfr_walk sfr_walk;

    gf_sim_stats st;
    bool timing;
    bool no_relax; ///< skip relax() (tests, and relax.method = none)
    bool use_nlist; ///< neighbour lists kept (not with relax.method = none: nothing reads them)
};

/// Gathers the particles within r_e of c into sim->inside and moves those
/// within r_s by u (SPEC 1.3 spot()). Returns the number moved (the ball's
/// population), or -1 with an error set.
long gf_spot_apply(gf_sim *sim, gf_work *w, const double c[3], const double u[3]);

/// One step of a spot at s: walk, truncation, removal test, spot(), relax()
/// (as relax.method says; *count is the spot's move counter for the counter
/// method). Updates s, or sets *deleted when the spot is to be removed; *ball
/// receives the number of particles it moved.
gf_status gf_spot_step(gf_sim *sim, gf_work *w, double s[3], uint32_t *count, bool *deleted, long *ball);

/// Number of particles within r of c (the biased walk's p_i, Sec. 3).
size_t gf_ball_count(const gf_sim *sim, const double c[3], double r);

/// Relaxes the whole packing at once (relax.method = global, 2009 paper
/// Sec. 5 method 3): every overlapping pair, every wall, displacements summed
/// then applied.
gf_status gf_relax_global(gf_sim *sim);

/// Ends a gather that is not followed by relax(): clears the inside marks
/// and does the bookkeeping of the particles spot() moved (cells, lists).
gf_status gf_spot_unmark(gf_sim *sim, gf_work *w);

/// Relaxes around c the particles gathered by gf_spot_apply (SPEC 1.3 relax()).
gf_status gf_relax_apply(gf_sim *sim, gf_work *w, const double c[3]);

/// Standalone relax(c, r_e) (gathers first): for tests and global relaxation.
gf_status gf_relax_at(gf_sim *sim, gf_work *w, const double c[3]);

/// Rebuilds the neighbour lists. With `reorder`, exited particles are
/// compacted away, the rest sorted by cell, and p0 reset to the positions;
/// without, the order and p0 are kept (resume: the grid must then already
/// hold the live particles), which gives the very lists the run had.
gf_status gf_nlist_build(gf_sim *sim, bool reorder);

/// Sets sim->nl_shift for the radii of the live particles (rows of
/// GF_NL_CAP slots when they are equal). GF_ERR_PARAM beyond GF_NL_CAP_MAX.
gf_status gf_nlist_slots(gf_sim *sim);

/// Particle i has moved past its skin: its p0 becomes its position and its
/// pairs are redone (its row and its old and new neighbours' rows).
gf_status gf_nlist_refresh(gf_sim *sim, uint32_t i);

/// Fills row i alone by the listing rule from the current references (the
/// rows naming i are left as they are): the sweep engine's batched refresh,
/// which rewrites those itself. Writes row i only.
gf_status gf_nlist_find_row(gf_sim *sim, uint32_t i);

/// Takes particle i out of every list (it has exited).
void gf_nlist_drop(gf_sim *sim, uint32_t i);

/// Removes particle i (below the exit plane) if it fell out of the orifice;
/// true when it did.
bool gf_sim_exit_slow(gf_sim *sim, gf_work *w, uint32_t i);

/// Removes particle i if it fell out of the orifice; true when it did.
static inline bool gf_sim_exit_check(gf_sim *sim, gf_work *w, uint32_t i)
{
    return sim->p[i].z < sim->box.z_exit && gf_sim_exit_slow(sim, w, i);
}

/// Bookkeeping after the moves of one step, for the entries k < m of
/// inside[] with moved[k] set: cells, and lists of those past their skin.
gf_status gf_sim_track_moves(gf_sim *sim, gf_work *w, size_t m, const uint8_t *moved);

/// qsort order of exits: by time, then id (the windowed engines' exits).
int gf_exit_cmp_time_id(const void *a, const void *b);

/// Queues particle i (just exited) for re-insertion; false when out of memory.
bool gf_sim_reinsert_queue(gf_sim *sim, uint32_t i);
/// Puts the queued particles back on the free surface (run.recirculate; in
/// id order, drawing on sim->rng), pass + 1, without overlaps.
gf_status gf_sim_reinsert(gf_sim *sim);
/// Whether a particle ending pass `pass` is to be put back.
static inline bool gf_sim_recirculates(const gf_sim *sim, int32_t pass)
{
    return sim->d.recirculate && (sim->d.max_passes == 0 || pass < sim->d.max_passes);
}

/// Allocates the particle arrays for n particles.
gf_status gf_sim_alloc_particles(gf_sim *sim, size_t n);
/// Room in sim->exits for `extra` more; false when out of memory.
bool gf_sim_exits_reserve(gf_sim *sim, size_t extra);
/// Allocates a worker's scratch, sized for the gather of one step.
gf_status gf_work_init(const gf_sim *sim, gf_work *w);
void gf_work_free(gf_work *w);
/// Makes the serial worker sim->w0 (scratch, sim->rng, sim->st).
gf_status gf_sim_alloc_scratch(gf_sim *sim);

/// The spatial fixed step (run.order = spatial, parallel.c): insertions,
/// then every spot once, in one of 16 random phases, block colour by block
/// colour, the blocks of one colour on run.threads threads. The result does
/// not depend on the thread count.
gf_status gf_sim_spatial_step(gf_sim *sim);
/// One cycle of the domain engine (run.order = domains, domains.c): the
/// insertions of a window of parallel.window tau, then every sector of every
/// domain in turn, each moving its spots at their own rate over the window,
/// the domains of one sector side by side on run.threads threads.
gf_status gf_sim_domains_cycle(gf_sim *sim);
/// One window of the sweep engine (run.order = sweep, sweep.c): insertions,
/// every spot's moves from the window-start packing, their displacements
/// summed, then parallel.sweeps Jacobi relaxation sweeps; parallel over spots
/// and cells, the result independent of run.threads.
gf_status gf_sim_sweep_window(gf_sim *sim);
/// Frees the sweep engine's state.
void gf_sweep_free(gf_sim *sim);
/// Tests: every window of the sweep engine visits every cell chunk, not
/// only those its moves reach (the result must not change).
void gf_sweep_set_dense(gf_sim *sim, int on);
/// Tests: the cell chunks the sweep engine's last window with moves visited.
size_t gf_sweep_touched_chunks(const gf_sim *sim);
/// Starts or stops profiling the sweep engine's chunks.
void gf_sweep_set_profiling(gf_sim *sim, int on);
/// The sweep engine's profile (gf_sim_par_profile).
gf_par_profile gf_sweep_profile(const gf_sim *sim);
/// Frees the domain engine's state.
void gf_dom_free(gf_sim *sim);
/// The domain engine's decomposition and profile (gf_sim_par_profile).
gf_par_profile gf_dom_profile(const gf_sim *sim);
/// Phases so far that had two or more sectors to run side by side.
uint64_t gf_dom_shared_phases(const gf_sim *sim);
/// MPI slabs: the particles in this rank's region (its slab and halo) and in
/// its slab, what it would hold were the memory divided; one process: every
/// particle in the grid, twice.
void gf_dom_region_particles(const gf_sim *sim, uint64_t *region, uint64_t *owned);
/// Tests only: makes the engine wrong on purpose (a spot whose move leaves
/// its sector is lost, with all its later moves, as a domain engine that
/// cannot hand spots over would lose them), to show that the flow test sees it.
gf_status gf_dom_test_drop_crossing(gf_sim *sim);
/// Starts or stops profiling the domain engine's sectors.
void gf_dom_set_profiling(gf_sim *sim, int on);

/// Everything a step of a spot at s touches lies within this distance of s
/// (parallel.c): regions that run side by side are two reaches and a cell
/// diagonal apart.
double gf_par_reach(const gf_sim *sim);
/// Threads of the parallel engines: run.threads, or every core (a machine's
/// cores shared between its MPI ranks).
int gf_par_threads(const gf_engine_defs *d);
/// The removal test's column tops, as gf_grid_column_top would answer now.
void gf_par_column_tops(const gf_sim *sim, double *coltop, size_t ncol);
struct gf_celllist;
/// Blocks of bs[a] cells along axis a (nb[a] of them) and their colours,
/// the block index modulo nc[a] along each axis: blockof[cell] is a cell's
/// block, and bycolour lists the blocks colour by colour, in index order.
gf_status gf_par_colour_blocks(const gf_grid *g, const int bs[3], const int nb[3], const int nc[3], uint32_t *blockof,
                               struct gf_celllist *bycolour);
/// Adds a region's counters (fixed order: the sums do not depend on threads).
void gf_par_add(gf_sim_stats *to, const gf_sim_stats *a);
/// Makespan of jobs of seconds secs[0, n) (heaviest first) on T threads,
/// each to the thread that frees first.
double gf_par_makespan(const double *secs, size_t n, int T);

/// Colour phases so far (this process) that had two or more blocks to run side by side.
uint64_t gf_par_shared_phases(const gf_sim *sim);
/// Frees the parallel step's state.
void gf_par_free(gf_sim *sim);
/// A fixed step's opening (clock, counters, Poisson(lambda / mu) insertions)
/// and closing (relax.method = global: the whole packing every k steps).
gf_status gf_sim_fixed_begin(gf_sim *sim);
gf_status gf_sim_fixed_end(gf_sim *sim);
/// Removes the spots flagged in dead[0, ns), keeping the rest in birth order.
void gf_spots_compact(gf_sim *sim, const uint8_t *dead);
/// A relaxation of the whole packing, timed into t_relax.
gf_status gf_sim_global(gf_sim *sim);
/// The insertions of the window (t_end - W, t_end] of the windowed engines
/// (domains.c, sweep.c): Poisson(lambda W) spots, each born at a uniform
/// time in the window and first moving an exponential time later (SPEC 1.3
/// insertion, as the event engine), drawing on sim->rng.
gf_status gf_spots_insert_window(gf_sim *sim, double t_end, double window);
/// The walk of a spot at s (SPEC 1.3): the candidate n, truncated at the
/// walls; false when the spot is to be removed (above its column's top, or
/// the biased walk finds no particle). Reads the particles, writes nothing
/// but w's stream.
bool gf_spot_walk(gf_sim *sim, gf_work *w, const double s[3], double n[3]);
/// Inserts one spot (SPEC 1.3 insertion), drawing on sim->rng.
gf_status gf_spot_insert(gf_sim *sim);
/// Moves spot k once with the serial worker (event mode, fixed random or
/// newest order), removing it when the step says so (walk.c).
gf_status gf_spot_move(gf_sim *sim, size_t k);
/// The engine's defs (sim->d, gf_config_engine_defs), derived parameters and container from sim->cfg.
void gf_sim_derive(gf_sim *sim);
/// Grid over the container and the packing's current extent.
gf_status gf_sim_make_grid(gf_sim *sim);
/// The end of a sim's creation, its particles placed and its grid made:
/// workers, stress field, neighbour lists (re-sorted), random stream.
gf_status gf_sim_finish(gf_sim *sim);
/// A sim with its config checked and derived, no particles yet (NULL and
/// *st on failure); gf_sim_discard frees one that failed to be made.
gf_sim *gf_sim_new(const gf_config *cfg, gf_status *st);
void gf_sim_discard(gf_sim *sim);
/// The grid's bounds (the container's, up to sim->grid_ztop).
void gf_sim_grid_bounds(const gf_sim *sim, double lo[3], double hi[3]);
/// Rank `me` of R of the domain engine: the sim of packing.file holding
/// only the particles of its region and a margin (window.c); GF_ERR_PARAM
/// when the config has no packing.file or asks for packing.types (then the
/// whole packing is read, as one process does).
gf_status gf_sim_create_part(const gf_config *cfg, int R, int me, gf_sim **out);
/// The cell layers along z of rank me's region of R ranks (the domain
/// engine's slabs, slabs.h) and a margin of `margin` layers each side,
/// [*lo, *hi): all layers when the slabs are not cut along z (domains.c).
gf_status gf_dom_window_layers(const gf_sim *sim, int R, int me, int margin, int *lo, int *hi);
/// The margin of a rank's window beyond its region, in cell layers: the
/// reach of a neighbour-list search (window.c).
int gf_window_margin(const gf_sim *sim);
/// A rank's re-sort of its window (window.c; the whole-state re-sort is
/// gf_nlist_build(sim, true)): the particles in cells [c0, c1), whose
/// records and cells must be exact here, take the indices [base, base + k)
/// one process's stable re-sort by cell gives them (k of them; `base` the
/// particles in the cells below c0, `n` in all, rmin and rmax their radii's
/// extremes); then its grid and neighbour rows are redone there.
gf_status gf_window_resort(gf_sim *sim, size_t c0, size_t c1, size_t base, size_t n, double rmin, double rmax);
/// Makes the domain engine's decomposition if not yet made and returns its
/// slabs (NULL: one process or not the domain engine).
const gf_slabs *gf_dom_slabs_made(gf_sim *sim, gf_status *st);
/// Particle records this process holds (a non-zero id): every particle in
/// one process; an MPI rank that read its region only, that region's and
/// the ones its neighbours sent it, until a gather made the state whole.
uint64_t gf_sim_held_particles(const gf_sim *sim);

/// With spot.flow_rule = sfr: solves the container's stress field up to the
/// packing's top (docs/stress.md) and the walk's constants; nothing otherwise.
gf_status gf_sim_make_stress(gf_sim *sim);

/// With spot.flow_rule = sfr: writes the stress field to dir/stress.csv (docs/stress.md).
gf_status gf_sim_write_stress(const gf_sim *sim, const char *dir);
/// On resume (checkpoint.c): the configuration text a checkpoint stored
/// (slen bytes, from the file) against the one this run would store (mine)
/// and the defaults' (def), setting by setting (ckpt_settings.c). GF_OK, or
/// the refusal naming the first key that differs, is missing while not at
/// its default, is unknown here or is listed twice.
gf_status gf_ckpt_compare_settings(const char *path, const char *stored, size_t slen, const char *mine, size_t mlen,
                                   const char *def, size_t dlen);

/// The calling thread's number in its OpenMP team (0 without OpenMP): the
/// per-thread scratch (gf_work, candidate lists) a parallel loop's body uses.
static inline int gf_sim_thread(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

#endif
