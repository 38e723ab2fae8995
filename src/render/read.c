/* read.c — reading a frame back from the VTK XML files of a run (see
 * render.h for the invariant): particles_NNNNNN.vtu, shapes_NNNNNN.vtp,
 * walls_NNNNNN.vtp and frames.pvd, as io/vtk.c writes them (docs/output.md:
 * an XML header that lists each DataArray and its offset, then raw appended
 * data, each array a little-endian UInt64 byte count and its values).
 *
 * Context-free: bytes in, a frame or a reason out. Every count, offset and
 * index is checked against the file before it is used.
 */
#define _POSIX_C_SOURCE 200809L

#include "render/render.h"

#include "core/alloc.h"
#include "core/error.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the file ------------------------------------------------------------ */

typedef struct sd_vtkfile {
    char *bytes;
    size_t size;
    size_t head;           /* bytes of the XML header (up to <AppendedData) */
    size_t data;           /* first byte after the '_' of the appended data */
    int polydata;          /* PolyData (.vtp), else UnstructuredGrid (.vtu) */
    size_t npts, ncells;
    const char *path;
} sd_vtkfile;

static sd_status sd_rd_fail(const char *path, sd_error *err, const char *what)
{
    return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "not a shapedem frame: %s", what);
}

static sd_status sd_rd_slurp(const char *path, char **bytes, size_t *size, sd_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot open: %s", strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *b = sd_malloc(cap + 1);
    while (b) {
        size_t got = fread(b + n, 1, cap - n, fp);
        n += got;
        if (n < cap)
            break;
        char *b2 = sd_realloc(b, 2 * cap + 1);
        if (!b2) {
            sd_free(b);
            b = NULL;
            break;
        }
        b = b2;
        cap *= 2;
    }
    int bad = ferror(fp);
    fclose(fp);
    if (!b)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    if (bad) {
        sd_free(b);
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot read (is it a directory?)");
    }
    b[n] = 0;
    *bytes = b;
    *size = n;
    return SD_OK;
}

/* Value of attribute `name` in the tag starting at tag (up to its '>'):
 * copied into buf; 0 when absent. */
static int sd_rd_attr(const char *tag, const char *end, const char *name, char *buf, size_t size)
{
    size_t ln = strlen(name);
    for (const char *p = tag; p + ln + 2 < end; ++p) {
        if ((p == tag || p[-1] == ' ' || p[-1] == '\n' || p[-1] == '\t') && !strncmp(p, name, ln) &&
            p[ln] == '=' && p[ln + 1] == '"') {
            const char *v = p + ln + 2, *q = v;
            while (q < end && *q != '"')
                ++q;
            if (q >= end)
                return 0;
            size_t m = (size_t)(q - v) < size - 1 ? (size_t)(q - v) : size - 1;
            memcpy(buf, v, m);
            buf[m] = 0;
            return 1;
        }
    }
    return 0;
}

static int sd_rd_size(const char *s, size_t *out)
{
    char *e;
    errno = 0;
    unsigned long long v = strtoull(s, &e, 10);
    if (e == s || *e || errno || s[0] == '-')
        return 0;
    *out = (size_t)v;
    return 1;
}

static sd_status sd_rd_open(const char *path, sd_vtkfile *f, sd_error *err)
{
    memset(f, 0, sizeof *f);
    f->path = path;
    sd_status s = sd_rd_slurp(path, &f->bytes, &f->size, err);
    if (s != SD_OK)
        return s;
    const char *b = f->bytes;
    const char *vf = strstr(b, "<VTKFile ");
    const char *ap = strstr(b, "<AppendedData encoding=\"raw\">");
    if (!vf || !ap || vf > ap)
        return sd_rd_fail(path, err, "no VTK XML header with raw appended data (docs/output.md)");
    f->head = (size_t)(ap - b);
    const char *vend = strchr(vf, '>');
    char buf[64];
    if (!vend || !sd_rd_attr(vf, vend, "type", buf, sizeof buf))
        return sd_rd_fail(path, err, "the VTKFile tag has no type");
    if (!strcmp(buf, "PolyData"))
        f->polydata = 1;
    else if (strcmp(buf, "UnstructuredGrid"))
        return sd_rd_fail(path, err, "a VTK file of another type than UnstructuredGrid or PolyData");
    if (!sd_rd_attr(vf, vend, "byte_order", buf, sizeof buf) || strcmp(buf, "LittleEndian") ||
        !sd_rd_attr(vf, vend, "header_type", buf, sizeof buf) || strcmp(buf, "UInt64"))
        return sd_rd_fail(path, err, "not little-endian with UInt64 headers");
    const char *u = ap + strlen("<AppendedData encoding=\"raw\">");
    while (u < b + f->size && (*u == ' ' || *u == '\n' || *u == '\r' || *u == '\t'))
        ++u;
    if (u >= b + f->size || *u != '_')
        return sd_rd_fail(path, err, "the appended data does not start with '_'");
    f->data = (size_t)(u + 1 - b);
    const char *piece = strstr(b, "<Piece ");
    if (!piece || piece > ap)
        return sd_rd_fail(path, err, "no Piece");
    const char *pend = strchr(piece, '>');
    if (!pend || !sd_rd_attr(piece, pend, "NumberOfPoints", buf, sizeof buf) || !sd_rd_size(buf, &f->npts) ||
        !sd_rd_attr(piece, pend, f->polydata ? "NumberOfPolys" : "NumberOfCells", buf, sizeof buf) ||
        !sd_rd_size(buf, &f->ncells))
        return sd_rd_fail(path, err, "the Piece has no point or cell count");
    return SD_OK;
}

/* The array named `name` in section `section` (PointData, CellData,
 * Points, Cells, Polys) as doubles; *count values of `comps` components
 * each. 0 with *out NULL when the file has no such array. */
static sd_status sd_rd_array(const sd_vtkfile *f, const char *section, const char *name, int want_comps,
                             double **out, size_t *count, int *comps_out, sd_error *err)
{
    *out = NULL;
    char open[40], close[40];
    snprintf(open, sizeof open, "<%s", section);
    snprintf(close, sizeof close, "</%s>", section);
    const char *b = f->bytes, *hend = f->bytes + f->head;
    const char *sec = strstr(b, open);
    while (sec && sec < hend && sec[strlen(open)] != '>' && sec[strlen(open)] != ' ')
        sec = strstr(sec + 1, open);
    if (!sec || sec >= hend)
        return SD_OK;
    const char *secend = strstr(sec, close);
    if (!secend || secend > hend)
        return sd_rd_fail(f->path, err, "a section is not closed");
    for (const char *t = strstr(sec, "<DataArray "); t && t < secend; t = strstr(t + 1, "<DataArray ")) {
        const char *tend = strchr(t, '>');
        char nm[80], type[32], buf[40];
        if (!tend || !sd_rd_attr(t, tend, "Name", nm, sizeof nm) || strcmp(nm, name))
            continue;
        size_t comps = 1, off;
        if (sd_rd_attr(t, tend, "NumberOfComponents", buf, sizeof buf) && (!sd_rd_size(buf, &comps) || comps < 1 || comps > 9))
            return sd_rd_fail(f->path, err, "a DataArray has a bad NumberOfComponents");
        if (want_comps && (int)comps != want_comps)
            return sd_rd_fail(f->path, err, "an array has an unexpected number of components");
        if (!sd_rd_attr(t, tend, "type", type, sizeof type) || !sd_rd_attr(t, tend, "offset", buf, sizeof buf) ||
            !sd_rd_size(buf, &off))
            return sd_rd_fail(f->path, err, "a DataArray has no type or offset");
        size_t vs = !strcmp(type, "Float64") || !strcmp(type, "Int64") || !strcmp(type, "UInt64") ? 8
                  : !strcmp(type, "Int32") || !strcmp(type, "Float32")                           ? 4
                  : !strcmp(type, "UInt8")                                                       ? 1
                                                                                                 : 0;
        if (!vs)
            return sd_rd_fail(f->path, err, "a DataArray of a type shapedem does not write");
        if (off > f->size || f->size - off < f->data || f->size - f->data - off < 8)
            return sd_rd_fail(f->path, err, "an array's offset is past the end of the file");
        const unsigned char *p = (const unsigned char *)f->bytes + f->data + off;
        uint64_t nbytes = 0;
        for (int k = 0; k < 8; ++k)
            nbytes |= (uint64_t)p[k] << (8 * k);
        p += 8;
        size_t left = f->size - f->data - off - 8;
        if (nbytes > left || nbytes % (vs * comps))
            return sd_rd_fail(f->path, err, "an array is cut short (the file is truncated?)");
        size_t n = (size_t)(nbytes / (vs * comps));
        size_t nv = n * comps;
        double *v = sd_malloc((nv ? nv : 1) * sizeof *v);
        if (!v)
            return sd_error_set(err, SD_ERR_MEMORY, f->path, 0, "", "out of memory");
        for (size_t i = 0; i < n * comps; ++i) {
            uint64_t u = 0;
            for (size_t k = 0; k < vs; ++k)
                u |= (uint64_t)p[vs * i + k] << (8 * k);
            double x;
            if (!strcmp(type, "Float64"))
                memcpy(&x, &u, 8);
            else if (!strcmp(type, "Float32")) {
                uint32_t u32 = (uint32_t)u;
                float fl;
                memcpy(&fl, &u32, 4);
                x = (double)fl;
            } else if (!strcmp(type, "Int64"))
                x = (double)(int64_t)u;
            else if (!strcmp(type, "Int32"))
                x = (double)(int32_t)(uint32_t)u;
            else
                x = (double)u;
            v[i] = x;
        }
        *out = v;
        *count = n;
        if (comps_out)
            *comps_out = (int)comps;
        return SD_OK;
    }
    return SD_OK;
}

/* The DataArray names of a section, comma separated, for messages. */
static void sd_rd_names(const sd_vtkfile *f, const char *section, char *buf, size_t size)
{
    buf[0] = 0;
    char open[40];
    snprintf(open, sizeof open, "<%s", section);
    const char *hend = f->bytes + f->head, *sec = strstr(f->bytes, open);
    if (!sec || sec >= hend)
        return;
    const char *secend = strstr(sec, "</");
    size_t used = 0;
    for (const char *t = strstr(sec, "<DataArray "); t && t < hend && (!secend || t < secend);
         t = strstr(t + 1, "<DataArray ")) {
        const char *tend = strchr(t, '>');
        char nm[80];
        if (tend && sd_rd_attr(t, tend, "Name", nm, sizeof nm)) {
            int w = snprintf(buf + used, size - used, "%s%s", used ? ", " : "", nm);
            if (w < 0 || (size_t)w >= size - used)
                break;
            used += (size_t)w;
        }
    }
    if (used)
        snprintf(buf + used, size - used, ", speed");
}

/* Field `field` of section per item (n items): speed = |velocity|, vectors
 * by their magnitude. */
static sd_status sd_rd_field(const sd_vtkfile *f, const char *section, const char *field, size_t n, double **out,
                             sd_error *err)
{
    const char *name = !strcmp(field, "speed") ? "velocity" : field;
    double *v = NULL;
    size_t count = 0;
    int comps = 1;
    sd_status s = sd_rd_array(f, section, name, 0, &v, &count, &comps, err);
    if (s != SD_OK)
        return s;
    if (!v) {
        char names[600];
        sd_rd_names(f, section, names, sizeof names);
        return sd_error_set(err, SD_ERR_INPUT, f->path, 0, "--field",
                            "the frame has no field '%s' (it has: %s)", field, names[0] ? names : "none");
    }
    if (count != n) {
        sd_free(v);
        return sd_rd_fail(f->path, err, "a field's length is not the number of particles");
    }
    double *r = sd_malloc((n ? n : 1) * sizeof *r);
    if (!r) {
        sd_free(v);
        return sd_error_set(err, SD_ERR_MEMORY, f->path, 0, "", "out of memory");
    }
    for (size_t i = 0; i < n; ++i) {
        double m = 0.0;
        if (comps == 1)
            m = v[i];
        else
            for (int c = 0; c < comps; ++c)
                m += v[(size_t)comps * i + (size_t)c] * v[(size_t)comps * i + (size_t)c];
        r[i] = comps == 1 ? m : sqrt(m);
    }
    sd_free(v);
    *out = r;
    return SD_OK;
}

/* Points, connectivity and cell ends of a PolyData's polygons (or a
 * grid's cells), every index checked. */
static sd_status sd_rd_polys(const sd_vtkfile *f, double **pts, int64_t **conn, size_t *nconn, int64_t **ends,
                             sd_error *err)
{
    const char *cells = f->polydata ? "Polys" : "Cells";
    double *p = NULL, *c = NULL, *o = NULL;
    size_t np = 0, nc = 0, no = 0;
    sd_status s = sd_rd_array(f, "Points", "position", 3, &p, &np, NULL, err);
    if (s == SD_OK)
        s = sd_rd_array(f, cells, "connectivity", 1, &c, &nc, NULL, err);
    if (s == SD_OK)
        s = sd_rd_array(f, cells, "offsets", 1, &o, &no, NULL, err);
    if (s == SD_OK && (!p || np != f->npts))
        s = sd_rd_fail(f->path, err, "the points do not match NumberOfPoints");
    if (s == SD_OK && (!c || !o || no != f->ncells))
        s = sd_rd_fail(f->path, err, "the cells do not match the cell count");
    int64_t *ci = NULL, *ei = NULL;
    if (s == SD_OK) {
        ci = sd_malloc((nc ? nc : 1) * sizeof *ci);
        ei = sd_malloc((no ? no : 1) * sizeof *ei);
        if (!ci || !ei)
            s = sd_error_set(err, SD_ERR_MEMORY, f->path, 0, "", "out of memory");
    }
    for (size_t k = 0; s == SD_OK && k < nc; ++k) {
        if (!(c[k] >= 0 && c[k] < (double)np))
            s = sd_rd_fail(f->path, err, "a cell names a point that is not there");
        else
            ci[k] = (int64_t)c[k];
    }
    double prev = 0.0;
    for (size_t k = 0; s == SD_OK && k < no; ++k) {
        if (!(o[k] >= prev && o[k] <= (double)nc))
            s = sd_rd_fail(f->path, err, "the cell offsets are not increasing within the connectivity");
        else
            ei[k] = (int64_t)(prev = o[k]);
    }
    if (s == SD_OK && no > 0 && ei[no - 1] != (int64_t)nc)
        s = sd_rd_fail(f->path, err, "the last cell offset is not the connectivity's end");
    sd_free(c);
    sd_free(o);
    if (s != SD_OK) {
        sd_free(p);
        sd_free(ci);
        sd_free(ei);
        return s;
    }
    *pts = p;
    *conn = ci;
    *nconn = nc;
    *ends = ei;
    return SD_OK;
}

/* ---- a frame ------------------------------------------------------------ */

/* dir/prefix + the digits of base's NNNNNN + suffix; path's base name
 * starts with `from` (the caller checks). */
static void sd_rd_sibling(const char *path, const char *from, const char *prefix, const char *suffix, char *out,
                          size_t size)
{
    const char *slash = strrchr(path, '/');
    size_t dirlen = slash ? (size_t)(slash + 1 - path) : 0;
    const char *digits = path + dirlen + strlen(from);
    size_t nd = 0;
    while (digits[nd] >= '0' && digits[nd] <= '9')
        ++nd;
    snprintf(out, size, "%.*s%s%.*s%s", (int)dirlen, path, prefix, (int)nd, digits, suffix);
}

static int sd_rd_exists(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (fp)
        fclose(fp);
    return fp != NULL;
}

void sd_render_frame_free(sd_render_frame *f)
{
    if (!f)
        return;
    sd_free(f->points);
    sd_free(f->conn);
    sd_free(f->ends);
    sd_free(f->cell_value);
    sd_free(f->cell_id);
    sd_free(f->centres);
    sd_free(f->radii);
    sd_free(f->sphere_value);
    sd_free(f->wall_points);
    sd_free(f->wall_conn);
    sd_free(f->wall_ends);
    sd_free(f->wall_fit);
    sd_free(f->names);
    memset(f, 0, sizeof *f);
}

static sd_status sd_rd_shapes(const char *path, const char *field, sd_render_frame *out, sd_error *err)
{
    sd_vtkfile f;
    sd_status s = sd_rd_open(path, &f, err);
    if (s == SD_OK && !f.polydata)
        s = sd_rd_fail(path, err, "a shapes file is PolyData");
    if (s == SD_OK)
        s = sd_rd_polys(&f, &out->points, &out->conn, &out->conn_count, &out->ends, err);
    if (s == SD_OK) {
        out->point_count = f.npts;
        out->cell_count = f.ncells;
        s = sd_rd_field(&f, "CellData", field, f.ncells, &out->cell_value, err);
    }
    if (s == SD_OK)
        s = sd_rd_field(&f, "CellData", "id", f.ncells, &out->cell_id, err);
    sd_free(f.bytes);
    return s;
}

static sd_status sd_rd_spheres(const char *path, const char *field, sd_render_frame *out, sd_error *err)
{
    sd_vtkfile f;
    sd_status s = sd_rd_open(path, &f, err);
    if (s == SD_OK && f.polydata)
        s = sd_rd_fail(path, err, "a particle frame is an UnstructuredGrid (.vtu)");
    size_t n = 0;
    double *shape = NULL;
    if (s == SD_OK)
        s = sd_rd_array(&f, "Points", "position", 3, &out->centres, &n, NULL, err);
    if (s == SD_OK && (!out->centres || n != f.npts))
        s = sd_rd_fail(path, err, "the points do not match NumberOfPoints");
    if (s == SD_OK)
        s = sd_rd_array(&f, "PointData", "radius", 1, &out->radii, &n, NULL, err);
    if (s == SD_OK && (!out->radii || n != f.npts))
        s = sd_rd_fail(path, err, "no radius per particle");
    if (s == SD_OK)
        s = sd_rd_field(&f, "PointData", field, f.npts, &out->sphere_value, err);
    if (s == SD_OK)
        s = sd_rd_array(&f, "PointData", "shape", 1, &shape, &n, NULL, err);
    if (s == SD_OK) {
        out->sphere_count = f.npts;
        for (size_t i = 0; shape && i < n; ++i)
            if (shape[i] >= 0)
                out->bounding_spheres = 1;
    }
    sd_free(shape);
    sd_free(f.bytes);
    return s;
}

static sd_status sd_rd_walls(const char *path, sd_render_frame *out, sd_error *err)
{
    sd_vtkfile f;
    sd_status s = sd_rd_open(path, &f, err);
    if (s == SD_OK && !f.polydata)
        s = sd_rd_fail(path, err, "a walls file is PolyData");
    if (s == SD_OK)
        s = sd_rd_polys(&f, &out->wall_points, &out->wall_conn, &out->wall_conn_count, &out->wall_ends, err);
    if (s == SD_OK) {
        out->wall_point_count = f.npts;
        out->wall_cell_count = f.ncells;
    }
    /* each cell's wall kind (0 plane, 1 box, 2 mesh, 3 drum), written since
     * issue 31; older files lack it and fit every wall */
    double *kind = NULL;
    size_t nk = 0;
    if (s == SD_OK)
        s = sd_rd_array(&f, "CellData", "kind", 1, &kind, &nk, NULL, err);
    if (s == SD_OK && kind && nk != f.ncells)
        s = sd_rd_fail(path, err, "the walls' kind array is not one per cell");
    if (s == SD_OK && kind) {
        out->wall_fit = sd_malloc(nk ? nk : 1);
        if (!out->wall_fit)
            s = sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
        for (size_t k = 0; s == SD_OK && k < nk; ++k)
            out->wall_fit[k] = kind[k] != 0.0;
    }
    sd_free(kind);
    sd_free(f.bytes);
    return s;
}

/* The names of a FieldData String array (`shape_names`, `material_names`:
 * each name's bytes in decimal, each ended by a 0, docs/output.md) into
 * *names (*count of them, at most max_count; 63 bytes each, bytes that are
 * not printable ASCII shown as '?'). *names NULL when the file has none. */
static sd_status sd_rd_string_array(const sd_vtkfile *f, const char *array, size_t max_count, char (**names)[64],
                                    size_t *count, sd_error *err)
{
    *names = NULL;
    *count = 0;
    const char *b = f->bytes, *hend = f->bytes + f->head;
    for (const char *t = strstr(b, "<Array "); t && t < hend; t = strstr(t + 1, "<Array ")) {
        const char *tend = strchr(t, '>');
        char nm[80], buf[40];
        size_t n;
        if (!tend || tend >= hend || !sd_rd_attr(t, tend, "Name", nm, sizeof nm) || strcmp(nm, array))
            continue;
        if (!sd_rd_attr(t, tend, "type", buf, sizeof buf) || strcmp(buf, "String") ||
            !sd_rd_attr(t, tend, "NumberOfTuples", buf, sizeof buf) || !sd_rd_size(buf, &n))
            return sd_rd_fail(f->path, err, "a field-data name array is not a String array with a count");
        if (n > max_count)
            n = max_count;
        char(*v)[64] = sd_calloc(n ? n : 1, sizeof *v);
        if (!v)
            return sd_error_set(err, SD_ERR_MEMORY, f->path, 0, "", "out of memory");
        const char *p = tend + 1, *close = strstr(p, "</Array>");
        if (!close || close > hend)
            close = hend;
        size_t k = 0, len = 0;
        while (k < n && p < close) {
            while (p < close && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t'))
                ++p;
            if (p >= close)
                break;
            char *e;
            long c = strtol(p, &e, 10);
            if (e == p || e > close || c < 0 || c > 255) {
                sd_free(v);
                return sd_rd_fail(f->path, err, "a field-data name array holds something other than bytes");
            }
            p = e;
            if (c == 0) {
                ++k;
                len = 0;
            } else if (len < 63) {
                v[k][len++] = c >= 32 && c < 127 ? (char)c : '?';
            }
        }
        *names = v;
        *count = k;
        return SD_OK;
    }
    return SD_OK;
}

/* The units of the particle fields a frame carries (docs/output.md's
 * table of particles_NNNNNN.vtu, io/vtk_bin.h's SD_VTK_POINT_FIELDS): the
 * reader takes any file, so the table is kept here, by name. */
#define SD_RENDER_FIELD_UNITS(X)                                                                                       \
    X("speed", "m/s", 0)                                                                                               \
    X("velocity", "m/s", 0)                                                                                            \
    X("radius", "m", 0)                                                                                                \
    X("angular_velocity", "rad/s", 0)                                                                                  \
    X("force", "N", 0)                                                                                                 \
    X("shape", "", 1)                                                                                                  \
    X("material", "", 1)

const char *sd_render_field_unit(const char *field, int *categorical)
{
    static const struct {
        const char *name, *unit;
        int categorical;
    } table[] = {
#define SD_X_UNIT(n, u, c) {n, u, c},
        SD_RENDER_FIELD_UNITS(SD_X_UNIT)
#undef SD_X_UNIT
    };
    for (size_t k = 0; k < sizeof table / sizeof table[0]; ++k)
        if (!strcmp(field, table[k].name)) {
            if (categorical)
                *categorical = table[k].categorical;
            return table[k].unit;
        }
    if (categorical)
        *categorical = 0;
    return "";
}

/* The largest number of categories a legend names; a field with more
 * indices than that is not a category (and a forged count is bounded). */
#define SD_RENDER_CATEGORIES_MAX 4096

/* A categorical field's names: the frame's own field data, else (a shapes
 * file, which carries none) its particles sibling's; indices without a name
 * get "shape K" / "material K". */
static sd_status sd_rd_categories(sd_render_frame *out, const char *path, const char *particles, sd_error *err)
{
    out->category_first = !strcmp(out->field, "shape") ? -1 : 0;
    char array[80];
    snprintf(array, sizeof array, "%s_names", out->field);
    char(*names)[64] = NULL;
    size_t count = 0;
    const char *from[2] = {path, particles};
    for (int k = 0; k < 2 && !names; ++k) {
        if (!from[k] || !from[k][0] || !sd_rd_exists(from[k]))
            continue;
        sd_vtkfile f;
        sd_status s = sd_rd_open(from[k], &f, err);
        if (s == SD_OK)
            s = sd_rd_string_array(&f, array, SD_RENDER_CATEGORIES_MAX, &names, &count, err);
        sd_free(f.bytes);
        if (s != SD_OK && k == 0)
            return s;
    }
    /* every index the frame uses gets a name: indices 0 .. need - 1 */
    double lo, hi;
    sd_render_frame_range(out, &lo, &hi);
    if (!(lo >= (double)out->category_first) || !(hi < (double)SD_RENDER_CATEGORIES_MAX)) {
        sd_free(names); /* not indices: drawn as a scale */
        out->categorical = 0;
        return SD_OK;
    }
    size_t need = hi >= 0.0 && (size_t)hi + 1 > count ? (size_t)hi + 1 : count;
    size_t total = need + (out->category_first < 0);
    char(*all)[64] = sd_calloc(total ? total : 1, sizeof *all);
    if (!all) {
        sd_free(names);
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    }
    size_t j = 0;
    if (out->category_first < 0)
        snprintf(all[j++], 64, "sphere");
    for (size_t k = 0; k < need; ++k, ++j) {
        if (k < count && names[k][0])
            memcpy(all[j], names[k], 64);
        else
            snprintf(all[j], 64, "%.40s %zu", out->field, k);
    }
    sd_free(names);
    out->names = all;
    out->category_count = total;
    return SD_OK;
}

double sd_render_category_t(const sd_render_frame *f, double v)
{
    double n = (double)f->category_count;
    return n > 1 ? (v - (double)f->category_first) / (n - 1.0) : 0.5;
}

void sd_render_describe(const sd_render_frame *f, const sd_render_def *d, char *buf, size_t size)
{
    size_t n = f->sphere_count, used = 0;
    for (size_t k = 0; k < f->cell_count; ++k) /* a particle's cells are consecutive */
        n += k == 0 || f->cell_id[k] != f->cell_id[k - 1];
    int w = snprintf(buf, size, "%zu particle%s coloured by %s", n, n == 1 ? "" : "s", f->field);
    used = w > 0 && (size_t)w < size ? (size_t)w : size - 1;
    if (!f->categorical) {
        double lo = d->lo, hi = d->hi;
        if (!d->fixed_range)
            sd_render_frame_range(f, &lo, &hi);
        w = snprintf(buf + used, size - used, ", %.4g .. %.4g%s%s", lo, hi, f->unit[0] ? " " : "", f->unit);
        used = w > 0 && used + (size_t)w < size ? used + (size_t)w : size - 1;
    }
    /* the categories present, in index order, with their counts */
    int listed = 0;
    for (size_t c = 0; f->categorical && c < f->category_count && used + 1 < size; ++c) {
        double v = (double)f->category_first + (double)c;
        size_t m = 0;
        for (size_t k = 0; k < f->sphere_count; ++k)
            m += f->sphere_value[k] == v;
        for (size_t k = 0; k < f->cell_count; ++k)
            m += f->cell_value[k] == v && (k == 0 || f->cell_id[k] != f->cell_id[k - 1]);
        if (!m)
            continue;
        w = snprintf(buf + used, size - used, "%s%s (%zu)", listed++ ? ", " : ": ", f->names[c], m);
        used = w > 0 && used + (size_t)w < size ? used + (size_t)w : size - 1;
    }
    if (f->not_finite && used + 1 < size)
        snprintf(buf + used, size - used, "; %zu more not drawn (a position or radius not finite)", f->not_finite);
}

sd_status sd_render_frame_load(const char *path, const char *field, sd_render_frame *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->field, sizeof out->field, "%s", field);
    snprintf(out->source, sizeof out->source, "%s", path);
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    char shapes[SD_RENDER_PATH_MAX], walls[SD_RENDER_PATH_MAX];
    sd_status s;
    int is_shapes = !strncmp(base, "shapes_", 7);
    if (!sd_rd_exists(path))
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot read the frame: %s", strerror(errno));
    int is_particles = !strncmp(base, "particles_", 10);
    shapes[0] = walls[0] = 0; /* a file of another name has no siblings */
    if (is_shapes) {
        snprintf(shapes, sizeof shapes, "%s", path);
        sd_rd_sibling(path, "shapes_", "walls_", ".vtp", walls, sizeof walls);
    } else if (is_particles) {
        sd_rd_sibling(path, "particles_", "shapes_", ".vtp", shapes, sizeof shapes);
        sd_rd_sibling(path, "particles_", "walls_", ".vtp", walls, sizeof walls);
    }
    if (is_shapes || (is_particles && sd_rd_exists(shapes))) {
        s = sd_rd_shapes(shapes, field, out, err);
    } else {
        s = sd_rd_spheres(path, field, out, err);
    }
    if (s == SD_OK && (is_particles || is_shapes) && sd_rd_exists(walls))
        s = sd_rd_walls(walls, out, err);
    snprintf(out->unit, sizeof out->unit, "%s", sd_render_field_unit(field, &out->categorical));
    if (s == SD_OK && out->categorical) {
        char particles[SD_RENDER_PATH_MAX] = "";
        if (is_shapes)
            sd_rd_sibling(path, "shapes_", "particles_", ".vtu", particles, sizeof particles);
        s = sd_rd_categories(out, is_shapes ? "" : path, particles, err);
    }
    if (s != SD_OK) {
        sd_render_frame_free(out);
        return s;
    }
    int planar = out->point_count + out->sphere_count > 0;
    for (size_t k = 0; planar && k < out->point_count; ++k)
        planar = out->points[3 * k + 2] == 0.0;
    for (size_t k = 0; planar && k < out->sphere_count; ++k)
        planar = out->centres[3 * k + 2] == 0.0;
    out->planar = planar;
    return SD_OK;
}

void sd_render_frame_range(const sd_render_frame *f, double *lo, double *hi)
{
    double a = INFINITY, b = -INFINITY;
    for (size_t k = 0; k < f->cell_count; ++k) {
        a = fmin(a, f->cell_value[k]);
        b = fmax(b, f->cell_value[k]);
    }
    for (size_t k = 0; k < f->sphere_count; ++k) {
        a = fmin(a, f->sphere_value[k]);
        b = fmax(b, f->sphere_value[k]);
    }
    if (!(a <= b))
        a = b = 0.0;
    *lo = a;
    *hi = b;
}

/* ---- particles handed over as arrays (a checkpoint's) -------------------- */

sd_status sd_render_frame_particles(const sd_render_particles *p, const char *field, sd_render_frame *out,
                                    sd_error *err)
{
    memset(out, 0, sizeof *out);
    const char *src = p->source ? p->source : "";
    snprintf(out->field, sizeof out->field, "%s", field);
    snprintf(out->source, sizeof out->source, "%s", src);
    /* the field: a vector by its magnitude, as from a frame's arrays */
    const double *vec = NULL;
    int which = 0; /* 1 radius, 2 id, 3 shape, 4 material */
    if (!strcmp(field, "speed") || !strcmp(field, "velocity"))
        vec = p->v;
    else if (!strcmp(field, "angular_velocity"))
        vec = p->w;
    else if (!strcmp(field, "force"))
        vec = p->f;
    else if (!strcmp(field, "radius"))
        which = 1;
    else if (!strcmp(field, "id"))
        which = 2;
    else if (!strcmp(field, "shape"))
        which = 3;
    else if (!strcmp(field, "material"))
        which = 4;
    else
        return sd_error_set(err, SD_ERR_INPUT, src, 0, "--field",
                            "the checkpoint has no field '%s' (it has: speed, velocity, radius, angular_velocity, "
                            "force, id, shape, material)", field);
    size_t n = p->n;
    out->centres = sd_malloc((n ? 3 * n : 1) * sizeof *out->centres);
    out->radii = sd_malloc((n ? n : 1) * sizeof *out->radii);
    out->sphere_value = sd_malloc((n ? n : 1) * sizeof *out->sphere_value);
    if (!out->centres || !out->radii || !out->sphere_value) {
        sd_render_frame_free(out);
        return sd_error_set(err, SD_ERR_MEMORY, src, 0, "", "out of memory");
    }
    size_t m = 0; /* spheres kept: a failed-NNNNNN.h5 may hold a state that is not finite */
    for (size_t k = 0; k < n; ++k) {
        if (!isfinite(p->x[3 * k]) || !isfinite(p->x[3 * k + 1]) || !isfinite(p->x[3 * k + 2]) ||
            !isfinite(p->radius[k])) {
            out->not_finite++;
            continue;
        }
        memcpy(out->centres + 3 * m, p->x + 3 * k, 3 * sizeof(double));
        out->radii[m] = p->radius[k];
        double val = 0.0;
        if (vec)
            val = sqrt(vec[3 * k] * vec[3 * k] + vec[3 * k + 1] * vec[3 * k + 1] + vec[3 * k + 2] * vec[3 * k + 2]);
        else
            val = which == 1 ? p->radius[k]
                : which == 2 ? (double)p->id[k]
                : which == 3 ? (double)p->shape[k]
                             : (double)p->material[k];
        out->sphere_value[m++] = val;
        if (p->shape[k] >= 0)
            out->bounding_spheres = 1;
    }
    out->sphere_count = m;
    int planar = m > 0;
    for (size_t k = 0; planar && k < m; ++k)
        planar = out->centres[3 * k + 2] == 0.0;
    out->planar = planar;
    snprintf(out->unit, sizeof out->unit, "%s", sd_render_field_unit(field, &out->categorical));
    if (out->categorical) { /* the names the checkpoint keeps (scene/shape_names, scene/material_names) */
        int shape = which == 3;
        size_t count = shape ? p->shape_count : p->material_count;
        out->category_first = shape ? -1 : 0;
        out->category_count = count + (size_t)shape;
        out->names = sd_calloc(out->category_count ? out->category_count : 1, sizeof *out->names);
        if (!out->names) {
            sd_render_frame_free(out);
            return sd_error_set(err, SD_ERR_MEMORY, src, 0, "", "out of memory");
        }
        if (shape)
            snprintf(out->names[0], 64, "sphere");
        for (size_t k = 0; k < count; ++k)
            snprintf(out->names[k + (size_t)shape], 64, "%s", shape ? p->shape_names[k] : p->material_names[k]);
    }
    return SD_OK;
}

/* ---- frames.pvd ---------------------------------------------------------- */

sd_status sd_render_pvd_list(const char *pvd, char ***paths, size_t *count, sd_error *err)
{
    *paths = NULL;
    *count = 0;
    char *b;
    size_t size;
    sd_status s = sd_rd_slurp(pvd, &b, &size, err);
    if (s != SD_OK)
        return s;
    if (!strstr(b, "<VTKFile type=\"Collection\"")) {
        sd_free(b);
        return sd_error_set(err, SD_ERR_INPUT, pvd, 0, "", "not a frames.pvd: no VTK Collection");
    }
    size_t n = 0;
    for (const char *t = strstr(b, "<DataSet "); t; t = strstr(t + 1, "<DataSet "))
        ++n;
    const char *slash = strrchr(pvd, '/');
    int dirlen = slash ? (int)(slash + 1 - pvd) : 0;
    /* One block: the n pointers, then the names packed. Each file attribute
     * is a part of the text of its own tag and decoding never lengthens it,
     * so the text's size plus a directory and a NUL per entry holds them
     * all (a fixed 4 KB per entry took 420 MB for 10^5 frames). */
    size_t slots = n ? n : 1, text = size + n * ((size_t)dirlen + 1) + 1;
    char **list = sd_malloc(slots * sizeof *list + text);
    if (!list) {
        sd_free(b);
        return sd_error_set(err, SD_ERR_MEMORY, pvd, 0, "", "out of memory");
    }
    char *at = (char *)(list + slots);
    size_t k = 0;
    for (const char *t = strstr(b, "<DataSet "); t; t = strstr(t + 1, "<DataSet ")) {
        const char *tend = strchr(t, '>');
        char part[16], file[SD_RENDER_PATH_MAX - 256];
        if (!tend || !sd_rd_attr(t, tend, "file", file, sizeof file))
            continue;
        if (sd_rd_attr(t, tend, "part", part, sizeof part) && strcmp(part, "0"))
            continue; /* walls and shapes come with their particle file */
        int w = file[0] == '/' ? snprintf(at, SD_RENDER_PATH_MAX, "%s", file)
                               : snprintf(at, SD_RENDER_PATH_MAX, "%.*s%s", dirlen, pvd, file);
        list[k++] = at;
        at += (w < SD_RENDER_PATH_MAX - 1 ? w : SD_RENDER_PATH_MAX - 1) + 1;
    }
    sd_free(b);
    if (k == 0) {
        sd_free(list);
        return sd_error_set(err, SD_ERR_INPUT, pvd, 0, "", "the collection lists no particle frames");
    }
    *paths = list;
    *count = k;
    return SD_OK;
}
