// SPDX-License-Identifier: MIT
// VTK output: the XML file formats of
// https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html
// (UnstructuredGrid for particles, PolyData for surfaces, a Collection for the
// series) and the legacy POLYDATA surface OVITO reads. The arrays of an XML
// file go, by default, zlib-compressed into one raw appended block (what
// ParaView itself writes); ASCII writes them inline, readable by eye.
#include "io/vtk.h"

#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"

// Uncompressed bytes per zlib block: VTK's own default (vtkXMLWriter), so
// that a reader never needs more than this at a time.
#define GF_VTK_BLOCK 32768

/// One DataArray: its values in host byte order, and (binary) their encoded
/// form, header and compressed blocks, at `offset` in the appended block.
typedef struct gf_vtk_arr {
    const char *name; ///< Name attribute, NULL for none (the Points array)
    const char *type; ///< VTK type: Float64, Int64, Int32, UInt8
    size_t width;     ///< bytes per value
    int ncomp;        ///< NumberOfComponents
    size_t count;     ///< values (tuples x ncomp)
    unsigned char *data;
    unsigned char *enc;
    size_t enc_len, enc_cap;
    uint64_t offset;
} gf_vtk_arr;

static const char *gf_vtk_byte_order(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b ? "LittleEndian" : "BigEndian";
}

static gf_status gf_vtk_arr_make(gf_vtk_arr *a, const char *name, const char *type, size_t width, int ncomp,
                                 size_t count)
{
    *a = (gf_vtk_arr){.name = name, .type = type, .width = width, .ncomp = ncomp, .count = count};
    if (count && !(a->data = GF_NEW(unsigned char, count * width)))
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the VTK array %s (%zu values)", name ? name : "Points",
                            count);
    return GF_OK;
}

static void gf_vtk_arr_free(gf_vtk_arr *a)
{
    if (a->data) GF_DELETE(a->data, a->count * a->width);
    if (a->enc) GF_DELETE(a->enc, a->enc_cap);
    memset(a, 0, sizeof *a);
}

static void gf_vtk_put64(unsigned char *at, uint64_t v) { memcpy(at, &v, sizeof v); }

/// The compressed form of `a` (vtkZLibDataCompressor, header_type UInt64):
/// [blocks, block size, last block's size, compressed size of each block],
/// then the blocks.
static gf_status gf_vtk_arr_encode(gf_vtk_arr *a)
{
    const size_t bytes = a->count * a->width;
    const size_t nb = (bytes + GF_VTK_BLOCK - 1) / GF_VTK_BLOCK;
    const size_t head = (3 + nb) * sizeof(uint64_t);
    a->enc_cap = head + nb * (size_t)compressBound(GF_VTK_BLOCK);
    if (!(a->enc = GF_NEW(unsigned char, a->enc_cap)))
        return gf_error_set(GF_ERR_NOMEM, "out of memory compressing the VTK array %s", a->name ? a->name : "Points");
    gf_vtk_put64(a->enc, nb);
    gf_vtk_put64(a->enc + 8, GF_VTK_BLOCK);
    gf_vtk_put64(a->enc + 16, nb ? bytes - (nb - 1) * GF_VTK_BLOCK : 0);
    size_t at = head;
    for (size_t b = 0; b < nb; b++) {
        size_t len = b + 1 < nb ? GF_VTK_BLOCK : bytes - b * GF_VTK_BLOCK;
        uLongf out = (uLongf)(a->enc_cap - at);
        // Level 1: a snapshot of 55,000 particles compresses in milliseconds,
        // to about the size level 6 gives (the coordinates are noise).
        if (compress2(a->enc + at, &out, a->data + b * GF_VTK_BLOCK, (uLong)len, 1) != Z_OK)
            return gf_error_set(GF_ERR_NOMEM, "zlib could not compress the VTK array %s", a->name ? a->name : "Points");
        gf_vtk_put64(a->enc + 24 + 8 * b, (uint64_t)out);
        at += out;
    }
    a->enc_len = at;
    return GF_OK;
}

/// One value of `a` as ASCII text.
static void gf_vtk_put_value(FILE *f, const gf_vtk_arr *a, size_t i)
{
    const unsigned char *p = a->data + i * a->width;
    if (!strcmp(a->type, "Float64")) {
        double v;
        memcpy(&v, p, sizeof v);
        fprintf(f, "%.17g", v);
    } else if (!strcmp(a->type, "Int64")) {
        int64_t v;
        memcpy(&v, p, sizeof v);
        fprintf(f, "%" PRId64, v);
    } else if (!strcmp(a->type, "Int32")) {
        int32_t v;
        memcpy(&v, p, sizeof v);
        fprintf(f, "%" PRId32, v);
    } else {
        fprintf(f, "%u", (unsigned)*p);
    }
}

/// The DataArray element of `a`: with its values (ASCII), or pointing into
/// the appended block.
static void gf_vtk_put_array(FILE *f, const gf_vtk_arr *a, gf_vtk_encoding enc)
{
    fprintf(f, "<DataArray type=\"%s\"", a->type);
    if (a->name) fprintf(f, " Name=\"%s\"", a->name);
    if (a->ncomp != 1) fprintf(f, " NumberOfComponents=\"%d\"", a->ncomp);
    if (enc == GF_VTK_BINARY) {
        fprintf(f, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", a->offset);
        return;
    }
    fputs(" format=\"ascii\">\n", f);
    for (size_t i = 0; i < a->count; i++) {
        gf_vtk_put_value(f, a, i);
        fputc((i + 1) % (size_t)a->ncomp ? ' ' : '\n', f);
    }
    fputs("</DataArray>\n", f);
}

/// A whole VTK XML file of `type` (UnstructuredGrid, PolyData): `piece` is
/// the Piece element's attributes; arrays [0, npd) are point data, then the
/// Points array, then the cell arrays of element `cells` (Cells, Polys).
/// `time` (unless NAN) goes in the field data TimeValue, which ParaView
/// reads as the dataset's time.
static gf_status gf_vtk_write_xml(const char *path, const char *type, const char *piece, double time, gf_vtk_arr *arr,
                                  size_t narr, size_t npd, const char *cells, gf_vtk_encoding enc)
{
    gf_status st = GF_OK;
    uint64_t offset = 0;
    for (size_t k = 0; st == GF_OK && enc == GF_VTK_BINARY && k < narr; k++) {
        st = gf_vtk_arr_encode(&arr[k]);
        arr[k].offset = offset;
        offset += arr[k].enc_len;
    }
    if (st != GF_OK) return st;
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    if ((st = gf_atomic_open(path, tmp, sizeof tmp, &f)) != GF_OK) return st;
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"%s\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\"%s>\n",
            type, gf_vtk_byte_order(), enc == GF_VTK_BINARY ? " compressor=\"vtkZLibDataCompressor\"" : "");
    fprintf(f, "<%s>\n", type);
    if (!isnan(time)) // the time, ASCII even in a binary file: one value, found by eye and by gf_vtk_read_time
        fprintf(f, "<FieldData>\n<DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                   "format=\"ascii\">%.17g</DataArray>\n</FieldData>\n", time);
    fprintf(f, "<Piece %s>\n", piece);
    if (npd) fprintf(f, "<PointData Scalars=\"%s\">\n", arr[npd > 1 ? 1 : 0].name);
    for (size_t k = 0; k < npd; k++) gf_vtk_put_array(f, &arr[k], enc);
    if (npd) fputs("</PointData>\n", f);
    fputs("<Points>\n", f);
    gf_vtk_put_array(f, &arr[npd], enc);
    fprintf(f, "</Points>\n<%s>\n", cells);
    for (size_t k = npd + 1; k < narr; k++) gf_vtk_put_array(f, &arr[k], enc);
    fprintf(f, "</%s>\n</Piece>\n</%s>\n", cells, type);
    if (enc == GF_VTK_BINARY) {
        fputs("<AppendedData encoding=\"raw\">\n_", f);
        for (size_t k = 0; k < narr; k++) fwrite(arr[k].enc, 1, arr[k].enc_len, f);
        fputs("\n</AppendedData>\n", f);
    }
    fputs("</VTKFile>\n", f);
    return gf_atomic_commit(f, tmp, path);
}

static void gf_vtk_set_f64(gf_vtk_arr *a, size_t i, double v) { memcpy(a->data + 8 * i, &v, 8); }
static void gf_vtk_set_i64(gf_vtk_arr *a, size_t i, int64_t v) { memcpy(a->data + 8 * i, &v, 8); }
static void gf_vtk_set_i32(gf_vtk_arr *a, size_t i, int32_t v) { memcpy(a->data + 4 * i, &v, 4); }

gf_status gf_vtk_write_particles_as(const char *path, const gf_packing *p, const int32_t *pass, double time,
                                    gf_vtk_encoding enc)
{
    const size_t n = p->n;
    enum { ID, RADIUS, PASS, LAYER, POINTS, CONN, OFFS, TYPES, NARR };
    gf_vtk_arr a[NARR];
    memset(a, 0, sizeof a);
    gf_status st = gf_vtk_arr_make(&a[ID], "id", "Int64", 8, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[RADIUS], "radius", "Float64", 8, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[PASS], "pass", "Int32", 4, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[LAYER], "layer", "Int32", 4, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[POINTS], NULL, "Float64", 8, 3, 3 * n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[CONN], "connectivity", "Int64", 8, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[OFFS], "offsets", "Int64", 8, 1, n);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[TYPES], "types", "UInt8", 1, 1, n);
    for (size_t i = 0; st == GF_OK && i < n; i++) {
        gf_vtk_set_i64(&a[ID], i, p->id[i]);
        gf_vtk_set_f64(&a[RADIUS], i, p->r[i]);
        gf_vtk_set_i32(&a[PASS], i, pass ? pass[i] : 1);
        gf_vtk_set_i32(&a[LAYER], i, p->layer[i]);
        gf_vtk_set_f64(&a[POINTS], 3 * i, p->x[i]);
        gf_vtk_set_f64(&a[POINTS], 3 * i + 1, p->y[i]);
        gf_vtk_set_f64(&a[POINTS], 3 * i + 2, p->z[i]);
        // One vertex cell (type 1) per particle, so that every VTK reader draws them.
        gf_vtk_set_i64(&a[CONN], i, (int64_t)i);
        gf_vtk_set_i64(&a[OFFS], i, (int64_t)i + 1);
        a[TYPES].data[i] = 1;
    }
    char piece[96];
    snprintf(piece, sizeof piece, "NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\"", n, n);
    if (st == GF_OK) st = gf_vtk_write_xml(path, "UnstructuredGrid", piece, time, a, NARR, POINTS, "Cells", enc);
    for (size_t k = 0; k < NARR; k++) gf_vtk_arr_free(&a[k]);
    return st;
}

gf_status gf_vtk_write_particles(const char *path, const gf_packing *p, const int32_t *pass, double time)
{
    return gf_vtk_write_particles_as(path, p, pass, time, GF_VTK_BINARY);
}

gf_status gf_vtk_write_surface(const char *path, const gf_mesh *m, gf_vtk_encoding enc)
{
    enum { POINTS, CONN, OFFS, NARR };
    gf_vtk_arr a[NARR];
    memset(a, 0, sizeof a);
    gf_status st = gf_vtk_arr_make(&a[POINTS], NULL, "Float64", 8, 3, 3 * m->nv);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[CONN], "connectivity", "Int64", 8, 1, 3 * m->nt);
    if (st == GF_OK) st = gf_vtk_arr_make(&a[OFFS], "offsets", "Int64", 8, 1, m->nt);
    for (size_t i = 0; st == GF_OK && i < m->nv; i++)
        for (int k = 0; k < 3; k++) gf_vtk_set_f64(&a[POINTS], 3 * i + (size_t)k, m->v[i][k]);
    for (size_t i = 0; st == GF_OK && i < m->nt; i++) {
        for (int k = 0; k < 3; k++) gf_vtk_set_i64(&a[CONN], 3 * i + (size_t)k, (int64_t)m->t[i][k]);
        gf_vtk_set_i64(&a[OFFS], i, 3 * (int64_t)i + 3);
    }
    char piece[160];
    snprintf(piece, sizeof piece,
             "NumberOfPoints=\"%zu\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"%zu\"",
             m->nv, m->nt);
    if (st == GF_OK) st = gf_vtk_write_xml(path, "PolyData", piece, NAN, a, NARR, 0, "Polys", enc);
    for (size_t k = 0; k < NARR; k++) gf_vtk_arr_free(&a[k]);
    return st;
}

gf_status gf_vtk_write_mesh(const char *path, const gf_mesh *m, const char *title)
{
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    fprintf(f, "# vtk DataFile Version 3.0\n%.200s\nASCII\nDATASET POLYDATA\nPOINTS %zu double\n", title, m->nv);
    for (size_t i = 0; i < m->nv; i++) fprintf(f, "%.9g %.9g %.9g\n", m->v[i][0], m->v[i][1], m->v[i][2]);
    fprintf(f, "POLYGONS %zu %zu\n", m->nt, 4 * m->nt);
    for (size_t i = 0; i < m->nt; i++) fprintf(f, "3 %zu %zu %zu\n", m->t[i][0], m->t[i][1], m->t[i][2]);
    return gf_atomic_commit(f, tmp, path);
}

gf_status gf_vtk_write_collection(const char *path, const char *const *files, const double *times, size_t n)
{
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"%s\">\n<Collection>\n",
            gf_vtk_byte_order());
    for (size_t k = 0; k < n; k++)
        fprintf(f, "<DataSet timestep=\"%.17g\" part=\"0\" file=\"%s\"/>\n", times[k], files[k]);
    fputs("</Collection>\n</VTKFile>\n", f);
    return gf_atomic_commit(f, tmp, path);
}

gf_status gf_vtk_read_time(const char *path, double *time)
{
    FILE *f = fopen(path, "rb");
    if (!f) return gf_error_set(GF_ERR_IO, "%s: cannot open", path);
    // The field data comes before the first piece, in the first lines.
    char head[1024];
    size_t len = fread(head, 1, sizeof head - 1, f);
    fclose(f);
    head[len] = '\0';
    static const char *const names[] = {"Name=\"TimeValue\"", "Name=\"TIME\""}; // TIME: granflow before issue 25
    for (size_t k = 0; k < 2; k++) {
        const char *p = strstr(head, names[k]);
        p = p ? strchr(p, '>') : NULL;
        char *end;
        double t = p ? strtod(p + 1, &end) : 0.0;
        if (p && end != p + 1) {
            *time = t;
            return GF_OK;
        }
    }
    return gf_error_set(GF_ERR_FORMAT, "%s: no TimeValue field data in its first %zu bytes", path, len);
}
