/* mesh.c — the context-free STL/OBJ reader (src/io/mesh.c): an ASCII STL,
 * a binary STL and an OBJ (a quad and a pentagon fanned into triangles,
 * negative indices, i/t/n corners, comments) read into the documented
 * indexed form; bad files refused with the file and the line (or facet)
 * in the error.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/mesh.h"
#include "test.h"

static char sd_dir[256];

static const char *sd_write(const char *name, const void *data, size_t n)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", sd_dir, name);
    FILE *f = fopen(path, "wb");
    sd_test_require(f != NULL, path, NULL);
    fwrite(data, 1, n, f);
    fclose(f);
    return path;
}

static const char *sd_write_text(const char *name, const char *text) { return sd_write(name, text, strlen(text)); }

/* Expects path to be refused with line `line` and every `want` in the message. */
static void sd_expect_bad(const char *label, const char *path, int line, const char *want1, const char *want2)
{
    sd_mesh m;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_mesh_read(path, &m, &err);
    int ok = st == SD_ERR_INPUT && err.line == line && !strcmp(err.file, path) && strstr(err.msg, path) &&
             strstr(err.msg, want1) && (!want2 || strstr(err.msg, want2)) && m.vertices == NULL &&
             m.triangle_count == 0;
    printf("%-4s %-28s status %s, line %d (expected %d): %s\n", ok ? "ok" : "FAIL", label, sd_status_name(st),
           err.line, line, err.msg);
    CHECK(ok);
}

static void sd_le32(unsigned char *b, uint32_t u)
{
    for (int k = 0; k < 4; ++k)
        b[k] = (unsigned char)(u >> (8 * k));
}

static void sd_lef32(unsigned char *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    sd_le32(b, u);
}

/* A binary STL of the unit tetrahedron; bad_facet >= 0 puts an inf there. */
static const char *sd_binary_tet(const char *name, int bad_facet)
{
    static const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    unsigned char b[84 + 4 * 50];
    memset(b, 0, sizeof b);
    sd_le32(b + 80, 4);
    for (int t = 0; t < 4; ++t)
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a)
                sd_lef32(b + 84 + 50 * t + 12 + 12 * c + 4 * a,
                         t == bad_facet && c == 1 && a == 2 ? (float)INFINITY : v[f[t][c]][a]);
    return sd_write(name, b, sizeof b);
}

int main(void)
{
    snprintf(sd_dir, sizeof sd_dir, "%s/sd_mesh_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(sd_dir) != NULL, "mkdtemp", NULL);
    sd_mesh m;
    sd_error err;

    /* ASCII STL, upper-case keywords and CRLF line ends as some writers emit */
    const char *astl = sd_write_text("tet.stl", "solid tet\r\n"
                                                " facet normal 0 0 -1\r\n  outer loop\r\n"
                                                "   vertex 0 0 0\r\n   vertex 0 1 0\r\n   vertex 1 0 0\r\n"
                                                "  endloop\r\n endfacet\r\n"
                                                " FACET NORMAL 0 0 0\n  OUTER LOOP\n"
                                                "   VERTEX 0 0 0\n   VERTEX 1 0 0\n   VERTEX 0 0 2.5e-1\n"
                                                "  ENDLOOP\n ENDFACET\nendsolid tet\n");
    CHECK(sd_mesh_read(astl, &m, &err) == SD_OK);
    CHECK(m.vertex_count == 6 && m.face_count == 2 && m.triangle_count == 2);
    if (m.triangle_count == 2) {
        CHECK(m.triangles[1][0] == 3 && m.triangles[1][1] == 4 && m.triangles[1][2] == 5);
        CHECK(m.triangle_face[0] == 0 && m.triangle_face[1] == 1);
        CHECK_NEAR("ascii stl: z of vertex 6", m.vertices[5].z, 0.25, 0.0);
        sd_v3d c = sd_mesh_face_centre(&m, 0);
        CHECK_NEAR("ascii stl: centre of facet 1, x", c.x, 1.0 / 3.0, 1e-15);
    }
    sd_mesh_free(&m);

    /* binary STL */
    const char *bstl = sd_binary_tet("bin.stl", -1);
    CHECK(sd_mesh_read(bstl, &m, &err) == SD_OK);
    CHECK(m.vertex_count == 12 && m.face_count == 4 && m.triangle_count == 4);
    if (m.triangle_count == 4) {
        CHECK(m.triangles[3][0] == 9 && m.triangles[3][2] == 11);
        CHECK_NEAR("binary stl: y of facet 1 vertex 2", m.vertices[1].y, 1.0, 0.0);
        CHECK_NEAR("binary stl: z of facet 4 vertex 3", m.vertices[11].z, 1.0, 0.0);
    }
    sd_mesh_free(&m);

    /* OBJ: a cube-ish prism with a quad, a pentagon, negative indices,
     * i/t/n corners, vn/vt/o/g/usemtl lines and comments */
    const char *obj = sd_write_text("poly.obj", "# a test mesh\n"
                                                "o thing\n"
                                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                "vt 0 0\nvn 0 0 1\n"
                                                "v 0.5 1.5 0 # the pentagon's tip\n"
                                                "g faces\nusemtl none\n"
                                                "f 1 2 3 4\n"
                                                "f 1/1/1 2//1 3/1 5 4\n"
                                                "f -5 -4 -1\n");
    CHECK(sd_mesh_read(obj, &m, &err) == SD_OK);
    CHECK(m.vertex_count == 5 && m.face_count == 3);
    printf("obj: %zu vertices, %zu faces, %zu triangles (expected 5, 3, 2 + 3 + 1 = 6)\n", m.vertex_count,
           m.face_count, m.triangle_count);
    CHECK(m.triangle_count == 6);
    if (m.triangle_count == 6) {
        /* the quad fanned from its first corner: (1 2 3), (1 3 4), 0-based */
        CHECK(m.triangles[0][0] == 0 && m.triangles[0][1] == 1 && m.triangles[0][2] == 2);
        CHECK(m.triangles[1][0] == 0 && m.triangles[1][1] == 2 && m.triangles[1][2] == 3);
        /* the pentagon: (1 2 3), (1 3 5), (1 5 4) */
        CHECK(m.triangles[4][0] == 0 && m.triangles[4][1] == 4 && m.triangles[4][2] == 3);
        CHECK(m.triangle_face[2] == 1 && m.triangle_face[4] == 1 && m.triangle_face[5] == 2);
        /* -5 -4 -1 after 5 vertices: 1, 2, 5 */
        CHECK(m.triangles[5][0] == 0 && m.triangles[5][1] == 1 && m.triangles[5][2] == 4);
        CHECK(m.face_start[1] == 4 && m.face_start[2] == 9 && m.face_start[3] == 12);
        sd_v3d c = sd_mesh_face_centre(&m, 1);
        CHECK_NEAR("obj: centre of the pentagon, y", c.y, (0 + 0 + 1 + 1.5 + 1) / 5.0, 1e-15);
    }
    sd_mesh_free(&m);

    /* bad files: each names the file and the line or facet */
    sd_expect_bad("binary stl, inf", sd_binary_tet("inf.stl", 2), 0, "facet 3 of 4", "not finite");
    sd_expect_bad("stl, two numbers", sd_write_text("short.stl", "solid a\nfacet\nvertex 1 2\n"), 3,
                  "line 3: expected 'vertex x y z' with 3 numbers", NULL);
    sd_expect_bad("stl, out of range", sd_write_text("big.stl", "solid a\n\nvertex 1 2 1e999\n"), 3,
                  "line 3: coordinate 1e999 is too large", NULL);
    sd_expect_bad("obj, hexadecimal", sd_write_text("hex.obj", "v 0x1p3 0 0\n"), 1, "line 1: hexadecimal", NULL);
    sd_expect_bad("obj, nan", sd_write_text("nan.obj", "v 0 nan 0\n"), 1, "line 1: coordinate nan is not finite",
                  NULL);
    sd_expect_bad("obj, index too high", sd_write_text("idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n# c\nf 1 2 4\n"), 5,
                  "line 5: a face names vertex '4', but 3 vertices", NULL);
    sd_expect_bad("obj, index 0", sd_write_text("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), 4,
                  "vertex '0'", NULL);
    sd_expect_bad("obj, negative too far", sd_write_text("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), 4,
                  "vertex '-4'", NULL);
    sd_expect_bad("obj, two-corner face", sd_write_text("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), 3,
                  "line 3: a face needs at least 3 vertices, got 2", NULL);
    const char nul[] = "v 0 0 0\0v 1 1 1\n";
    sd_expect_bad("obj, not text", sd_write("nul.obj", nul, sizeof nul - 1), 0, "nor a text file", NULL);
    sd_expect_bad("wrong extension", sd_write_text("mesh.ply", "ply\n"), 0, "expected an .obj or .stl file", NULL);
    char missing[300];
    snprintf(missing, sizeof missing, "%s/none.obj", sd_dir);
    sd_expect_bad("missing file", missing, 0, "cannot open the mesh file", NULL);

    /* the file checks of mesh walls (issue 14): size against the facet count, loops, empty files */
    sd_expect_bad("empty file", sd_write("empty.stl", "", 0), 0, "is empty (0 bytes)", NULL);
    {
        unsigned char b[84 + 4 * 50 + 7];
        FILE *f = fopen(sd_binary_tet("whole.stl", -1), "rb");
        sd_test_require(f && fread(b, 1, 84 + 4 * 50, f) == 84 + 4 * 50, "read whole.stl", NULL);
        fclose(f);
        sd_expect_bad("binary stl, truncated", sd_write("cut.stl", b, 84 + 4 * 50 - 10), 0,
                      "truncated binary STL file: its header counts 4 facets (284 bytes), the file has 274 bytes",
                      "facet 4 is cut off");
        memset(b + 84 + 4 * 50, 0, 7);
        sd_expect_bad("binary stl, extra bytes", sd_write("long.stl", b, sizeof b), 0, "header counts 4 facets",
                      "7 more; the facet count or the file is wrong");
        sd_le32(b + 80, 5);
        sd_expect_bad("binary stl, count too high", sd_write("count.stl", b, 84 + 4 * 50), 0, "counts 5 facets",
                      "facet 5 is cut off");
        sd_expect_bad("binary stl, no header", sd_write("tiny.stl", b, 40), 0, "shorter than its 84-byte header",
                      NULL);
    }
    sd_expect_bad("stl, four-vertex loop",
                  sd_write_text("quad.stl", "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                            "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n"),
                  8, "line 8: facet 2 has 4 vertices in its loop, expected 3", NULL);
    sd_expect_bad("stl, ends inside a facet",
                  sd_write_text("cutascii.stl", "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                                "vertex 1 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
                                                "vertex 0 0 0\n"),
                  11, "ends inside facet 2: it has 4 vertex lines", NULL);
    sd_expect_bad("stl, infinite", sd_write_text("infa.stl", "solid q\nfacet\nvertex inf 0 0\n"), 3,
                  "line 3: coordinate inf is not finite", NULL);

    /* an empty OBJ reads as an empty mesh: the callers decide what they need */
    CHECK(sd_mesh_read(sd_write_text("empty.obj", "# nothing\n"), &m, &err) == SD_OK);
    CHECK(m.vertex_count == 0 && m.face_count == 0 && m.triangle_count == 0);
    sd_mesh_free(&m);

    const char *names[] = {"tet.stl", "bin.stl", "poly.obj", "inf.stl", "short.stl", "big.stl", "hex.obj",
                           "nan.obj", "idx.obj", "zero.obj", "neg.obj", "two.obj", "nul.obj", "mesh.ply", "empty.obj",
                           "empty.stl", "whole.stl", "cut.stl", "long.stl", "count.stl", "tiny.stl", "quad.stl",
                           "cutascii.stl", "infa.stl"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
        char p[512];
        snprintf(p, sizeof p, "%s/%s", sd_dir, names[k]);
        unlink(p);
    }
    rmdir(sd_dir);
    return sd_test_summary();
}
