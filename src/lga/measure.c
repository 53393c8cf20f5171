// SPDX-License-Identifier: MIT
// What the LGA runs measure: density fields, the heap profile and its slope
// (paper Sec. 3.1), density waves along a channel (Sec. 3.2).
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "lga/lattice.h"

#define GF_LGA_RAD2DEG 57.295779513082320877

void gf_lga_density(const gf_lga *l, double *out)
{
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            size_t s = gf_lga_index(l, i, j);
            out[(size_t)j * (size_t)l->w + (size_t)i] = gf_lga_count(l, l->state[s]) + l->excess[s];
        }
}

void gf_lga_density_smoothed(const gf_lga *l, double *out)
{
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            size_t s = gf_lga_index(l, i, j);
            double *o = &out[(size_t)j * (size_t)l->w + (size_t)i];
            if (l->state[s] & GF_LGA_WALL) {
                *o = NAN;
                continue;
            }
            double sum = gf_lga_count(l, l->state[s]) + l->excess[s];
            int n = 1;
            for (int e = 1; e <= 6; e++) {
                size_t t = gf_lga_neighbour(l, i, j, e);
                if (l->state[t] & GF_LGA_WALL) continue;
                sum += gf_lga_count(l, l->state[t]) + l->excess[t];
                n++;
            }
            *o = sum / n;
        }
}

void gf_lga_profile(const gf_lga *l, double *out)
{
    // Floor: half a spacing below the lowest fluid site of any column.
    double floor_y = INFINITY;
    for (int i = 0; i < l->w; i++)
        for (int j = 0; j < l->h; j++) {
            uint16_t s = l->state[gf_lga_index(l, i, j)];
            if (s & GF_LGA_WALL) continue;
            double x, y;
            gf_lga_site_position(i, j, &x, &y);
            if (!(s & GF_LGA_SINK)) floor_y = fmin(floor_y, y - 0.5);
            break;
        }
    for (int i = 0; i < l->w; i++) {
        int first = -1, top = -1, gap = 0;
        for (int j = 0; j < l->h; j++) {
            uint16_t s = l->state[gf_lga_index(l, i, j)];
            if (first < 0) {
                if (s & GF_LGA_WALL) continue;
                if (s & GF_LGA_SINK) break;
                first = j;
            }
            if (s & GF_LGA_WALL) break;
            // The heap: resting particles up from the floor, gaps of one or two allowed.
            if (s & GF_LGA_REST) {
                top = j;
                gap = 0;
            } else if (++gap >= 3) {
                break;
            }
        }
        if (first < 0) {
            out[i] = NAN;
            continue;
        }
        double x, y;
        gf_lga_site_position(i, top, &x, &y);
        out[i] = top < 0 ? 0.0 : y + 0.5 - floor_y;
    }
}

// Least-squares slope of y against x over the points with mask set.
static bool gf_lga_fit_slope(const double *x, const double *y, int n, double *slope)
{
    if (n < 3) return false;
    double mx = 0, my = 0;
    for (int k = 0; k < n; k++) {
        mx += x[k];
        my += y[k];
    }
    mx /= n;
    my /= n;
    double sxx = 0, sxy = 0;
    for (int k = 0; k < n; k++) {
        sxx += (x[k] - mx) * (x[k] - mx);
        sxy += (x[k] - mx) * (y[k] - my);
    }
    if (!(sxx > 0)) return false;
    *slope = sxy / sxx;
    return true;
}

double gf_lga_slope_angle(const double *profile, int width, double lo, double hi, double *left, double *right)
{
    double peak = 0;
    int ipeak = -1;
    for (int i = 0; i < width; i++)
        if (profile[i] > peak) {
            peak = profile[i];
            ipeak = i;
        }
    double ang[2] = {NAN, NAN};
    if (ipeak >= 0 && width > 0) {
        double *x = gf_alloc(sizeof(double) * (size_t)width), *y = gf_alloc(sizeof(double) * (size_t)width);
        for (int side = 0; x && y && side < 2; side++) {
            int n = 0;
            for (int i = 0; i < width; i++) {
                if ((side == 0 && i >= ipeak) || (side == 1 && i <= ipeak)) continue;
                double h = profile[i];
                if (!(h >= lo * peak && h <= hi * peak)) continue;
                x[n] = i * 0.86602540378443864676;
                y[n] = h;
                n++;
            }
            double s;
            if (gf_lga_fit_slope(x, y, n, &s)) ang[side] = atan(fabs(s)) * GF_LGA_RAD2DEG;
        }
        if (x) gf_free(x, sizeof(double) * (size_t)width);
        if (y) gf_free(y, sizeof(double) * (size_t)width);
    }
    if (left) *left = ang[0];
    if (right) *right = ang[1];
    if (isnan(ang[0]) || isnan(ang[1])) return NAN;
    return 0.5 * (ang[0] + ang[1]);
}

int64_t gf_lga_outflow_time(const int64_t *iteration, const int64_t *count, size_t n, double fraction)
{
    if (!(fraction > 0 && fraction <= 1)) return -1;
    int64_t total = 0;
    for (size_t k = 0; k < n; k++) total += count[k];
    if (total <= 0) return -1;
    // Compared as integers: sum >= need, the product rounded up (less a hair, so
    // that 0.9 x 10 is 9 whatever its last bit); fraction 1 is the last outflow.
    int64_t need = (int64_t)ceil(fraction * (double)total - 1e-9);
    if (need < 1) need = 1;
    int64_t sum = 0;
    for (size_t k = 0; k < n; k++)
        if ((sum += count[k]) >= need) return iteration[k];
    return iteration[n - 1];
}

void gf_lga_row_density(const gf_lga *l, double *out)
{
    for (int j = 0; j < l->h; j++) {
        double sum = 0;
        int n = 0;
        for (int i = 0; i < l->w; i++) {
            size_t s = gf_lga_index(l, i, j);
            if (l->state[s] & GF_LGA_WALL) continue;
            sum += gf_lga_count(l, l->state[s]) + l->excess[s];
            n++;
        }
        out[j] = n ? sum / n : 0.0;
    }
}

double gf_lga_wave_variance(const gf_lga *l, int window)
{
    int h = l->h;
    if (window < 1) window = 1;
    double *rho = gf_alloc(sizeof(double) * (size_t)h);
    if (!rho) return NAN;
    gf_lga_row_density(l, rho);
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int j = 0; j < h; j++) {
        double acc = 0;
        int c = 0;
        for (int k = 0; k < window; k++) {
            int jj = j + k - window / 2;
            if (l->periodic) jj = ((jj % h) + h) % h;
            else if (jj < 0 || jj >= h) continue;
            acc += rho[jj];
            c++;
        }
        double v = acc / c;
        sum += v;
        sum2 += v * v;
        n++;
    }
    gf_free(rho, sizeof(double) * (size_t)h);
    double mean = sum / n;
    return fmax(0.0, sum2 / n - mean * mean);
}
