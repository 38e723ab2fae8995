/* trimesh.c — mesh preparation for mesh walls (src/geom/trimesh.c):
 * welding, degenerate and duplicate facets, orientation (flipped facets
 * repaired and counted, a Moebius strip refused), plane groups and the
 * active edge/corner rule of trimesh.h on a flat plane split into regular
 * and random triangles (one group), a cube (6 groups; from outside 12
 * convex edges active once and 8 corners; from inside none), and a trough
 * whose fold is concave one way and convex the other.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/rng.h"
#include "geom/trimesh.h"
#include "test.h"

/* Counts of active feature bits over all triangles. */
static void sd_count(const sd_trimesh *m, size_t *edges, size_t *corners)
{
    *edges = *corners = 0;
    for (size_t j = 0; j < m->triangle_count; ++j)
        for (int k = 0; k < 3; ++k) {
            *edges += (m->flags[j] & SD_TRIMESH_EDGE(k)) != 0;
            *corners += (m->flags[j] & SD_TRIMESH_CORNER(k)) != 0;
        }
}

/* Every vertex's active-corner count (at most one each, the rule). */
static size_t sd_max_corner_per_vertex(const sd_trimesh *m)
{
    size_t worst = 0;
    for (size_t v = 0; v < m->vertex_count; ++v) {
        size_t c = 0;
        for (size_t j = 0; j < m->triangle_count; ++j)
            for (int k = 0; k < 3; ++k)
                c += m->triangles[j][k] == v && (m->flags[j] & SD_TRIMESH_CORNER(k));
        worst = c > worst ? c : worst;
    }
    return worst;
}

/* Every unordered edge active on at most one facet. */
static size_t sd_max_edge_activity(const sd_trimesh *m)
{
    size_t worst = 0;
    for (size_t j = 0; j < m->triangle_count; ++j)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = m->triangles[j][k], b = m->triangles[j][(k + 1) % 3];
            size_t c = 0;
            for (size_t i = 0; i < m->triangle_count; ++i)
                for (int q = 0; q < 3; ++q) {
                    uint32_t x = m->triangles[i][q], y = m->triangles[i][(q + 1) % 3];
                    c += ((x == a && y == b) || (x == b && y == a)) && (m->flags[i] & SD_TRIMESH_EDGE(q));
                }
            worst = c > worst ? c : worst;
        }
    return worst;
}

/* Every pair of facets sharing an edge runs it in opposite directions. */
static int sd_consistent(const sd_trimesh *m)
{
    for (size_t j = 0; j < m->triangle_count; ++j)
        for (int k = 0; k < 3; ++k)
            for (size_t i = j + 1; i < m->triangle_count; ++i)
                for (int q = 0; q < 3; ++q)
                    if (m->triangles[j][k] == m->triangles[i][q] &&
                        m->triangles[j][(k + 1) % 3] == m->triangles[i][(q + 1) % 3])
                        return 0;
    return 1;
}

static sd_vec3 sd_tri_normal(const sd_trimesh *m, size_t j)
{
    sd_vec3 a = m->vertices[m->triangles[j][0]], b = m->vertices[m->triangles[j][1]],
            c = m->vertices[m->triangles[j][2]];
    return sd_v3_normalize(sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a)));
}

/* ---- welding ---- */
static void sd_test_weld(void)
{
    /* a unit square as two STL facets, six vertices; one copy off by 1e-12 m */
    sd_v3d v[6] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1e-12, 0}, {0, 1, 0}};
    v[4] = sd_test_v(1, 1 + 1e-12, 0);
    const uint32_t t[2][3] = {{0, 1, 2}, {3, 4, 5}};
    sd_trimesh m;
    sd_trimesh_report r;
    sd_error err;
    CHECK(sd_trimesh_build(v, 6, t, 2, 0.0, 0.0, &m, &r, &err) == SD_OK);
    printf("weld: %zu vertices, %zu welded, %zu groups\n", m.vertex_count, r.welded, m.group_count);
    CHECK(m.vertex_count == 4 && r.welded == 2 && m.group_count == 1 && !r.closed);
    CHECK(m.triangles[1][0] == m.triangles[0][0] && m.triangles[1][1] == m.triangles[0][2]);
    size_t e, c;
    sd_count(&m, &e, &c);
    CHECK(e == 4 && c == 4); /* the diagonal is inside the group; 4 boundary edges, 4 corners */
    CHECK(fabs(m.group_normal[0].z - 1.0) < 1e-15 && fabs(m.group_offset[0]) < 1e-15);
    /* an open sheet: no facet marked closed (the thin-wall rule leaves it alone) */
    CHECK(!(m.flags[0] & SD_TRIMESH_CLOSED) && !(m.flags[1] & SD_TRIMESH_CLOSED));
    sd_trimesh_free(&m);
    /* a gap of 1e-3 with a weld tolerance of 1e-4: not welded, the two facets apart */
    v[4] = sd_test_v(1, 1 + 1e-3, 0);
    CHECK(sd_trimesh_build(v, 6, t, 2, 1e-4, 0.0, &m, &r, &err) == SD_OK);
    CHECK(m.vertex_count == 5 && r.welded == 1);
    sd_count(&m, &e, &c);
    CHECK(e == 6); /* the two diagonals are boundary edges now */
    sd_trimesh_free(&m);
    /* the same with a tolerance of 2e-3: welded */
    CHECK(sd_trimesh_build(v, 6, t, 2, 2e-3, 0.0, &m, &r, &err) == SD_OK);
    CHECK(m.vertex_count == 4 && r.welded == 2);
    sd_trimesh_free(&m);
}

/* ---- a flat plane split into n x n cells, two triangles each ---- */
static void sd_test_plane(int random, uint64_t seed)
{
    enum { N = 12 };
    static sd_v3d v[(N + 1) * (N + 1)];
    static uint32_t t[2 * N * N][3];
    sd_rng rng = sd_rng_seed(seed);
    /* the plane z' = 0.3 tilted about x by 0.4 rad (any orientation) */
    double ca = cos(0.4), sa = sin(0.4);
    for (int i = 0; i <= N; ++i)
        for (int j = 0; j <= N; ++j) {
            double x = i, y = j;
            if (random && i > 0 && i < N && j > 0 && j < N) { /* interior points jittered: irregular triangles */
                x += 0.35 * (2.0 * sd_rng_uniform(&rng) - 1.0);
                y += 0.35 * (2.0 * sd_rng_uniform(&rng) - 1.0);
            }
            double z = 0.3;
            v[i * (N + 1) + j] = sd_test_v(x, ca * y - sa * z, sa * y + ca * z);
        }
    size_t nt = 0, flipped_in = 0;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            uint32_t a = (uint32_t)(i * (N + 1) + j), b = a + (N + 1), c = b + 1, d = a + 1;
            int diag = random ? sd_rng_uniform(&rng) < 0.5 : 0;
            uint32_t t0[3] = {a, b, c}, t1[3] = {a, c, d};
            if (diag) {
                t0[0] = a; t0[1] = b; t0[2] = d;
                t1[0] = b; t1[1] = c; t1[2] = d;
            }
            for (int q = 0; q < 2; ++q) {
                uint32_t *s = q ? t1 : t0;
                /* a quarter of the random plane's facets wound the wrong way: repaired, counted */
                if (random && sd_rng_uniform(&rng) < 0.25) {
                    uint32_t x = s[1];
                    s[1] = s[2];
                    s[2] = x;
                    ++flipped_in;
                }
                memcpy(t[nt++], s, sizeof t[0]);
            }
        }
    sd_trimesh m;
    sd_trimesh_report r;
    sd_error err;
    sd_status st = sd_trimesh_build(v, (N + 1) * (N + 1), (const uint32_t(*)[3])t, nt, 0.0, 0.0, &m, &r, &err);
    sd_test_require(st == SD_OK, "plane", &err);
    size_t e, c;
    sd_count(&m, &e, &c);
    printf("plane (%s): %zu facets, %zu groups, %zu flipped (%zu wound wrong), active edges %zu (boundary %d), "
           "corners %zu (boundary vertices %d)\n",
           random ? "random" : "regular", m.triangle_count, m.group_count, r.flipped, flipped_in, e, 4 * N, c,
           4 * N);
    CHECK(m.group_count == 1 && m.triangle_count == 2 * N * N && !r.closed);
    CHECK(r.flipped == flipped_in && sd_consistent(&m));
    CHECK(e == 4 * N && c == 4 * N && sd_max_corner_per_vertex(&m) == 1);
    /* the group normal is the winding's: (0, -sin, cos) of the tilt; offset 0.3 */
    CHECK_NEAR(random ? "random plane: normal . (0,-sa,ca)" : "regular plane: normal . (0,-sa,ca)",
               -sa * m.group_normal[0].y + ca * m.group_normal[0].z, 1.0, 1e-14);
    CHECK_NEAR(random ? "random plane: offset (m)" : "regular plane: offset (m)", m.group_offset[0], 0.3, 1e-13);
    /* no interior vertex has an active corner (flat surroundings) */
    int interior_active = 0;
    for (size_t j = 0; j < m.triangle_count; ++j)
        for (int k = 0; k < 3; ++k) {
            sd_vec3 p = m.vertices[m.triangles[j][k]];
            int boundary = p.x == 0.0 || p.x == N || fabs(ca * p.y + sa * p.z - 0.0) < 1e-9 ||
                           fabs(ca * p.y + sa * p.z - N) < 1e-9;
            if (!boundary && (m.flags[j] & SD_TRIMESH_CORNER(k)))
                interior_active = 1;
        }
    CHECK(!interior_active);
    sd_trimesh_free(&m);
}

/* ---- a unit cube, 12 facets, outward wound ---- */
static const sd_v3d sd_cube_v[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
static const uint32_t sd_cube_t[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

static void sd_test_cube(void)
{
    sd_trimesh m;
    sd_trimesh_report r;
    sd_error err;
    size_t e, c;
    /* as a closed box: the particles inside, normals inward, every fold concave */
    CHECK(sd_trimesh_build(sd_cube_v, 8, sd_cube_t, 12, 0.0, 0.0, &m, &r, &err) == SD_OK);
    sd_count(&m, &e, &c);
    printf("cube inside: %zu groups, closed %d, flipped %zu, active edges %zu, corners %zu\n", m.group_count,
           r.closed, r.flipped, e, c);
    CHECK(m.group_count == 6 && r.closed && r.flipped == 0 && e == 0 && c == 0 && sd_consistent(&m));
    for (size_t j = 0; j < 12; ++j) {
        /* inward: the normal points to the centre (0.5, 0.5, 0.5) */
        sd_vec3 n = sd_tri_normal(&m, j), a = m.vertices[m.triangles[j][0]];
        CHECK(sd_v3_dot(n, sd_v3_sub(sd_v3(0.5, 0.5, 0.5), a)) > 0.49);
        sd_vec3 g = m.group_normal[m.group[j]];
        CHECK(sd_v3_dot(g, n) > 1.0 - 1e-15 && fabs(sd_v3_dot(g, a) - m.group_offset[m.group[j]]) < 1e-15);
        CHECK(m.flags[j] & SD_TRIMESH_CLOSED); /* behind every facet: the part's solid */
    }
    sd_trimesh_free(&m);
    /* as an obstacle: particles outside; 12 convex edges active once, 8 corners once */
    CHECK(sd_trimesh_build_side(sd_cube_v, 8, sd_cube_t, 12, 0.0, 0.0, SD_TRIMESH_OUTSIDE, &m, &r, &err) == SD_OK);
    sd_count(&m, &e, &c);
    printf("cube outside: %zu groups, active edges %zu (12), corners %zu (8)\n", m.group_count, e, c);
    CHECK(m.group_count == 6 && e == 12 && c == 8 && sd_max_edge_activity(&m) == 1 &&
          sd_max_corner_per_vertex(&m) == 1);
    /* the face diagonals are inactive: every active edge is axis-aligned */
    for (size_t j = 0; j < 12; ++j)
        for (int k = 0; k < 3; ++k)
            if (m.flags[j] & SD_TRIMESH_EDGE(k)) {
                sd_vec3 d = sd_v3_sub(m.vertices[m.triangles[j][(k + 1) % 3]], m.vertices[m.triangles[j][k]]);
                CHECK(fabs(sd_v3_norm(d) - 1.0) < 1e-15);
            }
    sd_trimesh_free(&m);
    /* three facets wound the wrong way, one duplicated with reversed winding,
     * one degenerate (collinear), one with a repeated corner: repaired, counted */
    sd_v3d v[9];
    memcpy(v, sd_cube_v, sizeof sd_cube_v);
    v[8] = sd_test_v(0.5, 0, 0); /* on the edge 0-1 */
    uint32_t t[15][3];
    memcpy(t, sd_cube_t, sizeof sd_cube_t);
    for (int j = 3; j < 12; j += 4) { /* facets 4, 8, 12 (1-based) */
        uint32_t x = t[j][1];
        t[j][1] = t[j][2];
        t[j][2] = x;
    }
    const uint32_t extra[3][3] = {{0, 1, 8}, {6, 5, 1}, {2, 2, 3}};
    memcpy(t[12], extra, sizeof extra);
    CHECK(sd_trimesh_build(v, 9, (const uint32_t(*)[3])t, 15, 0.0, 0.0, &m, &r, &err) == SD_OK);
    printf("cube repaired: %zu facets, flipped %zu (first %zu), degenerate %zu (first %zu), duplicates %zu "
           "(first %zu), closed %d\n",
           m.triangle_count, r.flipped, r.first_flipped, r.degenerate, r.first_degenerate, r.duplicates,
           r.first_duplicate, r.closed);
    CHECK(m.triangle_count == 12 && r.flipped == 3 && r.first_flipped == 4 && r.degenerate == 2 &&
          r.first_degenerate == 13 && r.duplicates == 1 && r.first_duplicate == 14 && r.closed &&
          sd_consistent(&m) && m.group_count == 6);
    sd_trimesh_free(&m);
}

/* ---- a trough: floor z = 0 (x in [0, 1]) and wall x = 0 (z in [0, 1]) ---- */
static void sd_test_trough(void)
{
    const sd_v3d v[6] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 1}, {0, 1, 1}};
    /* wound so the normals point into the corner: floor +z, wall +x */
    const uint32_t t[4][3] = {{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}};
    sd_trimesh m;
    sd_trimesh_report r;
    sd_error err;
    size_t e, c;
    CHECK(sd_trimesh_build(v, 6, t, 4, 0.0, 0.0, &m, &r, &err) == SD_OK);
    sd_count(&m, &e, &c);
    printf("trough (concave fold): %zu groups, active edges %zu (6 boundary), corners %zu\n", m.group_count, e, c);
    CHECK(m.group_count == 2 && e == 6 && r.flipped == 0);
    CHECK(m.group_normal[0].z > 1.0 - 1e-15 && m.group_normal[1].x > 1.0 - 1e-15);
    /* the fold (0,0,0)-(0,1,0) is inactive on both facets */
    for (size_t j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k) {
            sd_vec3 a = m.vertices[m.triangles[j][k]], b = m.vertices[m.triangles[j][(k + 1) % 3]];
            if (a.x == 0 && b.x == 0 && a.z == 0 && b.z == 0)
                CHECK(!(m.flags[j] & SD_TRIMESH_EDGE(k)));
        }
    CHECK(sd_max_corner_per_vertex(&m) == 1);
    sd_trimesh_free(&m);
    /* wound the other way (particles under the floor and behind the wall): the fold is a ridge, active once */
    uint32_t u[4][3];
    for (int j = 0; j < 4; ++j) {
        u[j][0] = t[j][0];
        u[j][1] = t[j][2];
        u[j][2] = t[j][1];
    }
    CHECK(sd_trimesh_build(v, 6, (const uint32_t(*)[3])u, 4, 0.0, 0.0, &m, &r, &err) == SD_OK);
    sd_count(&m, &e, &c);
    printf("ridge (convex fold): active edges %zu (7)\n", e);
    CHECK(e == 7 && sd_max_edge_activity(&m) == 1);
    sd_trimesh_free(&m);
    /* a V: the two flanks at 45 degrees meeting at the valley y = 0 */
    const sd_v3d w[6] = {{0, 0, 0}, {1, 0, 0}, {0, -1, 1}, {1, -1, 1}, {0, 1, 1}, {1, 1, 1}};
    const uint32_t vt[4][3] = {{0, 3, 1}, {0, 2, 3}, {0, 5, 4}, {0, 1, 5}};
    CHECK(sd_trimesh_build(w, 6, vt, 4, 0.0, 0.0, &m, &r, &err) == SD_OK);
    sd_count(&m, &e, &c);
    printf("V valley: %zu groups, flipped %zu, active edges %zu (6 boundary)\n", m.group_count, r.flipped, e);
    CHECK(m.group_count == 2 && e == 6 && r.flipped == 0 && m.group_normal[0].z > 0.7 && m.group_normal[1].z > 0.7);
    sd_trimesh_free(&m);
}

/* ---- refusals ---- */
static void sd_test_errors(void)
{
    sd_trimesh m;
    sd_error err;
    /* a Moebius strip: 8 quads around a ring with a half twist */
    enum { S = 8 };
    sd_v3d v[2 * S];
    uint32_t t[2 * S][3];
    for (int i = 0; i < S; ++i) {
        double u = 2.0 * 3.14159265358979 * i / S, h = 0.5 * u; /* the strip turns by u/2 */
        for (int s = 0; s < 2; ++s) {
            double o = s ? 0.3 : -0.3;
            v[2 * i + s] = sd_test_v((2.0 + o * cos(h)) * cos(u), (2.0 + o * cos(h)) * sin(u), o * sin(h));
        }
    }
    for (int i = 0; i < S; ++i) {
        uint32_t a = (uint32_t)(2 * i), b = a + 1, c, d;
        if (i + 1 < S) {
            c = a + 2;
            d = a + 3;
        } else { /* the half twist: bottom meets top */
            c = 1;
            d = 0;
        }
        t[2 * i][0] = a; t[2 * i][1] = c; t[2 * i][2] = d;
        t[2 * i + 1][0] = a; t[2 * i + 1][1] = d; t[2 * i + 1][2] = b;
    }
    sd_status st = sd_trimesh_build(v, 2 * S, (const uint32_t(*)[3])t, 2 * S, 0.0, 0.0, &m, NULL, &err);
    printf("Moebius: %s: %s\n", sd_status_name(st), err.msg);
    CHECK(st == SD_ERR_INPUT && strstr(err.msg, "not orientable") && strstr(err.msg, "facets ") && !m.vertices);
    /* an index out of range */
    const uint32_t bad[1][3] = {{0, 1, 9}};
    st = sd_trimesh_build(sd_cube_v, 8, bad, 1, 0.0, 0.0, &m, NULL, &err);
    printf("index: %s: %s\n", sd_status_name(st), err.msg);
    CHECK(st == SD_ERR_INPUT && strstr(err.msg, "facet 1 names vertex 10") && !m.triangles);
    /* a NaN */
    sd_v3d nv[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    nv[2].y = NAN;
    const uint32_t one[1][3] = {{0, 1, 2}};
    st = sd_trimesh_build(nv, 3, one, 1, 0.0, 0.0, &m, NULL, &err);
    printf("nan: %s: %s\n", sd_status_name(st), err.msg);
    CHECK(st == SD_ERR_INPUT && strstr(err.msg, "vertex 3") && strstr(err.msg, "not finite"));
    /* nothing left */
    const uint32_t flat[2][3] = {{0, 0, 1}, {1, 2, 2}};
    st = sd_trimesh_build(sd_cube_v, 8, flat, 2, 0.0, 0.0, &m, NULL, &err);
    printf("all degenerate: %s: %s\n", sd_status_name(st), err.msg);
    CHECK(st == SD_ERR_INPUT && strstr(err.msg, "no facet is left"));
}

int main(void)
{
    sd_test_weld();
    sd_test_plane(0, 1);
    sd_test_plane(1, 7);
    sd_test_plane(1, 12345);
    sd_test_cube();
    sd_test_trough();
    sd_test_errors();
    return sd_test_summary();
}
