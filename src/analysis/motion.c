/* motion.c — energies, speeds and the binned velocity field
 * (shapedem/analysis.h): seed 004 §4.2 follows the drum by its mean
 * particle velocity; seed 000 §3.4 compares the velocity field on the
 * drum's mid plane with PIV.
 *
 * The velocity field is the number average of the centres' velocities per
 * cell of a 2D grid: particles whose centre lies in the box (the slab)
 * are binned by their two in-plane coordinates. A rigid rotation w x r
 * gives w x r at each cell's particles, so the field is its average there.
 *
 * Invariant: sums run over the particles in storage order, serially: the
 * same bits for any thread count.
 */
#include <math.h>
#include <string.h>

#include "analysis/analysis.h"

#define SD_COOKIE_ANALYSIS 0x5DA1

sd_status sd_world_motion_stats(const sd_world *w, const sd_region_def *region, sd_motion_stats *out, sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_motion_stats", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    sd_an_region r;
    sd_an_set set;
    sd_status st;
    if ((st = sd_an_region_make(region, w->dim2, &r, err)) != SD_OK || (st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    double vs = 0, vx = 0, vy = 0, vz = 0;
    for (size_t k = 0; k < set.n; ++k) {
        const sd_an_body *b = &set.b[k];
        if (!sd_an_region_has(&r, b->x))
            continue;
        double v2 = (double)sd_v3_dot(b->v, b->v), v = sqrt(v2);
        out->particles++;
        out->mass += (double)b->mass;
        out->kinetic_translational += 0.5 * (double)b->mass * v2;
        out->kinetic_rotational += sd_an_rot_energy(w, b);
        vs += v;
        vx += (double)b->v.x, vy += (double)b->v.y, vz += (double)b->v.z;
        out->max_speed = fmax(out->max_speed, v);
    }
    if (out->particles > 0) {
        double c = 1.0 / (double)out->particles;
        out->mean_speed = vs * c;
        out->mean_velocity.x = vx * c, out->mean_velocity.y = vy * c, out->mean_velocity.z = vz * c;
    }
    sd_an_free(&set);
    return SD_OK;
}

sd_status sd_world_speed_histogram(const sd_world *w, const sd_region_def *region, int bins, double max_speed,
                                   size_t *counts, double *top, sd_error *err)
{
    if (!w || !counts)
        return sd_error_null(err, "sd_world_speed_histogram", !w ? "world" : "counts");
    if (bins < 1)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "bins", "expected bins >= 1, got %d", bins);
    memset(counts, 0, (size_t)bins * sizeof *counts);
    sd_an_region r;
    sd_an_set set;
    sd_status st;
    if ((st = sd_an_region_make(region, w->dim2, &r, err)) != SD_OK || (st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    double vt = max_speed;
    if (!(vt > 0)) {
        vt = 0;
        for (size_t k = 0; k < set.n; ++k)
            if (sd_an_region_has(&r, set.b[k].x))
                vt = fmax(vt, (double)sd_v3_norm(set.b[k].v));
        if (!(vt > 0))
            vt = 1e-300; /* all at rest: everything in bin 0 */
    }
    for (size_t k = 0; k < set.n; ++k) {
        if (!sd_an_region_has(&r, set.b[k].x))
            continue;
        double v = (double)sd_v3_norm(set.b[k].v);
        long c = (long)(v / vt * bins);
        counts[c < 0 ? 0 : c >= bins ? bins - 1 : c]++;
    }
    if (top)
        *top = vt;
    sd_an_free(&set);
    return SD_OK;
}

sd_velocity_field_def sd_velocity_field_def_default(void)
{
    sd_velocity_field_def d;
    memset(&d, 0, sizeof d);
    d.region.kind = SD_REGION_BOX;
    d.plane = 1;
    d.cells[0] = d.cells[1] = 10;
    d.cookie = SD_COOKIE_ANALYSIS;
    return d;
}

sd_status sd_world_velocity_field(const sd_world *w, const sd_velocity_field_def *def, size_t *count, sd_v3d *mean,
                                  sd_error *err)
{
    if (!w || !count || !mean)
        return sd_error_null(err, "sd_world_velocity_field", !w ? "world" : !count ? "count" : "mean");
    if (!def || def->cookie != SD_COOKIE_ANALYSIS)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "sd_velocity_field_def not initialised with sd_velocity_field_def_default");
    if (def->region.kind != SD_REGION_BOX)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "region", "the velocity field needs a box region (the slab)");
    if (def->plane < 0 || def->plane > 2 || def->cells[0] < 1 || def->cells[1] < 1)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "cells", "expected a plane 0..2 and cells >= 1, got %d, [%d, %d]",
                            def->plane, def->cells[0], def->cells[1]);
    if (w->dim2 && def->plane != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "plane", "the planar mode's velocity field lies in the xy plane");
    const int nu = def->cells[0], nv = def->cells[1];
    const int au = def->plane == 2 ? 1 : 0, av = def->plane == 0 ? 1 : 2; /* xy, xz, yz */
    sd_an_region r;
    sd_an_set set;
    sd_status st;
    if ((st = sd_an_region_make(&def->region, w->dim2, &r, err)) != SD_OK || (st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    const double lo[3] = {r.lo.x, r.lo.y, r.lo.z}, hi[3] = {r.hi.x, r.hi.y, r.hi.z};
    size_t cells = (size_t)nu * (size_t)nv;
    memset(count, 0, cells * sizeof *count);
    memset(mean, 0, cells * sizeof *mean);
    for (size_t k = 0; k < set.n; ++k) {
        const sd_an_body *b = &set.b[k];
        if (!sd_an_region_has(&r, b->x))
            continue;
        const double x[3] = {b->x.x, b->x.y, b->x.z};
        long i = (long)((x[au] - lo[au]) / (hi[au] - lo[au]) * nu),
             j = (long)((x[av] - lo[av]) / (hi[av] - lo[av]) * nv);
        i = i < 0 ? 0 : i >= nu ? nu - 1 : i;
        j = j < 0 ? 0 : j >= nv ? nv - 1 : j;
        size_t c = (size_t)i + (size_t)nu * (size_t)j;
        count[c]++;
        mean[c].x += (double)b->v.x, mean[c].y += (double)b->v.y, mean[c].z += (double)b->v.z;
    }
    for (size_t c = 0; c < cells; ++c)
        if (count[c] > 0) {
            double f = 1.0 / (double)count[c];
            mean[c].x *= f, mean[c].y *= f, mean[c].z *= f;
        }
    sd_an_free(&set);
    return SD_OK;
}
