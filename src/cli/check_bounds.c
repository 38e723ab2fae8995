/* check_bounds.c — `shapedem check`'s proportion checks (see check_bounds.h). */
#include "cli/check_bounds.h"

#include <math.h>

#include "cli/check_report.h"
#include "io/scene.h"
#include "io/scene_analysis.h"
#include "io/scene_process.h"

/* Mesh-frame point x placed at the start: x' = q x q* + t, q = (w, x, y, z). */
static void sd_check_mesh_place(const sd_mesh_info *mi, const double *x, double out[3])
{
    const double *q = mi->rotation, *t = mi->translation;
    double uv[3] = {q[2] * x[2] - q[3] * x[1], q[3] * x[0] - q[1] * x[2], q[1] * x[1] - q[2] * x[0]};
    double uuv[3] = {q[2] * uv[2] - q[3] * uv[1], q[3] * uv[0] - q[1] * uv[2], q[1] * uv[1] - q[2] * uv[0]};
    for (int a = 0; a < 3; ++a)
        out[a] = x[a] + 2.0 * (q[0] * uv[a] + uuv[a]) + t[a];
}

int sd_check_print_meshes(FILE *f, const sd_world *w, double rmin, double rmax)
{
    int warnings = 0;
    for (size_t k = 0; k < sd_world_wall_count(w); ++k) {
        sd_mesh_info mi;
        if (sd_world_get_mesh(w, (int)k, &mi) != SD_OK || mi.vertex_count == 0)
            continue; /* not a mesh wall */
        sd_wall_info wi;
        const char *name = sd_world_get_wall(w, k, &wi) == SD_OK && wi.name ? wi.name : "?";
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        /* the box as placed at the start (rotation and translation of the pose) */
        for (size_t v = 0; v < mi.vertex_count; ++v) {
            double c[3];
            sd_check_mesh_place(&mi, mi.vertices + 3 * v, c);
            for (int a = 0; a < 3; ++a) {
                lo[a] = fmin(lo[a], c[a]);
                hi[a] = fmax(hi[a], c[a]);
            }
        }
        double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
        fprintf(f, "mesh         %s: %zu facets, box [%.4g, %.4g, %.4g] to [%.4g, %.4g, %.4g] m, %.4g m across", name,
                mi.triangle_count, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], size);
        if (rmax > 0)
            fprintf(f, " (%.3g particle diameters)", size / (2.0 * rmax));
        fprintf(f, "\n");
        if (!(rmax > 0))
            continue;
        double dmax = 2.0 * rmax, dmin = 2.0 * (rmin > 0 ? rmin : rmax);
        if (size > SD_CHECK_MESH_LARGE * dmax || size < dmin / SD_CHECK_MESH_SMALL) {
            fprintf(f,
                    "warning      mesh %s is %.4g m across, %.3g times the %s particle diameter (%.4g m): check the "
                    "units (`scale:`; scene values are metres, a mesh drawn in millimetres needs scale: 0.001)\n",
                    name, size, size > SD_CHECK_MESH_LARGE * dmax ? size / dmax : size / dmin,
                    size > SD_CHECK_MESH_LARGE * dmax ? "largest" : "smallest",
                    size > SD_CHECK_MESH_LARGE * dmax ? dmax : dmin);
            warnings++;
        }
    }
    return warnings;
}

int sd_check_print_analysis_size(FILE *f, const sd_scene *s, long steps)
{
    size_t files = 0;
    double bytes = sd_analysis_estimate_bytes(s, steps, &files);
    if (!files)
        return 0;
    char b[32];
    sd_check_format_bytes(bytes, b, sizeof b);
    fprintf(f, "analysis     about %s in %zu file%s (rows of all bins at every output)\n", b, files,
            files > 1 ? "s" : "");
    if (bytes > SD_CHECK_ANALYSIS_LARGE) {
        fprintf(f, "warning      the analysis files would hold about %s: fewer bins or cells, or a larger every:\n",
                b);
        return 1;
    }
    return 0;
}

/* 1 when triangle v (3 corners, 9 numbers) and the box [lo, hi] meet: no
 * separating axis among the box's 3 normals, the triangle's normal and the
 * 9 products of an edge with a box axis (Akenine-Moeller's test, 2001). */
static int sd_tri_box_meet(const double v[9], const double lo[3], const double hi[3])
{
    double c[3], h[3], p[3][3], e[3][3];
    for (int a = 0; a < 3; ++a) {
        c[a] = 0.5 * (lo[a] + hi[a]);
        h[a] = 0.5 * (hi[a] - lo[a]);
        for (int k = 0; k < 3; ++k)
            p[k][a] = v[3 * k + a] - c[a];
    }
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
            e[k][a] = p[(k + 1) % 3][a] - p[k][a];
    double axes[13][3];
    int n = 0;
    for (int a = 0; a < 3; ++a, ++n)
        for (int b = 0; b < 3; ++b)
            axes[n][b] = a == b;
    axes[n][0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    axes[n][1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    axes[n][2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    ++n;
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a, ++n) { /* e_k x unit axis a */
            double u[3] = {0, 0, 0};
            u[a] = 1;
            axes[n][0] = e[k][1] * u[2] - e[k][2] * u[1];
            axes[n][1] = e[k][2] * u[0] - e[k][0] * u[2];
            axes[n][2] = e[k][0] * u[1] - e[k][1] * u[0];
        }
    for (int q = 0; q < n; ++q) {
        const double *ax = axes[q];
        double r = h[0] * fabs(ax[0]) + h[1] * fabs(ax[1]) + h[2] * fabs(ax[2]);
        double t0 = ax[0] * p[0][0] + ax[1] * p[0][1] + ax[2] * p[0][2], tmin = t0, tmax = t0;
        for (int k = 1; k < 3; ++k) {
            double t = ax[0] * p[k][0] + ax[1] * p[k][1] + ax[2] * p[k][2];
            tmin = fmin(tmin, t);
            tmax = fmax(tmax, t);
        }
        if (tmin > r || tmax < -r)
            return 0;
    }
    return 1;
}

/* The facets of mesh wall `wall` (placed at the start) that meet the box
 * [lo, hi]; -1 when the wall is no mesh. */
static long sd_check_mesh_crossing(const sd_world *w, size_t wall, const double lo[3], const double hi[3])
{
    sd_mesh_info mi;
    if (sd_world_get_mesh(w, (int)wall, &mi) != SD_OK || mi.vertex_count == 0)
        return -1;
    long count = 0;
    for (size_t t = 0; t < mi.triangle_count; ++t) {
        double v[9];
        for (int k = 0; k < 3; ++k)
            sd_check_mesh_place(&mi, mi.vertices + 3 * mi.triangles[t][k], v + 3 * k);
        count += sd_tri_box_meet(v, lo, hi);
    }
    return count;
}

int sd_check_print_regions(FILE *f, const sd_scene *s, const sd_world *w)
{
    const sd_scene_process *sp = s->process;
    if (!sp)
        return 0;
    static const char *const faces[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    int warnings = 0, dim = s->world.dimension == 2 ? 2 : 3;
    for (size_t i = 0; i < sp->insert_count; ++i) {
        double lo[3], hi[3];
        sd_region_box(&sp->inserts[i].region, lo, hi);
        const char *name = sp->insert_names[i][0] ? sp->insert_names[i] : "(unnamed)";
        for (size_t k = 0; k < sd_world_wall_count(w); ++k) {
            sd_wall_info wi;
            if (sd_world_get_wall(w, k, &wi) != SD_OK)
                continue;
            /* how far the region's box reaches past the wall, and how much
             * of it lies past (all: no particle fits) */
            double beyond = 0, inside = HUGE_VAL;
            const char *where = "";
            if (wi.kind == 0) {
                const double n[3] = {wi.normal.x, wi.normal.y, wi.normal.z}, p[3] = {wi.point.x, wi.point.y,
                                                                                    wi.point.z};
                double dmin = 0, dmax = 0;
                for (int a = 0; a < 3; ++a) {
                    dmin += n[a] * ((n[a] >= 0 ? lo[a] : hi[a]) - p[a]);
                    dmax += n[a] * ((n[a] >= 0 ? hi[a] : lo[a]) - p[a]);
                }
                beyond = -dmin;
                inside = dmax;
                where = "behind plane";
            } else if (wi.kind == 1) {
                const double wl[3] = {wi.lo.x, wi.lo.y, wi.lo.z}, wh[3] = {wi.hi.x, wi.hi.y, wi.hi.z};
                for (int a = 0; a < dim; ++a) {
                    if (!(wi.open_faces & (1u << (2 * a)))) {
                        if (wl[a] - lo[a] > beyond) {
                            beyond = wl[a] - lo[a];
                            where = faces[2 * a];
                        }
                        inside = fmin(inside, hi[a] - wl[a]);
                    }
                    if (!(wi.open_faces & (1u << (2 * a + 1)))) {
                        if (hi[a] - wh[a] > beyond) {
                            beyond = hi[a] - wh[a];
                            where = faces[2 * a + 1];
                        }
                        inside = fmin(inside, wh[a] - lo[a]);
                    }
                }
            } else {
                /* a mesh: its facets inside the region's box; the placement
                 * keeps particles clear of them (and inside a closed
                 * container, outside a closed obstacle: world/mesh_clear.c) */
                long crossing = sd_check_mesh_crossing(w, k, lo, hi);
                if (crossing > 0) {
                    fprintf(f,
                            "warning      insertion %s: its region crosses mesh wall '%s' (%ld facet%s inside its "
                            "box): particles are placed only clear of the facets and on the particles' side of "
                            "the mesh, so part of the region is not used\n",
                            name, wi.name ? wi.name : "?", crossing, crossing > 1 ? "s" : "");
                    warnings++;
                }
                continue; /* drums: the run's placement checks them */
            }
            if (!(beyond > 0))
                continue;
            if (!(inside > 0))
                fprintf(f,
                        "warning      insertion %s: its region lies outside wall '%s' (%s%s): no particle can be "
                        "placed there\n",
                        name, wi.name ? wi.name : "?", wi.kind == 1 ? "beyond its closed face " : "", where);
            else
                fprintf(f,
                        "warning      insertion %s: its region reaches %.4g m %s%s of wall '%s': particles are placed "
                        "only inside the walls, so that part is not used\n",
                        name, beyond, wi.kind == 1 ? "beyond the closed face " : "", where, wi.name ? wi.name : "?");
            warnings++;
        }
    }
    return warnings;
}
