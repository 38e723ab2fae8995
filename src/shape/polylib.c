/* polylib.c — the built-in polyhedra (see polylib.h).
 *
 * Invariant: every preset's vertices lie on (random faces: within) the
 * circumscribed sphere of the given diameter, centred at the origin, and
 * the set depends only on the def (the seed included), never on the host.
 * Seed 000 §3.1 gives the cylinder template (42 vertices, 80 triangles).
 */
#include "shape/polylib.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"
#include "geom/hull.h"

static const char *const sd_poly_names[] = {
#define SD_X_NAME(e, name, doc) name,
    SD_POLY_PRESETS(SD_X_NAME)
#undef SD_X_NAME
};

const char *sd_polylib_name(int preset)
{
    return preset >= 0 && preset < SD_POLY_PRESET_COUNT ? sd_poly_names[preset] : "unknown";
}

int sd_polylib_from_name(const char *name)
{
    for (int k = 0; name && k < SD_POLY_PRESET_COUNT; ++k)
        if (strcmp(name, sd_poly_names[k]) == 0)
            return k;
    return -1;
}

double sd_polylib_edge_to_diameter(int preset, double a)
{
    /* circumradius / edge of the regular solids */
    switch (preset) {
    case SD_POLY_TETRAHEDRON:
        return 2.0 * a * sqrt(6.0) / 4.0;
    case SD_POLY_CUBE:
        return 2.0 * a * sqrt(3.0) / 2.0;
    case SD_POLY_OCTAHEDRON:
        return 2.0 * a / sqrt(2.0);
    case SD_POLY_DODECAHEDRON:
        return 2.0 * a * sqrt(3.0) * (1.0 + sqrt(5.0)) / 4.0;
    case SD_POLY_ICOSAHEDRON:
        return 2.0 * a * sqrt(10.0 + 2.0 * sqrt(5.0)) / 4.0;
    default:
        return 0.0;
    }
}

size_t sd_polylib_vertex_count(const sd_poly_def *d)
{
    switch (d->preset) {
    case SD_POLY_TETRAHEDRON:
        return 4;
    case SD_POLY_CUBE:
        return 8;
    case SD_POLY_OCTAHEDRON:
        return 6;
    case SD_POLY_DODECAHEDRON:
        return 20;
    case SD_POLY_ICOSAHEDRON:
        return 12;
    case SD_POLY_PRISM:
        return d->sides >= 3 && d->sides <= SD_POLY_MAX_SIDES ? 2 * (size_t)d->sides : 0;
    case SD_POLY_CYLINDER:
        return d->sides >= 3 && d->sides <= SD_POLY_MAX_SIDES ? 2 * (size_t)d->sides + 2 : 0;
    case SD_POLY_RANDOM:
        if (d->points >= 4 && d->points <= SD_POLY_MAX_RANDOM && d->faces == 0)
            return (size_t)d->points;
        if (d->faces >= 4 && d->faces <= SD_POLY_MAX_RANDOM && d->points == 0)
            return 2 * (size_t)d->faces - 4;
        return 0;
    default:
        return 0;
    }
}

static void sd_put(sd_v3d *o, double x, double y, double z)
{
    o->x = x;
    o->y = y;
    o->z = z;
}

/* a uniform unit vector (z uniform in [-1, 1], angle uniform: Archimedes) */
static sd_vec3 sd_rand_dir(sd_rng *r)
{
    double z = sd_rng_range(r, -1.0, 1.0), ph = sd_rng_range(r, 0.0, 2.0 * SD_PI_D);
    double s = sqrt(fmax(0.0, 1.0 - z * z));
    return sd_v3((sd_real)(s * cos(ph)), (sd_real)(s * sin(ph)), (sd_real)z);
}

/* F planes n . x = 1 at random unit normals: the vertices are the polar
 * images of the triangles of the normals' hull (every triangle of the hull
 * of points on a sphere is a vertex where three planes meet). Bounded when
 * the normals surround the origin; otherwise draw again. */
static sd_status sd_random_faces(const sd_poly_def *d, sd_v3d *out, size_t *count, sd_error *err)
{
    sd_hull_workspace *ws = sd_malloc(sizeof *ws);
    sd_hull *h = sd_malloc(sizeof *h);
    sd_vec3 *n = sd_malloc((size_t)d->faces * sizeof *n);
    sd_status st = SD_OK;
    if (!ws || !h || !n) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory making a random polyhedron");
        goto done;
    }
    sd_rng r = sd_rng_seed(d->seed);
    int ok = 0;
    for (int attempt = 0; attempt < 1000 && !ok; ++attempt) {
        for (int k = 0; k < d->faces; ++k)
            n[k] = sd_rand_dir(&r);
        if (sd_hull_build(n, (size_t)d->faces, ws, h) != SD_HULL_OK || h->nvert != d->faces ||
            h->ntri != 2 * d->faces - 4)
            continue;
        ok = 1;
        for (int t = 0; t < h->ntri; ++t)
            ok &= h->offset[t] > SD_R(1e-3); /* the origin well inside: bounded, no far vertex */
    }
    if (!ok) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "faces", "no bounded random polyhedron with %d faces", d->faces);
        goto done;
    }
    double rmax = 0;
    for (int t = 0; t < h->ntri; ++t) {
        /* the plane of the hull triangle is m . y = c: its polar point m / c
         * is where the three planes n_i . x = 1 meet */
        sd_vec3 v = sd_v3_scale(h->normal[t], SD_R(1.0) / h->offset[t]);
        sd_put(&out[t], (double)v.x, (double)v.y, (double)v.z);
        rmax = fmax(rmax, (double)sd_v3_norm(v));
    }
    for (int t = 0; t < h->ntri; ++t) {
        double k = 0.5 * d->diameter / rmax;
        sd_put(&out[t], out[t].x * k, out[t].y * k, out[t].z * k);
    }
    *count = (size_t)h->ntri;
done:
    sd_free(ws);
    sd_free(h);
    sd_free(n);
    return st;
}

sd_status sd_polylib_vertices(const sd_poly_def *d, sd_v3d *out, size_t cap, size_t *count, sd_error *err)
{
    *count = 0;
    if (d->preset < 0 || d->preset >= SD_POLY_PRESET_COUNT)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "preset", "unknown polyhedron preset %d", d->preset);
    if (!(isfinite(d->diameter) && d->diameter > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "size", "the size must be > 0 m, got %g", d->diameter);
    if (d->preset == SD_POLY_PRISM || d->preset == SD_POLY_CYLINDER) {
        if (d->sides < 3 || d->sides > SD_POLY_MAX_SIDES)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "sides", "expected 3 to %d sides, got %d", SD_POLY_MAX_SIDES,
                                d->sides);
        if (!(isfinite(d->length) && d->length > 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "length", "the length must be > 0 m, got %g", d->length);
    }
    if (d->preset == SD_POLY_RANDOM) {
        if ((d->points > 0) == (d->faces > 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "points",
                                "a random polyhedron needs exactly one of points and faces");
        int k = d->points > 0 ? d->points : d->faces;
        if (k < 4 || k > SD_POLY_MAX_RANDOM)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, d->points > 0 ? "points" : "faces",
                                "expected 4 to %d %s, got %d", SD_POLY_MAX_RANDOM, d->points > 0 ? "points" : "faces",
                                k);
    }
    size_t need = sd_polylib_vertex_count(d);
    if (need > cap)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "preset", "room for %zu vertices, the preset needs %zu", cap,
                            need);
    const double R = 0.5 * d->diameter;
    const double phi = 0.5 * (1.0 + sqrt(5.0)), iphi = 1.0 / phi;
    size_t m = 0;
    switch (d->preset) {
    case SD_POLY_TETRAHEDRON:
        sd_put(&out[m++], 1, 1, 1);
        sd_put(&out[m++], 1, -1, -1);
        sd_put(&out[m++], -1, 1, -1);
        sd_put(&out[m++], -1, -1, 1);
        break;
    case SD_POLY_CUBE:
        for (int k = 0; k < 8; ++k)
            sd_put(&out[m++], k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
        break;
    case SD_POLY_OCTAHEDRON:
        for (int a = 0; a < 3; ++a)
            for (int s = -1; s <= 1; s += 2)
                sd_put(&out[m++], a == 0 ? s : 0, a == 1 ? s : 0, a == 2 ? s : 0);
        break;
    case SD_POLY_DODECAHEDRON:
        for (int k = 0; k < 8; ++k)
            sd_put(&out[m++], k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
        for (int k = 0; k < 4; ++k) {
            double s1 = k & 1 ? 1 : -1, s2 = k & 2 ? 1 : -1;
            sd_put(&out[m++], 0, s1 * iphi, s2 * phi);
            sd_put(&out[m++], s1 * iphi, s2 * phi, 0);
            sd_put(&out[m++], s1 * phi, 0, s2 * iphi);
        }
        break;
    case SD_POLY_ICOSAHEDRON:
        for (int k = 0; k < 4; ++k) {
            double s1 = k & 1 ? 1 : -1, s2 = k & 2 ? 1 : -1;
            sd_put(&out[m++], 0, s1, s2 * phi);
            sd_put(&out[m++], s1, s2 * phi, 0);
            sd_put(&out[m++], s1 * phi, 0, s2);
        }
        break;
    case SD_POLY_PRISM:
    case SD_POLY_CYLINDER:
        for (int k = 0; k < d->sides; ++k) {
            double a = 2.0 * SD_PI_D * k / d->sides;
            sd_put(&out[m++], R * cos(a), R * sin(a), -0.5 * d->length);
            sd_put(&out[m++], R * cos(a), R * sin(a), 0.5 * d->length);
        }
        if (d->preset == SD_POLY_CYLINDER) {
            sd_put(&out[m++], 0, 0, -0.5 * d->length);
            sd_put(&out[m++], 0, 0, 0.5 * d->length);
        }
        *count = m;
        return SD_OK;
    case SD_POLY_RANDOM:
        if (d->faces > 0)
            return sd_random_faces(d, out, count, err);
        {
            sd_rng r = sd_rng_seed(d->seed);
            for (int k = 0; k < d->points; ++k) {
                sd_vec3 u = sd_rand_dir(&r);
                sd_put(&out[m++], R * (double)u.x, R * (double)u.y, R * (double)u.z);
            }
        }
        *count = m;
        return SD_OK;
    default:
        break;
    }
    /* the Platonic sets above are centred with every vertex at one radius:
     * scale that radius to R */
    double r0 = sqrt(out[0].x * out[0].x + out[0].y * out[0].y + out[0].z * out[0].z);
    for (size_t k = 0; k < m; ++k)
        sd_put(&out[k], out[k].x * R / r0, out[k].y * R / r0, out[k].z * R / r0);
    *count = m;
    return SD_OK;
}

double sd_mesh_concavity(const sd_v3d *pts, size_t n, const sd_v3d *centres, size_t nc, size_t *which, double *size)
{
    *which = 0;
    *size = 0;
    if (n < 4 || n > SD_HULL_MAX_POINTS)
        return -1;
    sd_hull_workspace *ws = sd_malloc(sizeof *ws);
    sd_hull *h = sd_malloc(sizeof *h);
    sd_vec3 *p = sd_malloc(n * sizeof *p);
    double worst = -1;
    if (!ws || !h || !p) {
        worst = -2;
        goto done;
    }
    for (size_t k = 0; k < n; ++k)
        p[k] = sd_v3((sd_real)pts[k].x, (sd_real)pts[k].y, (sd_real)pts[k].z);
    if (sd_hull_build(p, n, ws, h) != SD_HULL_OK)
        goto done;
    double diam = 0;
    for (int a = 0; a < h->nvert; ++a)
        for (int b = a + 1; b < h->nvert; ++b)
            diam = fmax(diam, (double)sd_v3_norm(sd_v3_sub(p[h->vert[a]], p[h->vert[b]])));
    *size = diam;
    worst = 0;
    for (size_t k = 0; k < n + nc; ++k) {
        const sd_v3d *q = k < n ? &pts[k] : &centres[k - n];
        /* depth below the hull's boundary: the smallest distance to a face
         * plane (every point is inside all of them, up to the hull's eps) */
        double depth = 1e300;
        for (int t = 0; t < h->ntri; ++t) {
            sd_vec3 nn = h->normal[t];
            depth =
                fmin(depth, (double)h->offset[t] - ((double)nn.x * q->x + (double)nn.y * q->y + (double)nn.z * q->z));
        }
        if (depth > worst) {
            worst = depth;
            *which = k;
        }
    }
done:
    sd_free(ws);
    sd_free(h);
    sd_free(p);
    return worst;
}
