/* mesh_fuzz.c — a fuzz-like sweep of the mesh reader and the mesh
 * preparation (io/mesh.c, geom/trimesh.c) on broken binary and ASCII STL
 * files: every truncation of a binary STL, and thousands of files with
 * random bytes overwritten (header count, coordinates, attribute bytes,
 * several bytes at once), from a fixed seed.
 *
 * What must hold: no crash (the sanitizer build checks memory too), the
 * status is SD_OK or SD_ERR_INPUT (never another code), an error names the
 * file, and a mesh read fine has finite coordinates and indices in range
 * and goes through sd_trimesh_build to SD_OK or a clear SD_ERR_INPUT.
 * Every proper truncation of a binary STL is refused.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/rng.h"
#include "geom/trimesh.h"
#include "io/mesh.h"
#include "test.h"

static char sd_dir[256], sd_path[512];
static size_t sd_ok, sd_refused, sd_prepared, sd_prep_refused, sd_bad;

static void sd_put(const unsigned char *b, size_t n)
{
    FILE *f = fopen(sd_path, "wb");
    sd_test_require(f != NULL, sd_path, NULL);
    if (n)
        fwrite(b, 1, n, f);
    fclose(f);
}

/* Reads sd_path and prepares what it reads; counts outcomes; 1 when
 * refused or read as no facets at all (a text file without vertex lines,
 * such as the first bytes of the header: the callers refuse an empty mesh). */
static int sd_try(void)
{
    sd_mesh m;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_mesh_read(sd_path, &m, &err);
    if (st != SD_OK) {
        int good = st == SD_ERR_INPUT && strstr(err.msg, sd_path) && m.vertices == NULL && m.triangles == NULL;
        if (!good) {
            ++sd_bad;
            printf("FAIL refusal: status %s, message '%s'\n", sd_status_name(st), err.msg);
        }
        ++sd_refused;
        return 1;
    }
    ++sd_ok;
    int good = 1;
    for (size_t i = 0; i < m.vertex_count; ++i)
        good &= isfinite(m.vertices[i].x) && isfinite(m.vertices[i].y) && isfinite(m.vertices[i].z);
    for (size_t j = 0; j < m.triangle_count; ++j)
        for (int k = 0; k < 3; ++k)
            good &= m.triangles[j][k] < m.vertex_count;
    if (m.triangle_count) {
        sd_trimesh tm;
        sd_trimesh_report rep;
        st = sd_trimesh_build(m.vertices, m.vertex_count, (const uint32_t(*)[3])m.triangles, m.triangle_count, 0.0, 0.0,
                              &tm, &rep, &err);
        if (st == SD_OK) {
            ++sd_prepared;
            for (size_t j = 0; j < tm.triangle_count; ++j)
                for (int k = 0; k < 3; ++k)
                    good &= tm.triangles[j][k] < tm.vertex_count && tm.group[j] < tm.group_count;
            for (size_t g = 0; g < tm.group_count; ++g)
                good &= fabs(sd_v3_norm(tm.group_normal[g]) - 1.0) < 1e-9;
            sd_trimesh_free(&tm);
        } else {
            good &= st == SD_ERR_INPUT && err.msg[0] != '\0';
            ++sd_prep_refused;
        }
    }
    int empty = m.triangle_count == 0;
    if (!good) {
        ++sd_bad;
        printf("FAIL a mesh read or prepared with bad contents\n");
    }
    sd_mesh_free(&m);
    return empty;
}

/* A closed binary STL: a sphere-ish polyhedron of 2 n (n - 1) facets from
 * latitude/longitude bands, outward wound. */
static size_t sd_make_stl(unsigned char **out, int n)
{
    size_t nt = (size_t)(2 * n * (n - 1));
    unsigned char *b = calloc(84 + 50 * nt, 1);
    sd_test_require(b != NULL, "alloc", NULL);
    memcpy(b, "fuzz test sphere", 16);
    size_t t = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double th0 = 3.14159265358979 * i / n, th1 = 3.14159265358979 * (i + 1) / n;
            double ph0 = 6.28318530717959 * j / n, ph1 = 6.28318530717959 * (j + 1) / n;
            float p[4][3] = {{(float)(sin(th0) * cos(ph0)), (float)(sin(th0) * sin(ph0)), (float)cos(th0)},
                             {(float)(sin(th1) * cos(ph0)), (float)(sin(th1) * sin(ph0)), (float)cos(th1)},
                             {(float)(sin(th1) * cos(ph1)), (float)(sin(th1) * sin(ph1)), (float)cos(th1)},
                             {(float)(sin(th0) * cos(ph1)), (float)(sin(th0) * sin(ph1)), (float)cos(th0)}};
            int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int q = 0; q < 2; ++q) {
                if ((i == 0 && q == 1) || (i == n - 1 && q == 0))
                    continue; /* the pole triangles that collapse */
                if (t >= nt)
                    continue;
                unsigned char *f = b + 84 + 50 * t++;
                for (int c = 0; c < 3; ++c)
                    memcpy(f + 12 + 12 * c, p[tris[q][c]], 12);
            }
        }
    uint32_t cnt = (uint32_t)t;
    for (int k = 0; k < 4; ++k)
        b[80 + k] = (unsigned char)(cnt >> (8 * k));
    *out = b;
    return 84 + 50 * t;
}

int main(void)
{
    snprintf(sd_dir, sizeof sd_dir, "%s/sd_mesh_fuzz_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(sd_dir) != NULL, "mkdtemp", NULL);
    snprintf(sd_path, sizeof sd_path, "%s/f.stl", sd_dir);
    unsigned char *good;
    size_t size = sd_make_stl(&good, 8);

    /* the intact file reads and prepares as one closed mesh */
    sd_put(good, size);
    sd_mesh m;
    sd_error err;
    CHECK(sd_mesh_read(sd_path, &m, &err) == SD_OK);
    sd_trimesh tm;
    sd_trimesh_report rep;
    CHECK(sd_trimesh_build(m.vertices, m.vertex_count, (const uint32_t(*)[3])m.triangles, m.triangle_count, 0.0, 0.0,
                           &tm, &rep, &err) == SD_OK);
    printf("intact: %zu facets, %zu welded vertices, closed %d, flipped %zu\n", m.triangle_count, tm.vertex_count,
           rep.closed, rep.flipped);
    CHECK(rep.closed && rep.flipped == 0 && tm.vertex_count == 2 + 8 * 7);
    sd_trimesh_free(&tm);
    sd_mesh_free(&m);

    /* every truncation is refused: each length through the header and the
     * first facets, then every 13th byte */
    size_t cut_refused = 0, cuts = 0;
    for (size_t n = 0; n < size; n += n < 400 ? 1 : 13, ++cuts) {
        sd_put(good, n);
        cut_refused += (size_t)sd_try();
    }
    printf("truncations: %zu of %zu refused (or read as no facets)\n", cut_refused, cuts);
    CHECK(cut_refused == cuts);

    /* random overwrites: 1 to 8 bytes anywhere, biased to the count and the first facets */
    sd_rng rng = sd_rng_seed(20261202);
    unsigned char *b = malloc(size + 64);
    sd_test_require(b != NULL, "alloc", NULL);
    enum { TRIES = 1500 };
    for (int k = 0; k < TRIES; ++k) {
        memcpy(b, good, size);
        size_t n = size;
        int flips = 1 + (int)(sd_rng_uniform(&rng) * 8.0);
        for (int q = 0; q < flips; ++q) {
            double u = sd_rng_uniform(&rng);
            size_t at =
                u < 0.2 ? 80 + (size_t)(sd_rng_uniform(&rng) * 4.0) : (size_t)(sd_rng_uniform(&rng) * (double)size);
            if (at >= size)
                at = size - 1;
            /* whole random bytes, or the exponent bytes of a float (NaN, inf, huge, tiny) */
            b[at] = sd_rng_uniform(&rng) < 0.5 ? (unsigned char)(sd_rng_next(&rng) & 0xff) : (unsigned char)0x7f;
        }
        if (sd_rng_uniform(&rng) < 0.1) /* sometimes also a few bytes more or less */
            n = size - 8 + (size_t)(sd_rng_uniform(&rng) * 16.0);
        if (n > size)
            memset(b + size, 0x20, n - size);
        sd_put(b, n);
        sd_try();
    }
    /* ASCII STL with random bytes overwritten (keywords, digits, line ends) */
    const char *ascii = "solid a\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
                        " endloop\nendfacet\nfacet normal 0 0 1\n outer loop\n  vertex 1 0 0\n  vertex 1 1 0\n"
                        "  vertex 0 1 0\n endloop\nendfacet\nendsolid a\n";
    size_t an = strlen(ascii);
    static const char pool[] = "0123456789.eE+-nanif \t\r\nvertexVERTEXendloopouter#x\x01\xff";
    for (int k = 0; k < TRIES; ++k) {
        memcpy(b, ascii, an);
        int flips = 1 + (int)(sd_rng_uniform(&rng) * 4.0);
        for (int q = 0; q < flips; ++q)
            b[(size_t)(sd_rng_uniform(&rng) * (double)an) % an] =
                (unsigned char)pool[(size_t)(sd_rng_uniform(&rng) * (double)(sizeof pool - 1)) % (sizeof pool - 1)];
        sd_put(b, an);
        sd_try();
    }
    printf("sweep: %zu files read (%zu prepared, %zu refused by the preparation), %zu refused by the reader, "
           "%zu bad outcomes\n",
           sd_ok, sd_prepared, sd_prep_refused, sd_refused, sd_bad);
    CHECK(sd_bad == 0);
    CHECK(sd_ok > 0 && sd_refused > cuts); /* both paths exercised */
    free(b);
    free(good);
    unlink(sd_path);
    rmdir(sd_dir);
    return sd_test_summary();
}
