/* mesh.c — the STL and OBJ reader (see mesh.h for the output format).
 *
 * STL: binary (80-byte header, a little-endian triangle count, 50 bytes
 * per triangle) when the file's size matches its count, ASCII otherwise
 * ("vertex x y z" lines, three per facet; the keywords in any case, as
 * some writers emit VERTEX). OBJ: "v x y z" lines and "f i j k ..." lines
 * whose indices are i, i/t, i/t/n or i//n, 1-based, negative = relative to
 * the vertices read so far; other lines (vn, vt, o, g, s, usemtl, #
 * comments) are skipped. Numbers are decimal: strtod's hexadecimal floats
 * and numbers out of a double's range are refused by name, so a mesh in
 * the wrong units says so instead of reading as flat.
 *
 * What a file must be (each refusal names the file and its line or
 * facet): not empty; a binary STL (NUL bytes) exactly 84 + 50 n bytes for
 * the n facets its header counts (shorter: truncated, naming the facet cut
 * off; longer: the count is wrong); an ASCII STL with 3 vertices in every
 * outer loop, a whole number of facets and every "facet" closed by its
 * "endfacet" (a file cut inside a facet is refused; endsolid is optional).
 * Degenerate, duplicated and wrongly wound facets are the mesh
 * preparation's business (geom/trimesh.c), which repairs them with a
 * warning.
 *
 * Invariant: see mesh.h — all or nothing; every message names the file
 * and its line or facet; file bytes quoted in a message are escaped.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/mesh.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "core/error.h"

/* A growing array of elem-byte items (all of the mesh's arrays). */
typedef struct sd_mesh_buf {
    void *p;
    size_t n, cap, elem;
} sd_mesh_buf;

/* Room for `more` items; 0 when out of memory. */
static int sd_mesh_buf_room(sd_mesh_buf *b, size_t more)
{
    if (b->n + more <= b->cap)
        return 1;
    size_t nc = b->cap ? 2 * b->cap : 64;
    while (nc < b->n + more)
        nc *= 2;
    void *np = sd_realloc(b->p, nc * b->elem);
    if (!np)
        return 0;
    b->p = np;
    b->cap = nc;
    return 1;
}

/* The mesh being read: its arrays as growing buffers. */
typedef struct sd_mesh_build {
    sd_mesh_buf v, start, corner, tri, tface;
} sd_mesh_build;

static int sd_mesh_add_vertex(sd_mesh_build *b, double x, double y, double z)
{
    if (!sd_mesh_buf_room(&b->v, 1))
        return 0;
    ((sd_v3d *)b->v.p)[b->v.n++] = (sd_v3d){x, y, z};
    return 1;
}

/* Closes the face whose corners were pushed since the last face, and fans
 * it into triangles from its first corner. */
static int sd_mesh_end_face(sd_mesh_build *b)
{
    size_t *st = b->start.p;
    size_t first = st[b->start.n - 1], nc = b->corner.n - first;
    uint32_t face = (uint32_t)(b->start.n - 1);
    if (!sd_mesh_buf_room(&b->start, 1) || !sd_mesh_buf_room(&b->tri, nc - 2) || !sd_mesh_buf_room(&b->tface, nc - 2))
        return 0;
    ((size_t *)b->start.p)[b->start.n++] = b->corner.n;
    const uint32_t *c = (const uint32_t *)b->corner.p + first;
    for (size_t k = 1; k + 1 < nc; ++k) {
        uint32_t *t = ((uint32_t(*)[3])b->tri.p)[b->tri.n++];
        t[0] = c[0];
        t[1] = c[k];
        t[2] = c[k + 1];
        ((uint32_t *)b->tface.p)[b->tface.n++] = face;
    }
    return 1;
}

static int sd_mesh_add_corner(sd_mesh_build *b, size_t vertex)
{
    if (!sd_mesh_buf_room(&b->corner, 1))
        return 0;
    ((uint32_t *)b->corner.p)[b->corner.n++] = (uint32_t)vertex;
    return 1;
}

static void sd_mesh_build_free(sd_mesh_build *b)
{
    sd_free(b->v.p);
    sd_free(b->start.p);
    sd_free(b->corner.p);
    sd_free(b->tri.p);
    sd_free(b->tface.p);
}

/* Little-endian binary STL fields, read byte by byte (any host order). */
static uint32_t sd_mesh_le32(const unsigned char *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static double sd_mesh_lef32(const unsigned char *b)
{
    uint32_t u = sd_mesh_le32(b);
    float f;
    memcpy(&f, &u, sizeof f);
    return (double)f;
}

#define SD_MESH_OOM(err, path, line) sd_error_set(err, SD_ERR_MEMORY, path, line, "", "out of memory")

static sd_status sd_mesh_binary_stl(const char *path, const unsigned char *buf, sd_mesh_build *b, sd_error *err)
{
    size_t nt = sd_mesh_le32(buf + 80);
    for (size_t t = 0; t < nt; ++t) {
        for (int c = 0; c < 3; ++c) {
            const unsigned char *q = buf + 84 + 50 * t + 12 + 12 * (size_t)c;
            double x = sd_mesh_lef32(q), y = sd_mesh_lef32(q + 4), z = sd_mesh_lef32(q + 8);
            if (!isfinite(x) || !isfinite(y) || !isfinite(z))
                return sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                                    "facet %zu of %zu in '%s': vertex %d is (%g, %g, %g), not finite", t + 1, nt,
                                    path, c + 1, x, y, z);
            if (!sd_mesh_add_vertex(b, x, y, z) || !sd_mesh_add_corner(b, b->v.n - 1))
                return SD_MESH_OOM(err, path, 0);
        }
        if (!sd_mesh_end_face(b))
            return SD_MESH_OOM(err, path, 0);
    }
    return SD_OK;
}

/* "x y z" after a vertex keyword at `at`: three finite decimal numbers. */
static sd_status sd_mesh_coords(const char *path, int ln, const char *tag, char *at, double x[3], sd_error *err)
{
    char *end;
    for (int a = 0; a < 3; ++a) {
        at += strspn(at, " \t");
        errno = 0;
        x[a] = strtod(at, &end);
        if (end != at && errno == ERANGE) {
            /* overflow to inf, or underflow to 0 or a subnormal */
            char num[64];
            sd_escape(num, sizeof num, at, (size_t)(end - at));
            return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                "%s line %d: coordinate %s is too %s for a double (%g); "
                                "write the mesh in other units and set scale:",
                                path, ln, num, fabs(x[a]) > 1.0 ? "large" : "small", x[a]);
        }
        if (end != at && !isfinite(x[a])) {
            char num[64];
            sd_escape(num, sizeof num, at, (size_t)(end - at));
            return sd_error_set(err, SD_ERR_INPUT, path, ln, "", "%s line %d: coordinate %s is not finite", path,
                                ln, num);
        }
        if (end != at && strpbrk(at, "xX") && strpbrk(at, "xX") < end)
            /* strtod reads C's hexadecimal floats; YAML scenes and outline
             * CSVs take decimal numbers only, and so do mesh files */
            return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                "%s line %d: hexadecimal numbers (0x...) are not accepted; write decimal numbers",
                                path, ln);
        if (end == at)
            return sd_error_set(err, SD_ERR_INPUT, path, ln, "", "%s line %d: expected '%s x y z' with 3 numbers",
                                path, ln, tag);
        at = end;
    }
    return SD_OK;
}

/* An OBJ "f" line's corners: the vertices it names (i, i/t, i/t/n, i//n). */
static sd_status sd_mesh_obj_face(const char *path, int ln, char *at, sd_mesh_build *b, sd_error *err)
{
    char *end;
    int nfv = 0;
    for (;;) {
        at += strspn(at, " \t\r");
        if (!*at)
            break;
        long idx = strtol(at, &end, 10);
        long k = idx < 0 ? (long)b->v.n + idx : idx - 1;
        if (end == at || idx == 0 || k < 0 || k >= (long)b->v.n) {
            char tok[48]; /* file bytes: escaped, they could be terminal controls */
            sd_escape(tok, sizeof tok, at, strcspn(at, " \t"));
            return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                "%s line %d: a face names vertex '%s', but %zu vertices are defined before it", path,
                                ln, tok, b->v.n);
        }
        if (!sd_mesh_add_corner(b, (size_t)k))
            return SD_MESH_OOM(err, path, ln);
        ++nfv;
        at = end + strcspn(end, " \t\r"); /* skip /t/n */
    }
    if (nfv < 3)
        return sd_error_set(err, SD_ERR_INPUT, path, ln, "", "%s line %d: a face needs at least 3 vertices, got %d",
                            path, ln, nfv);
    return sd_mesh_end_face(b) ? SD_OK : SD_MESH_OOM(err, path, ln);
}

/* The text formats, line by line (buf is NUL-terminated and is cut up). */
static sd_status sd_mesh_text(const char *path, int obj, char *text, sd_mesh_build *b, sd_error *err)
{
    const char *tag = obj ? "v" : "vertex";
    size_t tl = strlen(tag);
    int ln = 1;
    size_t loop_start = 0; /* STL: vertices before the current "outer loop" */
    /* STL: the facet opened by "facet" and not yet closed by "endfacet"
     * (0: none), its line, and whether its loop was closed: a file cut
     * inside a facet ends with one open, even when its three vertex lines
     * are whole */
    size_t open_facet = 0;
    int open_line = 0, loop_closed = 0;
    for (char *c = text; *c; ++ln) {
        char *eol = strchr(c, '\n');
        if (eol)
            *eol = '\0';
        char *t = c + strspn(c, " \t\r");
        sd_status st = SD_OK;
        /* OBJ keywords are lower case; STL writers also emit VERTEX */
        if ((obj ? !strncmp(t, tag, tl) : !strncasecmp(t, tag, tl)) && (t[tl] == ' ' || t[tl] == '\t')) {
            double x[3];
            if ((st = sd_mesh_coords(path, ln, tag, t + tl, x, err)) != SD_OK)
                return st;
            if (!sd_mesh_add_vertex(b, x[0], x[1], x[2]))
                return SD_MESH_OOM(err, path, ln);
            if (!obj) { /* a facet is every three vertices */
                if (!sd_mesh_add_corner(b, b->v.n - 1))
                    return SD_MESH_OOM(err, path, ln);
                if (b->v.n % 3 == 0 && !sd_mesh_end_face(b))
                    return SD_MESH_OOM(err, path, ln);
            }
        } else if (obj && t[0] == 'f' && (t[1] == ' ' || t[1] == '\t')) {
            if ((st = sd_mesh_obj_face(path, ln, t + 1, b, err)) != SD_OK)
                return st;
        } else if (!obj && !strncasecmp(t, "facet", 5) && (!t[5] || strchr(" \t\r", t[5]))) {
            if (open_facet)
                return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                    "%s line %d: a facet begins before facet %zu (line %d) has its endfacet", path,
                                    ln, open_facet, open_line);
            open_facet = b->v.n / 3 + 1;
            open_line = ln;
            loop_closed = 0;
        } else if (!obj && !strncasecmp(t, "endfacet", 8) && (!t[8] || strchr(" \t\r", t[8]))) {
            if (open_facet && !loop_closed)
                return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                    "%s line %d: facet %zu ends without a whole outer loop ... endloop", path, ln,
                                    open_facet);
            open_facet = 0;
        } else if (!obj && !strncasecmp(t, "outer", 5) && (t[5] == ' ' || t[5] == '\t')) {
            loop_start = b->v.n;
        } else if (!obj && !strncasecmp(t, "endloop", 7) && (!t[7] || strchr(" \t\r", t[7]))) {
            /* a loop of other than 3 vertices would shift every later facet */
            if (b->v.n - loop_start != 3 || b->v.n % 3 != 0)
                return sd_error_set(err, SD_ERR_INPUT, path, ln, "",
                                    "%s line %d: facet %zu has %zu vertices in its loop, expected 3 (a triangle)",
                                    path, ln, b->v.n / 3 + (b->v.n % 3 != 0), b->v.n - loop_start);
            loop_closed = 1;
        }
        c = eol ? eol + 1 : c + strlen(c);
    }
    /* STL vertices after the last whole facet: the file ends inside a facet */
    if (!obj && b->v.n % 3 != 0)
        return sd_error_set(err, SD_ERR_INPUT, path, ln - 1, "",
                            "%s ends inside facet %zu: it has %zu vertex lines, not a multiple of 3 (truncated?)",
                            path, b->v.n / 3 + 1, b->v.n);
    if (open_facet)
        return sd_error_set(err, SD_ERR_INPUT, path, ln - 1, "",
                            "%s ends inside facet %zu (begun at line %d, no endfacet: truncated?)", path, open_facet,
                            open_line);
    b->corner.n = ((size_t *)b->start.p)[b->start.n - 1];
    return SD_OK;
}

sd_status sd_mesh_read(const char *path, sd_mesh *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    const char *dot = strrchr(path, '.');
    int obj = dot && (!strcmp(dot, ".obj") || !strcmp(dot, ".OBJ"));
    int stl = dot && (!strcmp(dot, ".stl") || !strcmp(dot, ".STL"));
    if (!obj && !stl)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "expected an .obj or .stl file, got '%s'", path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot open the mesh file '%s': %s", path,
                            strerror(errno));
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    if (size < 0 || size > SD_MESH_MAX_BYTES || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot read the mesh file '%s' (at most 256 MiB)",
                            path);
    }
    unsigned char *buf = sd_malloc((size_t)size + 1);
    if (!buf) {
        fclose(f);
        return SD_MESH_OOM(err, path, 0);
    }
    size_t got = fread(buf, 1, (size_t)size, f);
    fclose(f);
    if (got != (size_t)size) {
        sd_free(buf);
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot read the mesh file '%s'", path);
    }
    buf[size] = '\0';
    sd_mesh_build b = {{NULL, 0, 0, sizeof(sd_v3d)},
                       {NULL, 0, 0, sizeof(size_t)},
                       {NULL, 0, 0, sizeof(uint32_t)},
                       {NULL, 0, 0, sizeof(uint32_t[3])},
                       {NULL, 0, 0, sizeof(uint32_t)}};
    sd_status st = SD_OK;
    if (!sd_mesh_buf_room(&b.start, 1)) {
        st = SD_MESH_OOM(err, path, 0);
    } else {
        ((size_t *)b.start.p)[b.start.n++] = 0;
        /* 64-bit: 84 + 50 * (2^32 - 1) does not overflow */
        unsigned long long expect = size >= 84 ? 84ull + 50ull * sd_mesh_le32(buf + 80) : 0;
        int binary = memchr(buf, '\0', (size_t)size) != NULL;
        if (size == 0)
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "", "the mesh file '%s' is empty (0 bytes)", path);
        else if (stl && size >= 84 && expect == (unsigned long long)size)
            st = sd_mesh_binary_stl(path, buf, &b, err);
        else if (stl && binary && size < 84)
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                              "'%s' is a binary STL file of %ld bytes, shorter than its 84-byte header (truncated)",
                              path, size);
        else if (stl && binary && expect > (unsigned long long)size)
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                              "'%s' is a truncated binary STL file: its header counts %llu facets (%llu bytes), the "
                              "file has %ld bytes, so facet %llu is cut off",
                              path, (expect - 84) / 50, expect, size, ((unsigned long long)size - 84) / 50 + 1);
        else if (stl && binary)
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                              "'%s': the binary STL header counts %llu facets (%llu bytes), but the file has %ld "
                              "bytes, %llu more; the facet count or the file is wrong",
                              path, (expect - 84) / 50, expect, size, (unsigned long long)size - expect);
        else if (binary)
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                              "'%s' is neither a binary STL file (its size does not match its triangle count) "
                              "nor a text file",
                              path);
        else
            st = sd_mesh_text(path, obj, (char *)buf, &b, err);
    }
    sd_free(buf);
    if (st != SD_OK) {
        sd_mesh_build_free(&b);
        return st;
    }
    out->vertex_count = b.v.n;
    out->vertices = b.v.p;
    out->face_count = b.start.n - 1;
    out->face_start = b.start.p;
    out->corners = b.corner.p;
    out->triangle_count = b.tri.n;
    out->triangles = (uint32_t(*)[3])b.tri.p;
    out->triangle_face = b.tface.p;
    return SD_OK;
}

void sd_mesh_free(sd_mesh *m)
{
    if (!m)
        return;
    sd_free(m->vertices);
    sd_free(m->face_start);
    sd_free(m->corners);
    sd_free(m->triangles);
    sd_free(m->triangle_face);
    memset(m, 0, sizeof *m);
}

sd_v3d sd_mesh_face_centre(const sd_mesh *m, size_t f)
{
    /* from -0.0, the additive identity: the first corner's value is kept
     * bit for bit, signed zeros included */
    double cx = -0.0, cy = -0.0, cz = -0.0;
    size_t a = m->face_start[f], e = m->face_start[f + 1];
    for (size_t k = a; k < e; ++k) {
        const sd_v3d *v = &m->vertices[m->corners[k]];
        cx += v->x;
        cy += v->y;
        cz += v->z;
    }
    double n = (double)(e - a);
    return (sd_v3d){cx / n, cy / n, cz / n};
}
