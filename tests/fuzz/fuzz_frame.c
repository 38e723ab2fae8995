/* fuzz_frame.c — libFuzzer target: the frame reader of `shapedem render`
 * (render/read.c): particle frames (.vtu), shapes and wall files (.vtp)
 * and frames.pvd, as a run writes them and as a user may hand them over.
 *
 * Input: byte 0 chooses the file (0: particles_000000.vtu, 1:
 * shapes_000000.vtp, 2: frames.pvd, 3: walls_000000.vtp next to a shapes
 * file that is the same bytes) and the field (bit 2: "id", or with bit 3
 * "shape", a categorical field whose names the reader takes from the
 * file's field data; else "speed");
 * the rest is the file. Besides the sanitizers, it checks render.h's
 * invariant: on SD_OK every connectivity index names a point, the cell
 * ends rise to the connectivity's end, every drawn value is there; on an
 * error the frame is empty and the message names the file.
 */
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_util.h"
#include "render/render.h"

#define SD_FUZZ_CHECK(c)                                                                                         \
    do {                                                                                                         \
        if (!(c)) {                                                                                              \
            fprintf(stderr, "fuzz_frame: invariant failed: %s\n", #c);                                           \
            __builtin_trap();                                                                                    \
        }                                                                                                        \
    } while (0)

static void sd_fuzz_check_cells(size_t npts, size_t ncells, size_t nconn, const int64_t *conn, const int64_t *ends)
{
    int64_t prev = 0;
    for (size_t k = 0; k < ncells; ++k) {
        SD_FUZZ_CHECK(ends[k] >= prev && ends[k] <= (int64_t)nconn);
        prev = ends[k];
    }
    SD_FUZZ_CHECK(ncells == 0 || prev == (int64_t)nconn);
    for (size_t k = 0; k < nconn; ++k)
        SD_FUZZ_CHECK(conn[k] >= 0 && conn[k] < (int64_t)npts);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    int kind = data[0] & 3;
    const char *field = (data[0] & 4) ? ((data[0] & 8) ? "shape" : "id") : "speed";
    static const char *names[4] = {"particles_000000.vtu", "shapes_000000.vtp", "frames.pvd", "walls_000000.vtp"};
    char path[1024], other[1024];
    sd_fuzz_write(names[kind], data + 1, size - 1, path, sizeof path);
    sd_error err;
    memset(&err, 0, sizeof err);
    if (kind == 2) {
        char **paths = NULL;
        size_t n = 0;
        sd_status st = sd_render_pvd_list(path, &paths, &n, &err);
        sd_fuzz_report("sd_render_pvd_list", st, &err);
        SD_FUZZ_CHECK((st == SD_OK) == (paths != NULL));
        SD_FUZZ_CHECK(st != SD_OK || n > 0);
        for (size_t k = 0; k < n; ++k)
            SD_FUZZ_CHECK(paths[k] && memchr(paths[k], 0, SD_RENDER_PATH_MAX) != NULL);
        sd_free(paths);
        return 0;
    }
    if (kind == 3) /* the walls file is read as the sibling of a shapes file */
        sd_fuzz_write("shapes_000000.vtp", data + 1, size - 1, other, sizeof other);
    sd_render_frame f;
    sd_status st = sd_render_frame_load(kind == 3 ? other : path, field, &f, &err);
    sd_fuzz_report("sd_render_frame_load", st, &err);
    if (st != SD_OK) {
        SD_FUZZ_CHECK(f.point_count == 0 && f.sphere_count == 0 && f.wall_cell_count == 0 && f.points == NULL);
        SD_FUZZ_CHECK(err.msg[0] != 0 && err.file[0] != 0);
        return 0;
    }
    sd_fuzz_check_cells(f.point_count, f.cell_count, f.conn_count, f.conn, f.ends);
    sd_fuzz_check_cells(f.wall_point_count, f.wall_cell_count, f.wall_conn_count, f.wall_conn, f.wall_ends);
    SD_FUZZ_CHECK(f.cell_count == 0 || (f.cell_value && f.cell_id));
    SD_FUZZ_CHECK(f.sphere_count == 0 || (f.centres && f.radii && f.sphere_value));
    double lo, hi;
    sd_render_frame_range(&f, &lo, &hi);
    if (f.categorical) { /* every index drawn has a name (a legend entry) */
        SD_FUZZ_CHECK(f.names != NULL && f.category_count > 0);
        SD_FUZZ_CHECK(lo >= f.category_first && hi < (double)f.category_first + (double)f.category_count);
        for (size_t k = 0; k < f.category_count; ++k)
            SD_FUZZ_CHECK(memchr(f.names[k], 0, sizeof f.names[k]) != NULL);
        char what[512];
        sd_render_def d = sd_render_def_default();
        sd_render_describe(&f, &d, what, sizeof what);
        SD_FUZZ_CHECK(memchr(what, 0, sizeof what) != NULL);
    }
    sd_render_frame_free(&f);
    if (kind == 3)
        remove(other);
    return 0;
}
