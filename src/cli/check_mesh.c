/* check_mesh.c — the part of `shapedem check`'s run-time estimate that the
 * scene's mesh walls add (see check_mesh.h; issue 31: the timed trial
 * steps the first particles, which seldom touch the mesh yet, and the
 * estimate was 2x low for a filled hopper of shaped grains).
 *
 * Not a cost model either: probe spheres of the scene's largest particle
 * radius are set on the facets (at the centroid of facets spread over the
 * mesh, on the particle side, 5 % of the radius deep, none touching
 * another), with the scene's materials and gravity, and a few steps of
 * them are timed on the run's threads, step by step in turn with the same
 * spheres alone: the difference is what the mesh adds to a particle-step
 * (its facet search and contacts), beyond what the scene's own trial
 * measured for a particle. How many particles of the run
 * lie against the facets is the meshes' area over a particle's footprint
 * (2 r)^2, at most all of them: right for a container filled to the brim
 * (the hopper), high for one with a heap in a corner.
 */
#define _POSIX_C_SOURCE 200809L

#include "cli/check_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/check_report.h"
#include "io/scene.h"

#define SD_MESH_PROBES 200 /* spheres at most in the trial */

static double sd_mesh_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Facet t of mi: its area (m^2), centroid and unit right-hand normal (the
 * particle side of a prepared mesh). */
static double sd_mesh_facet(const sd_mesh_info *mi, size_t t, double c[3], double n[3])
{
    const double *a = mi->vertices + 3 * mi->triangles[t][0], *b = mi->vertices + 3 * mi->triangles[t][1],
                 *d = mi->vertices + 3 * mi->triangles[t][2];
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = d[k] - a[k];
        c[k] = (a[k] + b[k] + d[k]) / 3.0;
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3 && len > 0; ++k)
        n[k] /= len;
    return 0.5 * len;
}

void sd_check_mesh_time(const sd_scene *s, double r, int material, sd_check_mesh_trial *m)
{
    memset(m, 0, sizeof *m);
    sd_world *tw = NULL;
    sd_sphere_def *d = NULL;
    size_t nd = 0;
    int ok = r > 0;
    /* the scene's meshes as it places them at the start, each on its side */
    for (size_t i = 0; ok && i < s->wall_count; ++i) {
        const sd_scene_wall *wl = &s->walls[i];
        if (wl->kind != 2 || wl->mesh_triangle_count == 0)
            continue;
        if (!tw && (tw = sd_check_world(s)) == NULL) {
            ok = 0;
            break;
        }
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = wl->mesh_vertices;
        md.vertex_count = wl->mesh_vertex_count;
        md.triangles = (const uint32_t(*)[3])wl->mesh_triangles;
        md.triangle_count = wl->mesh_triangle_count;
        md.material = wl->material;
        md.outside = wl->outside;
        md.weld_tolerance = wl->weld_tolerance;
        md.coplanar_tolerance = wl->coplanar_tolerance;
        sd_error err;
        memset(&err, 0, sizeof err);
        ok = sd_world_add_mesh(tw, wl->name, &md, &err) >= 0;
    }
    if (ok && tw)
        ok = (d = malloc(SD_MESH_PROBES * sizeof *d)) != NULL;
    /* probes spread over each mesh's prepared facets (their normals point
     * to the particle side), 0.95 r from the facet's plane, none touching
     * another */
    for (size_t k = 0; ok && tw && k < sd_world_wall_count(tw); ++k) {
        sd_mesh_info mi;
        if (sd_world_get_mesh(tw, (int)k, &mi) != SD_OK || mi.triangle_count == 0)
            continue;
        m->meshes++;
        double c[3], n[3];
        for (size_t t = 0; t < mi.triangle_count; ++t)
            m->area += sd_mesh_facet(&mi, t, c, n);
        size_t want = SD_MESH_PROBES / 4;
        for (size_t j = 0; j < want && nd < SD_MESH_PROBES; ++j) {
            size_t t = (size_t)((double)j * (double)mi.triangle_count / (double)want);
            if (!(sd_mesh_facet(&mi, t, c, n) > 0))
                continue;
            sd_v3d x = {c[0] + 0.95 * r * n[0], c[1] + 0.95 * r * n[1], c[2] + 0.95 * r * n[2]};
            int apart = 1;
            for (size_t q = 0; q < nd && apart; ++q) {
                double dx = d[q].position.x - x.x, dy = d[q].position.y - x.y, dz = d[q].position.z - x.z;
                apart = dx * dx + dy * dy + dz * dz >= 4.0 * r * r;
            }
            if (!apart)
                continue;
            memset(&d[nd], 0, sizeof d[nd]);
            d[nd].position = x;
            d[nd].radius = r;
            d[nd].material = material;
            ++nd;
        }
    }
    /* the same spheres alone (no mesh, no other wall): what a particle-step
     * costs without the mesh, in a world as small, so that the fixed cost
     * of a step over a few spheres cancels */
    sd_world *bare = ok && tw && nd > 0 ? sd_check_world(s) : NULL;
    if (bare) {
        double sec[2] = {0, 0};
        long steps = 0;
        sd_world *pair[2] = {tw, bare};
        for (int k = 0; k < 2 && ok; ++k) {
            sd_error err;
            memset(&err, 0, sizeof err);
            ok = sd_world_add_spheres(pair[k], nd, d, &err) == SD_OK && sd_world_prepare(pair[k], &err) == SD_OK;
        }
        /* steps of each in turn, one at a time (the machine's load shared
         * alike): 0.1 s of them, 3 at least, 50 at most */
        double t00 = sd_mesh_now();
        while (ok && steps < 50 && (steps < 3 || sd_mesh_now() - t00 < 0.1)) {
            for (int k = 0; k < 2 && ok; ++k) {
                sd_error err;
                double t0 = sd_mesh_now();
                ok = sd_world_step(pair[k], 1, &err) == SD_OK;
                sec[k] += sd_mesh_now() - t0;
            }
            steps += ok;
        }
        if (ok && steps > 0) {
            m->probes = nd;
            m->steps = steps;
            m->seconds_per_pstep = fmax(0.0, (sec[0] - sec[1]) / ((double)steps * (double)nd));
            m->ok = 1;
        }
        sd_world_destroy(bare);
    }
    free(d);
    sd_world_destroy(tw);
}

void sd_check_mesh_part(sd_check_mesh_trial *m, double r, size_t total, long steps)
{
    if (!m->ok)
        return;
    double against = m->area / (4.0 * r * r);
    m->against = against < (double)total ? (size_t)against : total;
    m->seconds = m->seconds_per_pstep * (double)m->against * (double)steps;
}
