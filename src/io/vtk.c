/* vtk.c — VTK XML writers for frames (see vtk.h for the invariant).
 *
 * File layout (VTK XML, "appended" raw data): an XML header that lists each
 * DataArray with its byte offset into the appended block, then
 * <AppendedData encoding="raw">_ followed by the arrays back to back, each
 * one a UInt64 byte count and the values. Offsets count from the byte after
 * the '_'. The header is written first, so every array's size is computed
 * from the particle and wall counts before any data is written.
 *
 * The world is read one particle at a time through sd_world_get_particle,
 * once per array, through a small buffer: writing a frame needs no memory
 * proportional to the particle count.
 */
#define _POSIX_C_SOURCE 200809L /* open_memstream */

#include "io/vtk.h"

#include "io/vtk_bin.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the binary stream, header helpers and the point field list: io/vtk_bin.h */

/* ---- particles ---------------------------------------------------------- */

/* One field-data string array of count names, in VTK's ascii String
 * encoding (each name's bytes in decimal, each ended by a 0), so that any
 * name survives the XML. */
static void sd_vtk_names(FILE *fp, const char *array, size_t count, const sd_world *w,
                         const char *(*name_of)(const sd_world *, size_t))
{
    fprintf(fp, "      <Array type=\"String\" Name=\"%s\" NumberOfTuples=\"%zu\" format=\"ascii\">\n       ",
            array, count);
    for (size_t k = 0; k < count; ++k) {
        const char *s = name_of(w, k);
        for (const unsigned char *c = (const unsigned char *)(s ? s : ""); *c; ++c)
            fprintf(fp, " %u", (unsigned)*c);
        fprintf(fp, " 0");
    }
    fprintf(fp, "\n      </Array>\n");
}

static const char *sd_vtk_shape_name(const sd_world *w, size_t k)
{
    sd_shape_info info;
    return sd_world_get_shape(w, k, &info) == SD_OK ? info.name : "";
}

static size_t sd_vtk_material_count(const sd_world *w)
{
    size_t n = 0;
    while (sd_world_material_name(w, n))
        ++n;
    return n;
}

/* The XML head of a particle frame of n particles, up to the '_' that
 * starts the appended data; returns the appended data's size in bytes.
 * Field data names the shape and material indices of the point data
 * (scripts/frame_to_csv.py reads them to write a packing that loads again). */
static uint64_t sd_vtk_particles_head(FILE *fp, const sd_world *w, size_t n)
{
    uint64_t off = 0;
    sd_vtk_file_open(fp, "UnstructuredGrid");
    fprintf(fp, "  <UnstructuredGrid>\n");
    fprintf(fp, "    <FieldData>\n");
    sd_vtk_names(fp, "shape_names", sd_world_shape_count(w), w, sd_vtk_shape_name);
    sd_vtk_names(fp, "material_names", sd_vtk_material_count(w), w, sd_world_material_name);
    fprintf(fp, "    </FieldData>\n");
    fprintf(fp, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", n, n);
    fprintf(fp, "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
#define SD_X_DECL(e, name, type, comps, size)                                                       \
    sd_vtk_array_decl(fp, "        ", type, name, comps, n, size, &off);
    SD_VTK_POINT_FIELDS(SD_X_DECL)
#undef SD_X_DECL
    fprintf(fp, "      </PointData>\n      <Points>\n");
    sd_vtk_array_decl(fp, "        ", "Float64", "position", 3, n, 8, &off);
    fprintf(fp, "      </Points>\n      <Cells>\n");
    sd_vtk_array_decl(fp, "        ", "Int64", "connectivity", 1, n, 8, &off);
    sd_vtk_array_decl(fp, "        ", "Int64", "offsets", 1, n, 8, &off);
    sd_vtk_array_decl(fp, "        ", "UInt8", "types", 1, n, 1, &off);
    fprintf(fp, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
    sd_vtk_appended_open(fp);
    return off;
}

uint64_t sd_vtk_particles_bytes(const sd_world *w, size_t n)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    if (!fp)
        return 0;
    uint64_t data = sd_vtk_particles_head(fp, w, n);
    sd_vtk_appended_close(fp);
    int bad = ferror(fp);
    fclose(fp);
    uint64_t total = bad ? 0 : (uint64_t)len + data;
    free(text);
    return total;
}

sd_status sd_vtk_write_particles(FILE *fp, const sd_world *w, sd_error *err)
{
    errno = 0; /* so that a failure below reports its own reason */
    size_t n = sd_world_particle_count(w);
    sd_vtk_particles_head(fp, w, n);

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

    sd_bin b;
    b.fp = fp;
    b.used = 0;
    b.failed = 0;
    sd_particle_state p;
    /* The stream was written with fprintf so far: the binary buffer starts
     * empty and fwrite keeps the order. */
    for (int f = 0; f < SD_VF_COUNT; ++f) {
        sd_bin_u64(&b, (uint64_t)n * (uint64_t)comps[f] * (uint64_t)sizes[f]);
        for (size_t i = 0; i < n; ++i) {
            sd_status s = sd_vtk_get(w, i, &p, err);
            if (s != SD_OK)
                return s;
            sd_vtk_put_field(&b, (sd_vtk_field)f, &p);
        }
    }
    sd_bin_u64(&b, (uint64_t)n * 24u);
    for (size_t i = 0; i < n; ++i) {
        sd_status s = sd_vtk_get(w, i, &p, err);
        if (s != SD_OK)
            return s;
        sd_bin_v3(&b, p.position);
    }
    /* One VTK_VERTEX (type 1) per particle: connectivity i, offset i + 1. */
    sd_bin_u64(&b, (uint64_t)n * 8u);
    for (size_t i = 0; i < n; ++i)
        sd_bin_i64(&b, (int64_t)i);
    sd_bin_u64(&b, (uint64_t)n * 8u);
    for (size_t i = 0; i < n; ++i)
        sd_bin_i64(&b, (int64_t)i + 1);
    sd_bin_u64(&b, (uint64_t)n);
    for (size_t i = 0; i < n; ++i)
        sd_bin_u8(&b, 1u);
    sd_status s = sd_vtk_bin_status(&b, err);
    if (s != SD_OK)
        return s;
    sd_vtk_appended_close(fp);
    return sd_vtk_stream_status(fp, err);
}

/* ---- walls -------------------------------------------------------------- */

double sd_vtk_plane_side(const sd_world *w)
{
    size_t n = sd_world_particle_count(w);
    sd_v3d lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    sd_particle_state p;
    int any = 0;
    for (size_t i = 0; i < n; ++i) {
        if (sd_world_get_particle(w, i, &p) != SD_OK)
            continue;
        double r = p.radius;
        lo.x = fmin(lo.x, p.position.x - r);
        lo.y = fmin(lo.y, p.position.y - r);
        lo.z = fmin(lo.z, p.position.z - r);
        hi.x = fmax(hi.x, p.position.x + r);
        hi.y = fmax(hi.y, p.position.y + r);
        hi.z = fmax(hi.z, p.position.z + r);
        any = 1;
    }
    double side = 0.0;
    if (any) {
        double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
        side = 1.2 * sqrt(dx * dx + dy * dy + dz * dz);
    }
    if (!(side >= 1e-3)) /* also catches NaN from a broken state */
        side = 1e-3;
    return side;
}

/* The cells that draw one wall (not a mesh): points and, per cell, its
 * corners, counter-clockwise seen from the side the normal points to (a
 * plane's normal; a box's and a drum's inward side faces the particles,
 * so their faces are wound to point outward). */
#define SD_VTK_DRUM_SEGMENTS 48
typedef struct sd_vtk_wall_cells {
    int npt, ncell, nconn;
    sd_v3d pt[2 * SD_VTK_DRUM_SEGMENTS];
    int64_t conn[6 * SD_VTK_DRUM_SEGMENTS];
    int size[SD_VTK_DRUM_SEGMENTS + 2]; /* corners of each cell */
} sd_vtk_wall_cells;

static void sd_vtk_cells_quad(sd_vtk_wall_cells *g, const sd_v3d q[4])
{
    for (int k = 0; k < 4; ++k) {
        g->conn[g->nconn++] = g->npt;
        g->pt[g->npt++] = q[k];
    }
    g->size[g->ncell++] = 4;
}

/* A drum (kind 3: point = centre, normal = axis, lo.x = radius, lo.y =
 * half length, open_faces bits 2 and 4 = caps left out): its mantle as
 * SD_VTK_DRUM_SEGMENTS quads between two rings of points, each closed cap
 * one polygon on its ring. Drawn at rest (the mantle looks the same
 * turned). */
static void sd_vtk_drum_cells(const sd_wall_info *wi, sd_vtk_wall_cells *g)
{
    double a[3] = {wi->normal.x, wi->normal.y, wi->normal.z};
    double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(len > 0.0))
        return;
    for (int k = 0; k < 3; ++k)
        a[k] /= len;
    /* e1 perpendicular to the axis, e2 = a x e1: (e1, e2, a) right-handed */
    double t[3] = {fabs(a[0]) < 0.9 ? 1.0 : 0.0, fabs(a[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    double d = t[0] * a[0] + t[1] * a[1] + t[2] * a[2], e1[3], e2[3];
    for (int k = 0; k < 3; ++k)
        e1[k] = t[k] - d * a[k];
    double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; ++k)
        e1[k] /= n1;
    e2[0] = a[1] * e1[2] - a[2] * e1[1];
    e2[1] = a[2] * e1[0] - a[0] * e1[2];
    e2[2] = a[0] * e1[1] - a[1] * e1[0];
    const double c[3] = {wi->point.x, wi->point.y, wi->point.z}, rad = wi->lo.x, half = wi->lo.y;
    const int n = SD_VTK_DRUM_SEGMENTS;
    for (int ring = 0; ring < 2; ++ring) /* points ring * n + k: ring 0 at -half, 1 at +half */
        for (int k = 0; k < n; ++k) {
            double th = 2.0 * 3.14159265358979323846 * k / n, cs = cos(th), sn = sin(th), s = ring ? half : -half;
            g->pt[g->npt].x = c[0] + rad * (cs * e1[0] + sn * e2[0]) + s * a[0];
            g->pt[g->npt].y = c[1] + rad * (cs * e1[1] + sn * e2[1]) + s * a[1];
            g->pt[g->npt].z = c[2] + rad * (cs * e1[2] + sn * e2[2]) + s * a[2];
            g->npt++;
        }
    /* mantle quads: along the turn, then along the axis (outward normal) */
    for (int k = 0; k < n; ++k) {
        int k1 = (k + 1) % n;
        g->conn[g->nconn++] = k;
        g->conn[g->nconn++] = k1;
        g->conn[g->nconn++] = n + k1;
        g->conn[g->nconn++] = n + k;
        g->size[g->ncell++] = 4;
    }
    if (!(wi->open_faces & 2u)) { /* the low cap, wound about -axis */
        for (int k = n - 1; k >= 0; --k)
            g->conn[g->nconn++] = k;
        g->size[g->ncell++] = n;
    }
    if (!(wi->open_faces & 4u)) { /* the high cap, about +axis */
        for (int k = 0; k < n; ++k)
            g->conn[g->nconn++] = n + k;
        g->size[g->ncell++] = n;
    }
}

static void sd_vtk_cells_of(const sd_wall_info *wi, double plane_side, sd_vtk_wall_cells *g)
{
    g->npt = g->ncell = g->nconn = 0;
    sd_v3d q[4];
    if (wi->kind == 0) {
        double nx = wi->normal.x, ny = wi->normal.y, nz = wi->normal.z;
        double len = sqrt(nx * nx + ny * ny + nz * nz);
        if (!(len > 0.0))
            return;
        nx /= len;
        ny /= len;
        nz /= len;
        /* u = n x a / |n x a| with a the axis least aligned with n; v = n x u. */
        double ax = 0.0, ay = 0.0, az = 0.0;
        if (fabs(nx) <= fabs(ny) && fabs(nx) <= fabs(nz))
            ax = 1.0;
        else if (fabs(ny) <= fabs(nz))
            ay = 1.0;
        else
            az = 1.0;
        double ux = ny * az - nz * ay, uy = nz * ax - nx * az, uz = nx * ay - ny * ax;
        double ul = sqrt(ux * ux + uy * uy + uz * uz);
        ux /= ul;
        uy /= ul;
        uz /= ul;
        double vx = ny * uz - nz * uy, vy = nz * ux - nx * uz, vz = nx * uy - ny * ux;
        double h = 0.5 * plane_side;
        static const double su[4] = {-1.0, 1.0, 1.0, -1.0}, sv[4] = {-1.0, -1.0, 1.0, 1.0};
        for (int k = 0; k < 4; ++k) {
            q[k].x = wi->point.x + h * (su[k] * ux + sv[k] * vx);
            q[k].y = wi->point.y + h * (su[k] * uy + sv[k] * vy);
            q[k].z = wi->point.z + h * (su[k] * uz + sv[k] * vz);
        }
        sd_vtk_cells_quad(g, q);
        return;
    }
    if (wi->kind == 1) {
        double lo[3] = {wi->lo.x, wi->lo.y, wi->lo.z}, hi[3] = {wi->hi.x, wi->hi.y, wi->hi.z};
        /* (b, c) corners in this order wind a face at +a counter-clockwise about +a. */
        static const int cb[4] = {0, 1, 1, 0}, cc[4] = {0, 0, 1, 1};
        for (int a = 0; a < 3; ++a) {
            int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int side = 0; side < 2; ++side) {
                unsigned bit = 1u << (2 * a + side); /* SD_BOX_XMIN, XMAX, YMIN, ... */
                if (wi->open_faces & bit)
                    continue;
                for (int k = 0; k < 4; ++k) {
                    int kk = side ? k : 3 - k; /* the lower face winds the other way */
                    double x[3];
                    x[a] = side ? hi[a] : lo[a];
                    x[b] = cb[kk] ? hi[b] : lo[b];
                    x[c] = cc[kk] ? hi[c] : lo[c];
                    q[k].x = x[0];
                    q[k].y = x[1];
                    q[k].z = x[2];
                }
                sd_vtk_cells_quad(g, q);
            }
        }
        return;
    }
    if (wi->kind == 3)
        sd_vtk_drum_cells(wi, g);
    /* a mesh (kind 2) is drawn from its facets (sd_vtk_mesh) */
}

static sd_status sd_vtk_wall(const sd_world *w, size_t i, double side, sd_wall_info *wi, sd_vtk_wall_cells *g,
                             sd_error *err)
{
    sd_status s = sd_world_get_wall(w, i, wi);
    if (s != SD_OK)
        return sd_error_set(err, s, "", 0, "", "cannot read wall %zu of the world", i);
    sd_vtk_cells_of(wi, side, g);
    return SD_OK;
}

/* Mesh wall i's facets (sd_world_get_mesh): 1 and *mi when wall i is a mesh. */
static int sd_vtk_mesh(const sd_world *w, size_t i, sd_mesh_info *mi)
{
    return sd_world_get_mesh(w, (int)i, mi) == SD_OK;
}

/* Vertex k of a mesh at its current pose: world = R x_mesh + t, R of the
 * unit quaternion (w, x, y, z). */
static sd_v3d sd_vtk_mesh_point(const sd_mesh_info *mi, size_t k)
{
    const double *x = mi->vertices + 3 * k, *q = mi->rotation, *t = mi->translation;
    double qw = q[0], qx = q[1], qy = q[2], qz = q[3];
    /* v' = v + 2 qw (u x v) + 2 u x (u x v), u = (qx, qy, qz) */
    double cx = qy * x[2] - qz * x[1], cy = qz * x[0] - qx * x[2], cz = qx * x[1] - qy * x[0];
    double dx = qy * cz - qz * cy, dy = qz * cx - qx * cz, dz = qx * cy - qy * cx;
    sd_v3d r = {x[0] + 2.0 * (qw * cx + dx) + t[0], x[1] + 2.0 * (qw * cy + dy) + t[1],
                x[2] + 2.0 * (qw * cz + dz) + t[2]};
    return r;
}

sd_status sd_vtk_write_walls(FILE *fp, const sd_world *w, double plane_side, sd_error *err)
{
    errno = 0; /* so that a failure below reports its own reason */
    size_t nw = sd_world_wall_count(w);
    sd_wall_info wi;
    sd_mesh_info mi;
    sd_vtk_wall_cells g; /* one wall at a time, ~5 kB */
    /* cells: quads (planes, boxes, a drum's mantle), a drum's caps, and a
     * mesh's triangles on its own (shared) points, at the mesh's current pose */
    size_t ncells = 0, npts = 0, nconn = 0;
    for (size_t i = 0; i < nw; ++i) {
        sd_status s = sd_vtk_wall(w, i, plane_side, &wi, &g, err);
        if (s != SD_OK)
            return s;
        if (sd_vtk_mesh(w, i, &mi)) {
            ncells += mi.triangle_count;
            npts += mi.vertex_count;
            nconn += 3 * mi.triangle_count;
        } else {
            ncells += (size_t)g.ncell;
            npts += (size_t)g.npt;
            nconn += (size_t)g.nconn;
        }
    }
    uint64_t off = 0;
    sd_vtk_file_open(fp, "PolyData");
    fprintf(fp, "  <PolyData>\n");
    fprintf(fp,
            "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"%zu\">\n",
            npts, ncells);
    fprintf(fp, "      <CellData Scalars=\"wall\" Vectors=\"force\">\n");
    sd_vtk_array_decl(fp, "        ", "Int32", "wall", 1, ncells, 4, &off);
    sd_vtk_array_decl(fp, "        ", "Float64", "force", 3, ncells, 8, &off);
    sd_vtk_array_decl(fp, "        ", "Int32", "kind", 1, ncells, 4, &off); /* issue 31: what render frames */
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
    /* Pass 0: wall index per cell; 1: force per cell; K: wall kind per
     * cell (0 plane, 1 box, 2 mesh, 3 drum: a reader frames the bounded
     * ones); 2: points; 3: connectivity; 4: offsets. */
    enum { SD_PASS_KIND = 5 };
    static const int order[6] = {0, 1, SD_PASS_KIND, 2, 3, 4}; /* the header's order */
    for (int o = 0; o < 6; ++o) {
        int pass = order[o];
        uint64_t bytes = pass == 0 || pass == SD_PASS_KIND ? (uint64_t)ncells * 4u
                       : pass == 1 ? (uint64_t)ncells * 24u
                       : pass == 2 ? (uint64_t)npts * 24u
                       : pass == 3 ? (uint64_t)nconn * 8u
                                   : (uint64_t)ncells * 8u;
        sd_bin_u64(&b, bytes);
        int64_t base = 0, end = 0; /* first point of the wall; running cell end */
        for (size_t i = 0; i < nw; ++i) {
            sd_status s = sd_vtk_wall(w, i, plane_side, &wi, &g, err);
            if (s != SD_OK)
                return s;
            int mesh = sd_vtk_mesh(w, i, &mi);
            size_t cells = mesh ? mi.triangle_count : (size_t)g.ncell;
            for (size_t k = 0; k < cells; ++k) {
                if (pass == 0) {
                    sd_bin_i32(&b, (int32_t)i);
                } else if (pass == SD_PASS_KIND) {
                    sd_bin_i32(&b, (int32_t)wi.kind);
                } else if (pass == 1) {
                    sd_bin_v3(&b, wi.force);
                } else if (pass == 3 && mesh) {
                    for (int c = 0; c < 3; ++c)
                        sd_bin_i64(&b, base + (int64_t)mi.triangles[k][c]);
                } else if (pass == 4) {
                    end += mesh ? 3 : g.size[k];
                    sd_bin_i64(&b, end);
                }
            }
            if (pass == 2 && mesh)
                for (size_t k = 0; k < mi.vertex_count; ++k)
                    sd_bin_v3(&b, sd_vtk_mesh_point(&mi, k));
            if (pass == 2 && !mesh)
                for (int k = 0; k < g.npt; ++k)
                    sd_bin_v3(&b, g.pt[k]);
            if (pass == 3 && !mesh)
                for (int k = 0; k < g.nconn; ++k)
                    sd_bin_i64(&b, base + g.conn[k]);
            base += mesh ? (int64_t)mi.vertex_count : (int64_t)g.npt;
        }
    }
    sd_status s = sd_vtk_bin_status(&b, err);
    if (s != SD_OK)
        return s;
    sd_vtk_appended_close(fp);
    return sd_vtk_stream_status(fp, err);
}

/* ---- collection --------------------------------------------------------- */

sd_status sd_vtk_write_collection(FILE *fp, size_t n, const sd_vtk_dataset *sets, sd_error *err)
{
    errno = 0; /* so that a failure below reports its own reason */
    static const char *part_names[3] = {"particles", "walls", "shapes"};
    fprintf(fp, "<?xml version=\"1.0\"?>\n");
    fprintf(fp, "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    fprintf(fp, "  <Collection>\n");
    for (size_t i = 0; i < n; ++i) {
        int part = sets[i].part;
        /* %.17g keeps the simulated time exact; "name" is read by recent
         * ParaView as the block name and ignored by older readers. */
        fprintf(fp, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"%d\" name=\"%s\" file=\"%s\"/>\n",
                sets[i].time, part, part_names[part >= 0 && part <= 2 ? part : 0], sets[i].file);
    }
    fprintf(fp, "  </Collection>\n</VTKFile>\n");
    return sd_vtk_stream_status(fp, err);
}
