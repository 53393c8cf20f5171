// SPDX-License-Identifier: MIT
// The records of the MPI exchange: checked, then applied (mpi_records.h).
// Every index a record carries is checked against this rank's state before
// anything is written: a rank out of step (another seed, another container,
// another version) sends indices that mean nothing here, and writing through
// them corrupted the heap (issue 26).
#include "spot/mpi_records.h"

#include <string.h>

#include "core/error.h"

void gf_mpi_records_kinds(const gf_sim *sim, size_t nblock, size_t block_size, size_t limit[GF_TOUCH_KINDS],
                          size_t rec[GF_TOUCH_KINDS])
{
    const size_t row = sim->use_nlist && sim->nl ? sizeof(uint32_t) << sim->nl_shift : 0;
    limit[GF_TOUCH_ROW] = row ? sim->n : 0;
    limit[GF_TOUCH_PARTICLE] = limit[GF_TOUCH_MOVED] = sim->n;
    limit[GF_TOUCH_CELL] = sim->grid.ncell;
    limit[GF_TOUCH_SPOT] = sim->ns;
    limit[GF_TOUCH_BLOCK] = nblock;
    rec[GF_TOUCH_PARTICLE] = sizeof(gf_mpi_part);
    rec[GF_TOUCH_MOVED] = sizeof(gf_mpi_pos);
    rec[GF_TOUCH_ROW] = sizeof(uint32_t) + row;
    rec[GF_TOUCH_CELL] = sizeof(gf_mpi_cell) + GF_CELL_CAP * sizeof(uint32_t);
    rec[GF_TOUCH_SPOT] = sizeof(gf_mpi_spot);
    rec[GF_TOUCH_BLOCK] = sizeof(uint32_t) + block_size;
}

static const char *const gf_mpi_kind_name[GF_TOUCH_KINDS] = {"particle", "moved-particle", "neighbour-list",
                                                              "cell", "spot", "block"};

// The refusal of rank `from`'s record e of kind k.
static gf_status gf_mpi_bad(int from, int k, size_t e, const char *what, uint64_t value, size_t limit)
{
    return gf_error_set(GF_ERR_STATE,
                        "MPI exchange: rank %d sent %s record %zu with %s %llu, beyond the %zu there are here: the "
                        "ranks are out of step (every rank must run the same configuration and version)",
                        from, gf_mpi_kind_name[k], e, what, (unsigned long long)value, limit);
}

gf_status gf_mpi_records_check(const gf_sim *sim, const unsigned char *msg, size_t len, size_t nblock,
                               size_t block_size, int from)
{
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, nblock, block_size, limit, rec);
    gf_mpi_head h;
    if (len < sizeof h)
        return gf_error_set(GF_ERR_STATE, "MPI exchange: rank %d sent a message of %zu bytes, shorter than its head",
                            from, len);
    memcpy(&h, msg, sizeof h);
    uint64_t need = sizeof h;
    for (int k = 0; k < GF_TOUCH_KINDS; k++) need += (uint64_t)h.v[1 + k] * rec[k];
    if (h.v[0] != len || need != len)
        return gf_error_set(GF_ERR_STATE,
                            "MPI exchange: rank %d sent a message of %zu bytes whose head says %u and whose records "
                            "take %llu: the ranks are out of step",
                            from, len, h.v[0], (unsigned long long)need);
    const unsigned char *o = msg + sizeof h;
    const uint32_t row_slots = (uint32_t)((rec[GF_TOUCH_ROW] - sizeof(uint32_t)) / sizeof(uint32_t));
    for (int k = 0; k < GF_TOUCH_KINDS; k++) {
        for (size_t e = 0; e < h.v[1 + k]; e++, o += rec[k]) {
            uint32_t i; // every record's index comes first but the spot's
            if (k == GF_TOUCH_SPOT) {
                gf_mpi_spot r;
                memcpy(&r, o, sizeof r);
                if (r.k >= limit[k]) return gf_mpi_bad(from, k, e, "spot", r.k, limit[k]);
                if (r.dead > 1) return gf_mpi_bad(from, k, e, "dead flag", r.dead, 2);
                continue;
            }
            memcpy(&i, o, sizeof i);
            if (i >= limit[k]) return gf_mpi_bad(from, k, e, "index", i, limit[k]);
            if (k == GF_TOUCH_PARTICLE) {
                gf_mpi_part r;
                memcpy(&r, o, sizeof r);
                if (r.cell != GF_NO_CELL && r.cell >= sim->grid.ncell)
                    return gf_mpi_bad(from, k, e, "cell", r.cell, sim->grid.ncell);
                if (r.cell != GF_NO_CELL && r.slot >= GF_CELL_CAP)
                    return gf_mpi_bad(from, k, e, "slot", r.slot, GF_CELL_CAP);
                if (r.alive > 1) return gf_mpi_bad(from, k, e, "alive flag", r.alive, 2);
            } else if (k == GF_TOUCH_ROW) {
                uint32_t n;
                memcpy(&n, o + sizeof i, sizeof n);
                if (n >= row_slots) return gf_mpi_bad(from, k, e, "row length", n, row_slots);
                for (uint32_t j = 1; j <= n; j++) {
                    uint32_t v;
                    memcpy(&v, o + sizeof i + j * sizeof v, sizeof v);
                    if (v >= sim->n) return gf_mpi_bad(from, k, e, "neighbour", v, sim->n);
                }
            } else if (k == GF_TOUCH_CELL) {
                gf_mpi_cell r;
                memcpy(&r, o, sizeof r);
                if (r.count > GF_CELL_CAP) return gf_mpi_bad(from, k, e, "count", r.count, GF_CELL_CAP);
                for (uint32_t j = 0; j < r.count; j++) {
                    uint32_t v;
                    memcpy(&v, o + sizeof r + j * sizeof v, sizeof v);
                    if (v >= sim->n) return gf_mpi_bad(from, k, e, "particle", v, sim->n);
                }
            }
        }
    }
    return GF_OK;
}

void gf_mpi_records_apply(gf_sim *sim, const unsigned char *o, uint8_t *dead, void *blocks, size_t nblock,
                          size_t block_size, bool cells, uint64_t *parts, uint64_t *ncells)
{
    gf_grid *g = &sim->grid;
    size_t limit[GF_TOUCH_KINDS], rec[GF_TOUCH_KINDS];
    gf_mpi_records_kinds(sim, nblock, block_size, limit, rec);
    gf_mpi_head h;
    memcpy(&h, o, sizeof h);
    o += sizeof h;
    const size_t row = rec[GF_TOUCH_ROW] - sizeof(uint32_t), cell_row = GF_CELL_CAP * sizeof(uint32_t);
    for (int k = 0; k < GF_TOUCH_KINDS; k++) {
        const uint32_t count = h.v[1 + k];
        if ((k == GF_TOUCH_CELL) != cells) {
            o += count * rec[k];
            continue;
        }
        for (size_t e = 0; e < count; e++, o += rec[k]) {
            switch (k) {
            case GF_TOUCH_PARTICLE: {
                gf_mpi_part r;
                memcpy(&r, o, sizeof r);
                g->cell_of[r.i] = r.cell;
                g->slot_of[r.i] = r.slot;
                sim->alive[r.i] = (uint8_t)r.alive;
                sim->p[r.i] = r.p;
                sim->p0[r.i] = r.p0;
                sim->id[r.i] = r.id;
                sim->layer[r.i] = r.layer;
                sim->hist[r.i] = r.hist;
                break;
            }
            case GF_TOUCH_MOVED: {
                gf_mpi_pos r;
                memcpy(&r, o, sizeof r);
                sim->p[r.i].x = r.x;
                sim->p[r.i].y = r.y;
                sim->p[r.i].z = r.z;
                break;
            }
            case GF_TOUCH_ROW: {
                uint32_t i;
                memcpy(&i, o, sizeof i);
                memcpy(sim->nl + ((size_t)i << sim->nl_shift), o + sizeof i, row);
                break;
            }
            case GF_TOUCH_CELL: {
                gf_mpi_cell r;
                memcpy(&r, o, sizeof r);
                uint32_t *s = g->slot + (size_t)r.c * GF_CELL_CAP;
                memcpy(s, o + sizeof r, cell_row);
                g->count[r.c] = r.count;
                for (uint32_t j = 0; j < r.count; j++) {
                    g->cell_of[s[j]] = r.c;
                    g->slot_of[s[j]] = j;
                }
                break;
            }
            case GF_TOUCH_SPOT: {
                gf_mpi_spot r;
                memcpy(&r, o, sizeof r);
                sim->sx[r.k] = r.x;
                sim->sy[r.k] = r.y;
                sim->sz[r.k] = r.z;
                sim->scount[r.k] = r.count;
                sim->snext[r.k] = r.next;
                dead[r.k] = (uint8_t)r.dead;
                break;
            }
            default: {
                uint32_t b;
                memcpy(&b, o, sizeof b);
                memcpy((unsigned char *)blocks + b * block_size, o + sizeof b, block_size);
            }
            }
        }
        if (k == GF_TOUCH_PARTICLE || k == GF_TOUCH_MOVED) *parts += count;
        if (k == GF_TOUCH_CELL) *ncells += count;
    }
}
