/* check_bounds.c — `shapedem check`'s proportion checks (see check_bounds.h). */
#include "cli/check_bounds.h"

#include <math.h>

#include "cli/check_report.h"
#include "io/scene.h"
#include "io/scene_analysis.h"
#include "io/scene_process.h"

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
        const double *q = mi.rotation, *t = mi.translation;
        for (size_t v = 0; v < mi.vertex_count; ++v) {
            const double *x = mi.vertices + 3 * v;
            /* x' = q x q* + t, q = (w, x, y, z) */
            double uv[3] = {q[2] * x[2] - q[3] * x[1], q[3] * x[0] - q[1] * x[2], q[1] * x[1] - q[2] * x[0]};
            double uuv[3] = {q[2] * uv[2] - q[3] * uv[1], q[3] * uv[0] - q[1] * uv[2], q[1] * uv[1] - q[2] * uv[0]};
            for (int a = 0; a < 3; ++a) {
                double c = x[a] + 2.0 * (q[0] * uv[a] + uuv[a]) + t[a];
                lo[a] = fmin(lo[a], c);
                hi[a] = fmax(hi[a], c);
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
                continue; /* drums and meshes: the run's placement checks drums; meshes are not checked */
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
