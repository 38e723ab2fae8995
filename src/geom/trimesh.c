/* trimesh.c — mesh preparation for mesh walls (see trimesh.h for the rule).
 *
 * Seed 000 §2.4 contacts a body with the facets of a wall mesh, weighting
 * each facet by its overlap area; a body crossing the seam of two coplanar
 * facets, or resting in a concave fold, must feel one smooth force, which
 * needs the connectivity this file derives once: welded vertices, a
 * consistent winding, plane groups, and the edges and corners that may
 * make contacts of their own (active) or not (inactive).
 *
 * Invariant: all or nothing (an error leaves *out empty), and the result
 * depends on the input arrays only: every sort breaks ties by index and
 * every traversal starts at the lowest-numbered facet.
 */
#include "geom/trimesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

#define SD_TM_OOM(err) sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory preparing a mesh")

typedef struct sd_tm_v {
    double x, y, z;
} sd_tm_v;

static sd_tm_v sd_tm_sub(sd_tm_v a, sd_tm_v b)
{
    return (sd_tm_v){a.x - b.x, a.y - b.y, a.z - b.z};
}
static sd_tm_v sd_tm_cross(sd_tm_v a, sd_tm_v b)
{
    return (sd_tm_v){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static double sd_tm_dot(sd_tm_v a, sd_tm_v b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static double sd_tm_norm(sd_tm_v a)
{
    return sqrt(sd_tm_dot(a, a));
}

/* ---- welding: a hash of cells of edge h >= weld_tol ---- */

typedef struct sd_tm_cell {
    int64_t i, j, k;
    int64_t head; /* first representative vertex in the cell, -1 = empty slot */
} sd_tm_cell;

static uint64_t sd_tm_hash(int64_t i, int64_t j, int64_t k)
{
    uint64_t h =
        (uint64_t)i * 0x9E3779B97F4A7C15u ^ (uint64_t)j * 0xC2B2AE3D27D4EB4Fu ^ (uint64_t)k * 0x165667B19E3779F9u;
    return h ^ (h >> 29);
}

/* The slot of cell (i, j, k): its own, or the empty one where it would go. */
static size_t sd_tm_slot(const sd_tm_cell *c, size_t mask, int64_t i, int64_t j, int64_t k)
{
    size_t s = (size_t)sd_tm_hash(i, j, k) & mask;
    while (c[s].head >= 0 && (c[s].i != i || c[s].j != j || c[s].k != k))
        s = (s + 1) & mask;
    return s;
}

/* map[v] = the vertex v is welded to (the lowest-numbered representative
 * within tol; v itself when none). Returns 0 when out of memory. */
static int sd_tm_weld(const sd_tm_v *p, size_t nv, double tol, double h, uint32_t *map)
{
    size_t cap = 16;
    while (cap < 2 * nv + 16)
        cap *= 2;
    sd_tm_cell *cells = sd_malloc(cap * sizeof *cells);
    int64_t *next = sd_malloc((nv ? nv : 1) * sizeof *next);
    if (!cells || !next) {
        sd_free(cells);
        sd_free(next);
        return 0;
    }
    for (size_t s = 0; s < cap; ++s)
        cells[s].head = -1;
    size_t mask = cap - 1;
    double tol2 = tol * tol;
    for (size_t v = 0; v < nv; ++v) {
        int64_t ci = (int64_t)floor(p[v].x / h), cj = (int64_t)floor(p[v].y / h), ck = (int64_t)floor(p[v].z / h);
        int64_t best = -1;
        for (int64_t di = -1; di <= 1; ++di)
            for (int64_t dj = -1; dj <= 1; ++dj)
                for (int64_t dk = -1; dk <= 1; ++dk) {
                    size_t s = sd_tm_slot(cells, mask, ci + di, cj + dj, ck + dk);
                    for (int64_t r = cells[s].head; r >= 0; r = next[r]) {
                        sd_tm_v d = sd_tm_sub(p[v], p[r]);
                        if (sd_tm_dot(d, d) <= tol2 && (best < 0 || r < best))
                            best = r;
                    }
                }
        if (best >= 0) {
            map[v] = (uint32_t)best;
            continue;
        }
        map[v] = (uint32_t)v;
        size_t s = sd_tm_slot(cells, mask, ci, cj, ck);
        if (cells[s].head < 0) {
            cells[s].i = ci;
            cells[s].j = cj;
            cells[s].k = ck;
            next[v] = -1;
        } else {
            next[v] = cells[s].head;
        }
        cells[s].head = (int64_t)v;
    }
    sd_free(cells);
    sd_free(next);
    return 1;
}

/* ---- sorting keys ---- */

typedef struct sd_tm_key {
    uint32_t a, b, c; /* sorted vertex triple (duplicates) or (lo, hi, 0) (edges) */
    uint32_t tri, k;  /* triangle and its corner/edge number */
} sd_tm_key;

static int sd_tm_key_cmp(const void *pa, const void *pb)
{
    const sd_tm_key *x = pa, *y = pb;
    if (x->a != y->a)
        return x->a < y->a ? -1 : 1;
    if (x->b != y->b)
        return x->b < y->b ? -1 : 1;
    if (x->c != y->c)
        return x->c < y->c ? -1 : 1;
    if (x->tri != y->tri)
        return x->tri < y->tri ? -1 : 1;
    return x->k < y->k ? -1 : x->k > y->k;
}

static void sd_tm_sort3(uint32_t v[3])
{
    uint32_t t;
    if (v[0] > v[1]) {
        t = v[0];
        v[0] = v[1];
        v[1] = t;
    }
    if (v[1] > v[2]) {
        t = v[1];
        v[1] = v[2];
        v[2] = t;
    }
    if (v[0] > v[1]) {
        t = v[0];
        v[0] = v[1];
        v[1] = t;
    }
}

/* The edge records of triangles tri[0 .. n), sorted: edge k of triangle
 * j runs from corner k to corner k+1. */
static sd_tm_key *sd_tm_edges(const uint32_t (*tri)[3], size_t n)
{
    sd_tm_key *e = sd_malloc((n ? 3 * n : 1) * sizeof *e);
    if (!e)
        return NULL;
    for (size_t j = 0; j < n; ++j)
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t a = tri[j][k], b = tri[j][(k + 1) % 3];
            e[3 * j + k] = (sd_tm_key){a < b ? a : b, a < b ? b : a, 0, (uint32_t)j, k};
        }
    qsort(e, 3 * n, sizeof *e, sd_tm_key_cmp);
    return e;
}

/* nbr[3 j + k]: the triangle across edge k of triangle j, -1 for a
 * boundary edge, -2 for a non-manifold one; same[3 j + k] = 1 when that
 * neighbour runs the edge in the same direction (windings disagree). */
static size_t sd_tm_adjacency(const uint32_t (*tri)[3], const sd_tm_key *e, size_t n, int64_t *nbr, uint8_t *same)
{
    size_t nonmanifold = 0;
    for (size_t s = 0; s < 3 * n;) {
        size_t r = s + 1;
        while (r < 3 * n && e[r].a == e[s].a && e[r].b == e[s].b)
            ++r;
        for (size_t q = s; q < r; ++q) {
            size_t slot = 3 * (size_t)e[q].tri + e[q].k;
            nbr[slot] = r - s == 1 ? -1 : -2;
            same[slot] = 0;
        }
        if (r - s == 2) {
            const sd_tm_key *x = &e[s], *y = &e[s + 1];
            int same_dir = tri[x->tri][x->k] == tri[y->tri][y->k];
            nbr[3 * (size_t)x->tri + x->k] = y->tri;
            nbr[3 * (size_t)y->tri + y->k] = x->tri;
            same[3 * (size_t)x->tri + x->k] = (uint8_t)same_dir;
            same[3 * (size_t)y->tri + y->k] = (uint8_t)same_dir;
        } else if (r - s > 2) {
            ++nonmanifold;
        }
        s = r;
    }
    return nonmanifold;
}

/* The refusal of a mesh whose size makes its squares overflow or underflow. */
static sd_status sd_tm_fail_free(sd_error *err, double big, double diag, void *a, void *b, void *c, void *d, void *e,
                                 void *f, void *g)
{
    sd_free(a);
    sd_free(b);
    sd_free(c);
    sd_free(d);
    sd_free(e);
    sd_free(f);
    sd_free(g);
    return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                        "the mesh's coordinates reach %g m and its bounding box is %g m across: outside "
                        "[1e-100, 1e100] m, wrong units (check scale:)",
                        big, diag);
}

void sd_trimesh_free(sd_trimesh *m)
{
    if (!m)
        return;
    sd_free(m->vertices);
    sd_free(m->triangles);
    sd_free(m->group);
    sd_free(m->flags);
    sd_free(m->group_normal);
    sd_free(m->group_offset);
    sd_free(m->source);
    sd_free(m->nbr);
    memset(m, 0, sizeof *m);
}

sd_status sd_trimesh_build(const sd_v3d *v, size_t nv, const uint32_t (*t)[3], size_t nt, double weld_tol,
                           double coplanar_tol, sd_trimesh *out, sd_trimesh_report *rep, sd_error *err)
{
    return sd_trimesh_build_side(v, nv, t, nt, weld_tol, coplanar_tol, SD_TRIMESH_INSIDE, out, rep, err);
}

sd_status sd_trimesh_build_side(const sd_v3d *v, size_t nv, const uint32_t (*t)[3], size_t nt, double weld_tol,
                                double coplanar_tol, int side, sd_trimesh *out, sd_trimesh_report *rep, sd_error *err)
{
    sd_trimesh_report local;
    if (!rep)
        rep = &local;
    memset(rep, 0, sizeof *rep);
    memset(out, 0, sizeof *out);
    if (nv >= UINT32_MAX || nt >= UINT32_MAX / 3)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "a mesh of %zu vertices and %zu facets is too large", nv, nt);
    if (nt == 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the mesh has no facets");
    if (!(weld_tol >= 0.0) || !isfinite(weld_tol) || !(coplanar_tol >= 0.0) || !(coplanar_tol < 1.0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "weld tolerance %g m and coplanar tolerance %g rad: expected >= 0 (and < 1 rad)", weld_tol,
                            coplanar_tol);
    for (size_t j = 0; j < nt; ++j)
        for (int k = 0; k < 3; ++k)
            if (t[j][k] >= nv)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                                    "facet %zu names vertex %u, but the mesh has %zu vertices", j + 1,
                                    (unsigned)t[j][k] + 1, nv);
    for (size_t i = 0; i < nv; ++i)
        if (!isfinite(v[i].x) || !isfinite(v[i].y) || !isfinite(v[i].z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "vertex %zu is (%g, %g, %g), not finite", i + 1, v[i].x,
                                v[i].y, v[i].z);
    if (coplanar_tol == 0.0)
        coplanar_tol = 1e-6;

    sd_status st = SD_OK;
    sd_tm_v *p = sd_malloc(nv * sizeof *p);
    uint32_t *map = sd_malloc(nv * sizeof *map), *newv = sd_malloc(nv * sizeof *newv);
    uint32_t(*tri)[3] = sd_malloc(nt * sizeof *tri);
    uint32_t *src = sd_malloc(nt * sizeof *src);
    sd_tm_key *keys = sd_malloc(nt * sizeof *keys);
    uint8_t *drop = sd_calloc(nt, 1);
    sd_tm_key *edges = NULL;
    int64_t *nbr = NULL, *queue = NULL;
    uint8_t *same = NULL, *flip = NULL, *vactive = NULL;
    int64_t *part = NULL;
    sd_tm_v *tn = NULL;
    if (!p || !map || !newv || !tri || !src || !keys || !drop) {
        st = SD_TM_OOM(err);
        goto done;
    }

    /* 1. weld */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, big = 0.0;
    for (size_t i = 0; i < nv; ++i) {
        p[i] = (sd_tm_v){v[i].x, v[i].y, v[i].z};
        double c[3] = {v[i].x, v[i].y, v[i].z};
        for (int a = 0; a < 3; ++a) {
            lo[a] = fmin(lo[a], c[a]);
            hi[a] = fmax(hi[a], c[a]);
            big = fmax(big, fabs(c[a]));
        }
    }
    double diag =
        sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    /* squares of lengths (areas, dot products) must stay finite and normal;
     * the extent, not diag, tells a tiny mesh: diag's squares underflow to
     * 0 below 1e-154 m (a mesh scaled by 1e-300) */
    double extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(big <= 1e100) || (extent > 0.0 && !(extent >= 1e-100)))
        return sd_tm_fail_free(err, big, diag > 0.0 ? diag : extent, p, map, newv, tri, src, keys, drop);
    double tol = weld_tol > 0.0 ? weld_tol : 1e-9 * diag;
    /* cells no finer than 1e-15 of the coordinates, so cell numbers fit in 64 bits */
    double h = fmax(tol, 1e-15 * big);
    if (!(h > 0.0))
        h = 1.0;
    if (!sd_tm_weld(p, nv, tol, h, map)) {
        st = SD_TM_OOM(err);
        goto done;
    }
    for (size_t i = 0; i < nv; ++i)
        rep->welded += map[i] != i;

    /* 2. degenerate facets: corners welded together, or a height below tol */
    size_t nk = 0;
    for (size_t j = 0; j < nt; ++j) {
        uint32_t a = map[t[j][0]], b = map[t[j][1]], c = map[t[j][2]];
        int bad = a == b || b == c || c == a;
        if (!bad) {
            sd_tm_v e0 = sd_tm_sub(p[b], p[a]), e1 = sd_tm_sub(p[c], p[b]), e2 = sd_tm_sub(p[a], p[c]);
            double lmax = fmax(sd_tm_norm(e0), fmax(sd_tm_norm(e1), sd_tm_norm(e2)));
            /* |e0 x e2| is twice the area; over the longest edge, the least height */
            bad = !(sd_tm_norm(sd_tm_cross(e0, e2)) > tol * lmax) || !(lmax > 0.0);
        }
        if (bad) {
            drop[j] = 1;
            if (!rep->degenerate++)
                rep->first_degenerate = j + 1;
            continue;
        }
        uint32_t s3[3] = {a, b, c};
        sd_tm_sort3(s3);
        keys[nk++] = (sd_tm_key){s3[0], s3[1], s3[2], (uint32_t)j, 0};
    }
    /* duplicates: the same three welded vertices, any order; the first stays */
    qsort(keys, nk, sizeof *keys, sd_tm_key_cmp);
    for (size_t s = 1; s < nk; ++s)
        if (keys[s].a == keys[s - 1].a && keys[s].b == keys[s - 1].b && keys[s].c == keys[s - 1].c) {
            drop[keys[s].tri] = 1;
            ++rep->duplicates;
            if (!rep->first_duplicate || keys[s].tri + 1 < rep->first_duplicate)
                rep->first_duplicate = keys[s].tri + 1;
        }
    /* compact: kept facets in input order; vertices in order of their index */
    for (size_t i = 0; i < nv; ++i)
        newv[i] = UINT32_MAX;
    size_t n = 0;
    for (size_t j = 0; j < nt; ++j)
        if (!drop[j])
            for (int k = 0; k < 3; ++k)
                newv[map[t[j][k]]] = 0;
    size_t nvo = 0;
    for (size_t i = 0; i < nv; ++i)
        if (newv[i] == 0)
            newv[i] = (uint32_t)nvo++;
    for (size_t j = 0; j < nt; ++j)
        if (!drop[j]) {
            for (int k = 0; k < 3; ++k)
                tri[n][k] = newv[map[t[j][k]]];
            src[n++] = (uint32_t)j;
        }
    if (n == 0) {
        if (rep->degenerate == nt && weld_tol <= 0.0 && diag > 0.0)
            /* the weld tolerance is 1e-9 of the box: a box made huge by one
             * stray vertex, or in the wrong units, welds the rest into one */
            st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                              "no facet is left: all %zu are degenerate at the weld tolerance %g m (1e-9 of the "
                              "bounding box, %g m across, coordinates up to %g m): a vertex far from the others, or "
                              "wrong units (check scale:)",
                              nt, tol, diag, big);
        else
            st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                              "no facet is left: all %zu are degenerate (zero area) or duplicates", nt);
        goto done;
    }
    /* positions of the kept vertices, in the output numbering */
    for (size_t i = 0, o = 0; i < nv; ++i)
        if (newv[i] != UINT32_MAX && map[i] == i)
            p[o++] = p[i]; /* o <= i: safe in place */

    /* 3. orientation, part by part */
    edges = sd_tm_edges((const uint32_t(*)[3])tri, n);
    nbr = sd_malloc(3 * n * sizeof *nbr);
    same = sd_malloc(3 * n);
    flip = sd_calloc(n, 1);
    part = sd_malloc(n * sizeof *part);
    queue = sd_malloc(n * sizeof *queue);
    if (!edges || !nbr || !same || !flip || !part || !queue) {
        st = SD_TM_OOM(err);
        goto done;
    }
    rep->nonmanifold = sd_tm_adjacency((const uint32_t(*)[3])tri, edges, n, nbr, same);
    for (size_t j = 0; j < n; ++j)
        part[j] = -1;
    rep->closed = 1;
    for (size_t seed = 0; seed < n; ++seed) {
        if (part[seed] >= 0)
            continue;
        int64_t pid = (int64_t)rep->parts++;
        size_t qh = 0, qt = 0, nflip = 0;
        int closed = 1;
        part[seed] = pid;
        queue[qt++] = (int64_t)seed;
        while (qh < qt) {
            size_t j = (size_t)queue[qh++];
            for (int k = 0; k < 3; ++k) {
                int64_t i = nbr[3 * j + (size_t)k];
                if (i < 0) {
                    closed = 0;
                    continue;
                }
                uint8_t want = (uint8_t)(flip[j] ^ same[3 * j + (size_t)k]);
                if (part[i] < 0) {
                    part[i] = pid;
                    flip[i] = want;
                    queue[qt++] = i;
                } else if (flip[i] != want) {
                    st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                                      "facets %u and %u cannot be wound consistently: the surface through "
                                      "them is not orientable (a Moebius-like part), so it has no inside",
                                      (unsigned)src[j] + 1, (unsigned)src[i] + 1);
                    goto done;
                }
            }
        }
        for (size_t q = 0; q < qt; ++q)
            nflip += flip[queue[q]];
        /* the majority's winding wins */
        if (2 * nflip > qt)
            for (size_t q = 0; q < qt; ++q)
                flip[queue[q]] ^= 1;
        for (size_t q = 0; q < qt; ++q)
            if (flip[queue[q]]) {
                ++rep->flipped;
                size_t f = src[queue[q]] + (size_t)1;
                if (!rep->first_flipped || f < rep->first_flipped)
                    rep->first_flipped = f;
            }
        if (!closed) {
            rep->closed = 0;
            continue;
        }
        /* a closed part: signed volume (divergence theorem, about its first vertex) */
        sd_tm_v o = p[tri[seed][0]];
        double vol = 0.0;
        for (size_t q = 0; q < qt; ++q) {
            size_t j = (size_t)queue[q];
            uint32_t b = flip[j] ? 2 : 1, c = flip[j] ? 1 : 2;
            sd_tm_v a0 = sd_tm_sub(p[tri[j][0]], o), b0 = sd_tm_sub(p[tri[j][b]], o), c0 = sd_tm_sub(p[tri[j][c]], o);
            vol += sd_tm_dot(a0, sd_tm_cross(b0, c0));
        }
        /* vol > 0: right-hand normals point outward */
        if ((vol > 0.0) != (side == SD_TRIMESH_OUTSIDE))
            for (size_t q = 0; q < qt; ++q)
                flip[queue[q]] ^= 2; /* the global turn, not counted */
        for (size_t q = 0; q < qt; ++q)
            flip[queue[q]] |= 4; /* a closed part (SD_TRIMESH_CLOSED below; not a turn) */
    }
    for (size_t j = 0; j < n; ++j) {
        int f = (flip[j] & 1) ^ ((flip[j] >> 1) & 1);
        if (f) {
            uint32_t x = tri[j][1];
            tri[j][1] = tri[j][2];
            tri[j][2] = x;
        }
    }
    /* the adjacency again, for the new windings */
    sd_free(edges);
    edges = sd_tm_edges((const uint32_t(*)[3])tri, n);
    if (!edges) {
        st = SD_TM_OOM(err);
        goto done;
    }
    sd_tm_adjacency((const uint32_t(*)[3])tri, edges, n, nbr, same);

    /* 4. plane groups */
    tn = sd_malloc(n * sizeof *tn);
    uint32_t *group = sd_malloc(n * sizeof *group);
    out->group = group;
    out->flags = sd_calloc(n, 1);
    if (!tn || !group || !out->flags) {
        st = SD_TM_OOM(err);
        goto done;
    }
    for (size_t j = 0; j < n; ++j) {
        tn[j] = sd_tm_cross(sd_tm_sub(p[tri[j][1]], p[tri[j][0]]), sd_tm_sub(p[tri[j][2]], p[tri[j][0]]));
        group[j] = UINT32_MAX;
    }
    double sin_tol = sin(coplanar_tol);
    size_t ng = 0;
    for (size_t seed = 0; seed < n; ++seed) {
        if (group[seed] != UINT32_MAX)
            continue;
        double ls = sd_tm_norm(tn[seed]);
        size_t qh = 0, qt = 0;
        group[seed] = (uint32_t)ng;
        queue[qt++] = (int64_t)seed;
        while (qh < qt) {
            size_t j = (size_t)queue[qh++];
            for (int k = 0; k < 3; ++k) {
                int64_t i = nbr[3 * j + (size_t)k];
                if (i < 0 || group[i] != UINT32_MAX)
                    continue;
                double li = sd_tm_norm(tn[i]);
                /* the angle to the group's first facet: sin from the cross product, side from the dot */
                if (sd_tm_dot(tn[seed], tn[i]) > 0.0 && sd_tm_norm(sd_tm_cross(tn[seed], tn[i])) <= sin_tol * ls * li) {
                    group[i] = (uint32_t)ng;
                    queue[qt++] = i;
                }
            }
        }
        ++ng;
    }
    out->group_normal = sd_malloc(ng * sizeof *out->group_normal);
    out->group_offset = sd_malloc(ng * sizeof *out->group_offset);
    double *gs = sd_calloc(4 * ng, sizeof *gs);
    if (!out->group_normal || !out->group_offset || !gs) {
        sd_free(gs);
        st = SD_TM_OOM(err);
        goto done;
    }
    /* area-weighted normal, summed in facet order; offset: area-weighted n . centroid */
    for (size_t j = 0; j < n; ++j) {
        double *g = gs + 4 * group[j];
        g[0] += tn[j].x;
        g[1] += tn[j].y;
        g[2] += tn[j].z;
    }
    for (size_t g = 0; g < ng; ++g) {
        sd_tm_v s = {gs[4 * g], gs[4 * g + 1], gs[4 * g + 2]};
        double l = sd_tm_norm(s);
        gs[4 * g] = s.x / l;
        gs[4 * g + 1] = s.y / l;
        gs[4 * g + 2] = s.z / l;
        gs[4 * g + 3] = 0.0;
    }
    for (size_t j = 0; j < n; ++j) {
        double *g = gs + 4 * group[j];
        sd_tm_v u = {g[0], g[1], g[2]};
        sd_tm_v c = {(p[tri[j][0]].x + p[tri[j][1]].x + p[tri[j][2]].x) / 3.0,
                     (p[tri[j][0]].y + p[tri[j][1]].y + p[tri[j][2]].y) / 3.0,
                     (p[tri[j][0]].z + p[tri[j][1]].z + p[tri[j][2]].z) / 3.0};
        g[3] += sd_tm_norm(tn[j]) * sd_tm_dot(u, c);
    }
    {
        double *area = sd_calloc(ng, sizeof *area);
        if (!area) {
            sd_free(gs);
            st = SD_TM_OOM(err);
            goto done;
        }
        for (size_t j = 0; j < n; ++j)
            area[group[j]] += sd_tm_norm(tn[j]);
        for (size_t g = 0; g < ng; ++g) {
            out->group_normal[g] = sd_v3((sd_real)gs[4 * g], (sd_real)gs[4 * g + 1], (sd_real)gs[4 * g + 2]);
            out->group_offset[g] = (sd_real)(gs[4 * g + 3] / area[g]);
        }
        sd_free(area);
    }
    sd_free(gs);

    /* 5. active edges, then corners */
    vactive = sd_calloc(nvo, 1);
    if (!vactive) {
        st = SD_TM_OOM(err);
        goto done;
    }
    for (size_t s = 0; s < 3 * n;) {
        size_t r = s + 1;
        while (r < 3 * n && edges[r].a == edges[s].a && edges[r].b == edges[s].b)
            ++r;
        const sd_tm_key *f = &edges[s]; /* the lowest-numbered facet on the edge (sorted by triangle) */
        int active = 1;
        if (r - s == 2) {
            const sd_tm_key *g = &edges[s + 1];
            if (group[f->tri] == group[g->tri]) {
                active = 0;
            } else {
                sd_tm_v a = p[f->a], far = p[tri[g->tri][(g->k + 2) % 3]];
                sd_tm_v d = sd_tm_sub(far, a);
                double ln = sd_tm_norm(tn[f->tri]);
                /* far corner below f's plane (away from the particle side): a ridge, convex.
                 * Within half the coplanar tolerance of the plane it counts as flat. */
                active = sd_tm_dot(tn[f->tri], d) < -0.5 * sin_tol * ln * sd_tm_norm(d);
            }
        }
        if (active) {
            out->flags[f->tri] |= (uint8_t)SD_TRIMESH_EDGE(f->k);
            vactive[f->a] = 1;
            vactive[f->b] = 1;
        }
        s = r;
    }
    for (size_t j = 0; j < n; ++j)
        if (flip[j] & 4)
            out->flags[j] |= (uint8_t)SD_TRIMESH_CLOSED;
    for (size_t j = 0; j < n; ++j)
        for (int k = 0; k < 3; ++k)
            if (vactive[tri[j][k]] == 1) {
                out->flags[j] |= (uint8_t)SD_TRIMESH_CORNER(k);
                vactive[tri[j][k]] = 2; /* taken by its lowest-numbered facet */
            }

    /* the output */
    out->vertices = sd_malloc(nvo * sizeof *out->vertices);
    out->triangles = sd_malloc(n * sizeof *out->triangles);
    out->source = sd_malloc(n * sizeof *out->source);
    out->nbr = sd_malloc(n * sizeof *out->nbr);
    if (!out->vertices || !out->triangles || !out->source || !out->nbr) {
        st = SD_TM_OOM(err);
        goto done;
    }
    for (size_t i = 0; i < nvo; ++i)
        out->vertices[i] = sd_v3((sd_real)p[i].x, (sd_real)p[i].y, (sd_real)p[i].z);
    memcpy(out->triangles, tri, n * sizeof *tri);
    memcpy(out->source, src, n * sizeof *src);
    for (size_t j = 0; j < n; ++j)
        for (int k = 0; k < 3; ++k) {
            int64_t i = nbr[3 * j + (size_t)k];
            out->nbr[j][k] = i >= 0 ? (uint32_t)i : UINT32_MAX;
        }
    out->vertex_count = nvo;
    out->triangle_count = n;
    out->group_count = ng;

done:
    if (st != SD_OK)
        sd_trimesh_free(out);
    sd_free(p);
    sd_free(map);
    sd_free(newv);
    sd_free(tri);
    sd_free(src);
    sd_free(keys);
    sd_free(drop);
    sd_free(edges);
    sd_free(nbr);
    sd_free(same);
    sd_free(flip);
    sd_free(part);
    sd_free(queue);
    sd_free(vactive);
    sd_free(tn);
    return st;
}
