// SPDX-License-Identifier: MIT
// VTK output: the file formats of https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html
// (XML UnstructuredGrid for particles, legacy POLYDATA for surfaces), ASCII.
#include "io/vtk.h"

#include <inttypes.h>
#include <stdio.h>

#include "core/atomic_file.h"
#include "core/error.h"

gf_status gf_vtk_write_particles(const char *path, const gf_packing *p, const int32_t *pass, double time)
{
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    const size_t n = p->n;
    fputs("<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
          "<UnstructuredGrid>\n",
          f);
    fprintf(f, "<FieldData>\n<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n"
               "</FieldData>\n", time);
    fprintf(f, "<Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", n, n);
    fputs("<PointData Scalars=\"radius\">\n<DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%" PRId64 "\n", p->id[i]);
    fputs("</DataArray>\n<DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%.9g\n", p->r[i]);
    fputs("</DataArray>\n<DataArray type=\"Int32\" Name=\"pass\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%d\n", pass ? (int)pass[i] : 1);
    fputs("</DataArray>\n<DataArray type=\"Int32\" Name=\"layer\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%d\n", (int)p->layer[i]);
    fputs("</DataArray>\n</PointData>\n<Points>\n"
          "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%.7f %.7f %.7f\n", p->x[i], p->y[i], p->z[i]);
    // One vertex cell (type 1) per particle, so every VTK reader draws them.
    fputs("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%zu\n", i);
    fputs("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fprintf(f, "%zu\n", i + 1);
    fputs("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n", f);
    for (size_t i = 0; i < n; i++) fputs("1\n", f);
    fputs("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n", f);
    return gf_atomic_commit(f, tmp, path);
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
