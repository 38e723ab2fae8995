/* vtk_bin.h — what the VTK XML writers share (vtk.c, vtk_shapes.c): the
 * little-endian binary stream of the appended data, the XML header helpers,
 * the per-particle field list (point data of particle frames, cell data of
 * shapes files) and the failed-write statuses.
 *
 * Invariant (vtk.h): every value is encoded byte by byte, little-endian on
 * any host; each appended array is a UInt64 byte count and its values.
 */
#ifndef SD_IO_VTK_BIN_H
#define SD_IO_VTK_BIN_H

#include "core/error.h"
#include "world/rebuild.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <shapedem/shapedem.h>

/* ---- little-endian binary stream --------------------------------------- */

typedef struct sd_bin {
    FILE *fp;
    size_t used;
    int failed;   /* errno of the first failed write (EIO when it gave none), 0 if none */
    unsigned char buf[1 << 14];
} sd_bin;

static inline void sd_bin_flush(sd_bin *b)
{
    if (b->used && fwrite(b->buf, 1, b->used, b->fp) != b->used && !b->failed)
        b->failed = errno ? errno : EIO;
    b->used = 0;
}

/* Byte k of the value goes to position k: little-endian on any host. */
static inline void sd_bin_bytes(sd_bin *b, uint64_t v, int nbytes)
{
    if (b->used + 8 > sizeof b->buf)
        sd_bin_flush(b);
    for (int k = 0; k < nbytes; ++k)
        b->buf[b->used++] = (unsigned char)(v >> (8 * k));
}

static inline void sd_bin_u64(sd_bin *b, uint64_t v) { sd_bin_bytes(b, v, 8); }
static inline void sd_bin_i64(sd_bin *b, int64_t v) { sd_bin_bytes(b, (uint64_t)v, 8); }
static inline void sd_bin_i32(sd_bin *b, int32_t v) { sd_bin_bytes(b, (uint64_t)(uint32_t)v, 4); }
static inline void sd_bin_u8(sd_bin *b, unsigned v) { sd_bin_bytes(b, v & 0xffu, 1); }
static inline void sd_bin_f64(sd_bin *b, double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u); /* IEEE 754 binary64 has the integer byte order on every host we target */
    sd_bin_u64(b, u);
}
static inline void sd_bin_v3(sd_bin *b, sd_v3d v)
{
    sd_bin_f64(b, v.x);
    sd_bin_f64(b, v.y);
    sd_bin_f64(b, v.z);
}

/* ---- XML header helpers ------------------------------------------------- */

/* One appended DataArray declaration; advances *offset past its block. */
static inline void sd_vtk_array_decl(FILE *fp, const char *indent, const char *type, const char *name,
                              int components, size_t count, size_t value_size, uint64_t *offset)
{
    fprintf(fp, "%s<DataArray type=\"%s\" Name=\"%s\"", indent, type, name);
    if (components > 1)
        fprintf(fp, " NumberOfComponents=\"%d\"", components);
    fprintf(fp, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", *offset);
    *offset += 8u + (uint64_t)count * (uint64_t)components * (uint64_t)value_size;
}

static inline void sd_vtk_file_open(FILE *fp, const char *type)
{
    fprintf(fp, "<?xml version=\"1.0\"?>\n");
    fprintf(fp,
            "<VTKFile type=\"%s\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\">\n",
            type);
}

static inline void sd_vtk_appended_open(FILE *fp) { fprintf(fp, "  <AppendedData encoding=\"raw\">\n   _"); }

static inline void sd_vtk_appended_close(FILE *fp) { fprintf(fp, "\n  </AppendedData>\n</VTKFile>\n"); }

/* ---- per-particle fields (point data of frames, cell data of shapes) --- */

/* X(enum, VTK name, VTK type, components, bytes per value): the point data of
 * a particle frame, listed once for the header and the data pass. */
#define SD_VTK_POINT_FIELDS(X)                                                                     \
    X(SD_VF_ID, "id", "UInt64", 1, 8)                                                               \
    X(SD_VF_RADIUS, "radius", "Float64", 1, 8)                                                      \
    X(SD_VF_VELOCITY, "velocity", "Float64", 3, 8)                                                  \
    X(SD_VF_ANGULAR_VELOCITY, "angular_velocity", "Float64", 3, 8)                                  \
    X(SD_VF_FORCE, "force", "Float64", 3, 8)                                                        \
    X(SD_VF_MATERIAL, "material", "Int32", 1, 4)                                                    \
    X(SD_VF_ORIENTATION, "orientation", "Float64", 4, 8)                                             \
    X(SD_VF_AXIS, "axis", "Float64", 3, 8)                                                          \
    X(SD_VF_SHAPE, "shape", "Int32", 1, 4)

typedef enum sd_vtk_field {
#define SD_X_ENUM(e, name, type, comps, size) e,
    SD_VTK_POINT_FIELDS(SD_X_ENUM)
#undef SD_X_ENUM
    SD_VF_COUNT
} sd_vtk_field;

static inline void sd_vtk_put_field(sd_bin *b, sd_vtk_field f, const sd_particle_state *p)
{
    switch (f) {
    case SD_VF_ID: sd_bin_u64(b, p->id); break;
    case SD_VF_RADIUS: sd_bin_f64(b, p->radius); break;
    case SD_VF_VELOCITY: sd_bin_v3(b, p->velocity); break;
    case SD_VF_ANGULAR_VELOCITY: sd_bin_v3(b, p->angular_velocity); break;
    case SD_VF_FORCE: sd_bin_v3(b, p->force); break;
    case SD_VF_MATERIAL: sd_bin_i32(b, (int32_t)p->material); break;
    case SD_VF_SHAPE: sd_bin_i32(b, (int32_t)p->shape); break; /* -1: a plain sphere */
    case SD_VF_ORIENTATION:
        for (int k = 0; k < 4; ++k)
            sd_bin_f64(b, p->quat[k]);
        break;
    case SD_VF_AXIS: {
        /* the body's x axis in the world frame, R(q) e_x: ParaView's Glyph
         * filter orients glyphs by such a vector (in 2D it is (cos a, sin a, 0)
         * for the rotation angle a about z) */
        double w = p->quat[0], x = p->quat[1], y = p->quat[2], z = p->quat[3];
        sd_v3d ax = {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)};
        sd_bin_v3(b, ax);
        break;
    }
    case SD_VF_COUNT: break;
    }
}

static inline sd_status sd_vtk_get(const sd_world *w, size_t i, sd_particle_state *p, sd_error *err)
{
    sd_status s = sd_world_get_particle(w, i, p);
    if (s != SD_OK)
        return sd_error_set(err, s, "", 0, "", "cannot read particle %zu of the world", i);
    sd_world_wrap_periodic(w, &p->position); /* frames show the periodic box (world/rebuild.h) */
    return SD_OK;
}

/* A failed write keeps the system's reason (a full disk says "No space left
 * on device"): errno of the failing call, else of the stream's last error. */
static inline sd_status sd_vtk_write_failed(int e, sd_error *err)
{
    return sd_error_set(err, SD_ERR_IO, "", 0, "", "write failed: %s", strerror(e ? e : EIO));
}

static inline sd_status sd_vtk_stream_status(FILE *fp, sd_error *err)
{
    return ferror(fp) ? sd_vtk_write_failed(errno, err) : SD_OK;
}

static inline sd_status sd_vtk_bin_status(sd_bin *b, sd_error *err)
{
    sd_bin_flush(b);
    if (b->failed || ferror(b->fp))
        return sd_vtk_write_failed(b->failed ? b->failed : errno, err);
    return SD_OK;
}

#endif
