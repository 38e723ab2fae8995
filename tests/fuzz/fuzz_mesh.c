/* fuzz_mesh.c — libFuzzer target: the STL/OBJ reader (io/mesh.c) and the
 * scene's check of a polyhedron mesh (sd_scene_read_mesh: distinct
 * vertices, convexity or the hull).
 *
 * Input: byte 0 chooses the file kind (bit 0: 0 = .stl, 1 = .obj) and
 * take_hull (bit 1); the rest is the file. Besides the sanitizers, it
 * checks mesh.h's invariant: on SD_OK every coordinate is finite, every
 * index < vertex_count, the faces' CSR is ordered and each triangle's face
 * exists; on an error the mesh is empty and the message is set.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_util.h"
#include "io/mesh.h"
#include "io/scene.h"

#define SD_FUZZ_CHECK(c)                                                                                         \
    do {                                                                                                         \
        if (!(c)) {                                                                                              \
            fprintf(stderr, "fuzz_mesh: invariant failed: %s\n", #c);                                            \
            __builtin_trap();                                                                                    \
        }                                                                                                        \
    } while (0)

static void sd_fuzz_check_mesh(const sd_mesh *m)
{
    for (size_t i = 0; i < m->vertex_count; ++i)
        SD_FUZZ_CHECK(isfinite(m->vertices[i].x) && isfinite(m->vertices[i].y) && isfinite(m->vertices[i].z));
    SD_FUZZ_CHECK(m->face_start[0] == 0);
    for (size_t f = 0; f < m->face_count; ++f) {
        SD_FUZZ_CHECK(m->face_start[f] <= m->face_start[f + 1]);
        (void)sd_mesh_face_centre(m, f);
    }
    for (size_t k = 0; k < m->face_start[m->face_count]; ++k)
        SD_FUZZ_CHECK(m->corners[k] < m->vertex_count);
    for (size_t t = 0; t < m->triangle_count; ++t) {
        for (int c = 0; c < 3; ++c)
            SD_FUZZ_CHECK(m->triangles[t][c] < m->vertex_count);
        SD_FUZZ_CHECK(m->triangle_face[t] < m->face_count);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    const int obj = data[0] & 1, take_hull = (data[0] >> 1) & 1;
    char path[1024];
    sd_fuzz_write(obj ? "mesh.obj" : "mesh.stl", data + 1, size - 1, path, sizeof path);
    sd_mesh m;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_mesh_read(path, &m, &err);
    sd_fuzz_report("sd_mesh_read", st, &err);
    if (st == SD_OK) {
        sd_fuzz_check_mesh(&m);
        sd_mesh_free(&m);
    } else {
        SD_FUZZ_CHECK(err.msg[0] && m.vertex_count == 0 && !m.vertices && !m.face_start && !m.triangles);
    }
    sd_v3d *v = NULL;
    size_t n = 0;
    char warning[400];
    memset(&err, 0, sizeof err);
    st = sd_scene_read_mesh(path, take_hull, &v, &n, warning, sizeof warning, &err);
    sd_fuzz_report("sd_scene_read_mesh", st, &err);
    if (st == SD_OK) {
        SD_FUZZ_CHECK(n >= 4);
        for (size_t i = 0; i < n; ++i)
            SD_FUZZ_CHECK(isfinite(v[i].x) && isfinite(v[i].y) && isfinite(v[i].z));
        sd_free(v);
    } else {
        SD_FUZZ_CHECK(err.msg[0] && !v);
    }
    return 0;
}
