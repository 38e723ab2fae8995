/* vtk_shapes.c — the shapes file of a frame (shapes_NNNNNN.vtp): every
 * particle drawn as its true surface, posed, as VTK XML PolyData.
 *
 * Invariant: a template's surface (shape/surface.h) is built once, the first
 * time a frame needs it, and afterwards only posed: x_world = x + R(q) x_body
 * (a plain sphere's unit ball scaled by its radius first), so frames never
 * re-tessellate and every frame of a run draws a template with the same
 * cells. Each cell carries its particle's fields (the point data list of
 * particle frames, io/vtk_bin.h), so ParaView colours the true shapes by
 * any of them. The file layout is the particle frame's (vtk.c): one XML
 * header with every array's offset, then the raw appended arrays.
 *
 * The particles are read through the public API; the template geometry
 * (vertex pool, composite elements, planar pools) from the world's own
 * tables, which the public sd_shape_info does not carry.
 */
#include "io/vtk.h"

#include "core/alloc.h"
#include "io/vtk_bin.h"
#include "shape/surface.h"
#include "world/world.h"

struct sd_vtk_shapes {
    int resolution;
    int planar;
    sd_surface ball;     /* plain spheres (shape -1): the unit ball */
    int ball_made;
    size_t count;        /* templates with a slot */
    sd_surface *surf;    /* per template, built on first use */
    unsigned char *made;
};

sd_status sd_vtk_shapes_make(const sd_world *w, int resolution, sd_vtk_shapes **out, sd_error *err)
{
    *out = NULL;
    if (resolution < SD_SURFACE_RES_MIN || resolution > SD_SURFACE_RES_MAX)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "output.shape_resolution",
                            "the shape resolution is %d; it must be %d to %d directions per turn", resolution,
                            SD_SURFACE_RES_MIN, SD_SURFACE_RES_MAX);
    sd_vtk_shapes *t = sd_calloc(1, sizeof *t);
    if (!t)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    t->resolution = resolution;
    t->planar = w->dim2;
    *out = t;
    return SD_OK;
}

void sd_vtk_shapes_free(sd_vtk_shapes *t)
{
    if (!t)
        return;
    for (size_t k = 0; k < t->count; ++k)
        sd_surface_free(&t->surf[k]);
    sd_surface_free(&t->ball);
    sd_free(t->surf);
    sd_free(t->made);
    sd_free(t);
}

/* The surface of template `shape` (-1: a plain sphere's unit ball), built
 * the first time it is asked for. */
sd_status sd_vtk_shapes_surface(sd_vtk_shapes *t, const sd_world *w, int shape, const sd_surface **out,
                                sd_error *err)
{
    if (shape < 0) {
        if (!t->ball_made) {
            sd_status s = sd_surface_unit_ball(t->planar, t->resolution, &t->ball, err);
            if (s != SD_OK)
                return s;
            t->ball_made = 1;
        }
        *out = &t->ball;
        return SD_OK;
    }
    size_t n = t->planar ? w->shape2d_count : w->shape_count;
    if ((size_t)shape >= n)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "a particle names shape %d of %zu", shape, n);
    if (n > t->count) { /* templates added since the last frame get slots */
        sd_surface *s2 = sd_realloc(t->surf, n * sizeof *s2);
        if (!s2)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        t->surf = s2;
        unsigned char *m2 = sd_realloc(t->made, n);
        if (!m2)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        t->made = m2;
        for (size_t k = t->count; k < n; ++k) {
            memset(&t->surf[k], 0, sizeof t->surf[k]);
            t->made[k] = 0;
        }
        t->count = n;
    }
    if (!t->made[shape]) {
        sd_status s;
        if (t->planar)
            s = sd_surface_outline(&w->shapes2d[shape], w->pool2d, t->resolution, &t->surf[shape], err);
        else if (w->shapes[shape].kind == SD_SHAPE_COMPOSITE)
            s = sd_surface_composite(&w->shapes[shape], w->elements, w->shapes, w->verts, t->resolution,
                                     &t->surf[shape], err);
        else
            s = sd_surface_convex(&w->shapes[shape], w->verts, t->resolution, &t->surf[shape], err);
        if (s != SD_OK)
            return s;
        t->made[shape] = 1;
    }
    *out = &t->surf[shape];
    return SD_OK;
}

/* Point k of surface s posed at particle p: x + R(q) (scale x_k), R of the
 * unit quaternion (w, x, y, z), scale the radius for plain spheres. */
static sd_v3d sd_vtk_pose(const sd_surface *s, size_t k, const sd_particle_state *p)
{
    double sc = p->shape < 0 ? p->radius : 1.0;
    double x = sc * s->points[3 * k], y = sc * s->points[3 * k + 1], z = sc * s->points[3 * k + 2];
    double qw = p->quat[0], qx = p->quat[1], qy = p->quat[2], qz = p->quat[3];
    /* v' = v + 2 qw (u x v) + 2 u x (u x v), u = (qx, qy, qz) */
    double cx = qy * z - qz * y, cy = qz * x - qx * z, cz = qx * y - qy * x;
    double dx = qy * cz - qz * cy, dy = qz * cx - qx * cz, dz = qx * cy - qy * cx;
    sd_v3d r = {p->position.x + x + 2.0 * (qw * cx + dx), p->position.y + y + 2.0 * (qw * cy + dy),
                p->position.z + z + 2.0 * (qw * cz + dz)};
    return r;
}

static sd_status sd_vtk_shapes_at(sd_vtk_shapes *t, const sd_world *w, size_t i, sd_particle_state *p,
                                  const sd_surface **s, sd_error *err)
{
    sd_status st = sd_vtk_get(w, i, p, err);
    return st == SD_OK ? sd_vtk_shapes_surface(t, w, p->shape, s, err) : st;
}

sd_status sd_vtk_write_shapes(FILE *fp, const sd_world *w, sd_vtk_shapes *t, sd_error *err)
{
    errno = 0; /* so that a failure below reports its own reason */
    size_t n = sd_world_particle_count(w);
    sd_particle_state p;
    const sd_surface *s = NULL;
    size_t npts = 0, ncells = 0, nconn = 0;
    for (size_t i = 0; i < n; ++i) {
        sd_status st = sd_vtk_shapes_at(t, w, i, &p, &s, err);
        if (st != SD_OK)
            return st;
        npts += s->point_count;
        ncells += s->cell_count;
        nconn += s->conn_count;
    }
    static const int comps[SD_VF_COUNT] = {
#define SD_X_COMPS(e, name, type, c, size) c,
        SD_VTK_POINT_FIELDS(SD_X_COMPS)
#undef SD_X_COMPS
    };
    static const int sizes[SD_VF_COUNT] = {
#define SD_X_SIZE(e, name, type, c, size) size,
        SD_VTK_POINT_FIELDS(SD_X_SIZE)
#undef SD_X_SIZE
    };

    uint64_t off = 0;
    sd_vtk_file_open(fp, "PolyData");
    fprintf(fp, "  <PolyData>\n");
    fprintf(fp,
            "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"%zu\">\n",
            npts, ncells);
    fprintf(fp, "      <CellData Scalars=\"shape\" Vectors=\"velocity\">\n");
#define SD_X_DECL(e, name, type, c, size) sd_vtk_array_decl(fp, "        ", type, name, c, ncells, size, &off);
    SD_VTK_POINT_FIELDS(SD_X_DECL)
#undef SD_X_DECL
    fprintf(fp, "      </CellData>\n      <Points>\n");
    sd_vtk_array_decl(fp, "        ", "Float64", "position", 3, npts, 8, &off);
    fprintf(fp, "      </Points>\n      <Polys>\n");
    sd_vtk_array_decl(fp, "        ", "Int64", "connectivity", 1, nconn, 8, &off);
    sd_vtk_array_decl(fp, "        ", "Int64", "offsets", 1, ncells, 8, &off);
    fprintf(fp, "      </Polys>\n    </Piece>\n  </PolyData>\n");
    sd_vtk_appended_open(fp);

    sd_bin b;
    b.fp = fp;
    b.used = 0;
    b.failed = 0;
    /* cell data: each particle's value once per cell of its surface */
    for (int f = 0; f < SD_VF_COUNT; ++f) {
        sd_bin_u64(&b, (uint64_t)ncells * (uint64_t)comps[f] * (uint64_t)sizes[f]);
        for (size_t i = 0; i < n; ++i) {
            sd_status st = sd_vtk_shapes_at(t, w, i, &p, &s, err);
            if (st != SD_OK)
                return st;
            for (size_t c = 0; c < s->cell_count; ++c)
                sd_vtk_put_field(&b, (sd_vtk_field)f, &p);
        }
    }
    /* pass 0: points; 1: connectivity; 2: offsets */
    for (int pass = 0; pass < 3; ++pass) {
        sd_bin_u64(&b, pass == 0 ? (uint64_t)npts * 24u : pass == 1 ? (uint64_t)nconn * 8u : (uint64_t)ncells * 8u);
        int64_t base = 0, end = 0; /* the particle's first point; running cell end */
        for (size_t i = 0; i < n; ++i) {
            sd_status st = sd_vtk_shapes_at(t, w, i, &p, &s, err);
            if (st != SD_OK)
                return st;
            if (pass == 0)
                for (size_t k = 0; k < s->point_count; ++k)
                    sd_bin_v3(&b, sd_vtk_pose(s, k, &p));
            else if (pass == 1)
                for (size_t k = 0; k < s->conn_count; ++k)
                    sd_bin_i64(&b, base + s->conn[k]);
            else
                for (size_t c = 0; c < s->cell_count; ++c)
                    sd_bin_i64(&b, end + s->ends[c]);
            base += (int64_t)s->point_count;
            end += (int64_t)s->conn_count;
        }
    }
    sd_status st = sd_vtk_bin_status(&b, err);
    if (st != SD_OK)
        return st;
    sd_vtk_appended_close(fp);
    return sd_vtk_stream_status(fp, err);
}
