/* vtk.h — VTK XML writers: particles as an UnstructuredGrid (.vtu), walls
 * as PolyData (.vtp) and the time-series Collection (.pvd).
 *
 * Invariant: the binary blocks are raw appended data, each a UInt64 byte
 * count followed by the values, always in little-endian byte order whatever
 * the host (values are encoded byte by byte), so the files declare
 * byte_order="LittleEndian" header_type="UInt64" truthfully everywhere.
 * The writers only read the world through the public API, but for the
 * template geometry of the shapes file (vtk_shapes.c).
 */
#ifndef SD_IO_VTK_H
#define SD_IO_VTK_H

#include <shapedem/shapedem.h>
#include <stdio.h>

/* Writes every particle of w as one VTK_VERTEX with its point data.
 * Returns SD_ERR_IO when a write failed (errors on fp are also left for the
 * caller's ferror check) or the world could not be read. */
sd_status sd_vtk_write_particles(FILE *fp, const sd_world *w, sd_error *err);

/* Bytes of the particle frame sd_vtk_write_particles writes for n
 * particles of w (the layout depends on n and the names of w's shapes and
 * materials only); 0 when out of memory. */
uint64_t sd_vtk_particles_bytes(const sd_world *w, size_t n);

/* Side (m) of the square drawn for plane walls: 1.2 x the diagonal of the
 * particles' bounding box (radii included), at least 1e-3 m. */
double sd_vtk_plane_side(const sd_world *w);

/* Writes planes as squares of side plane_side centred at their point,
 * boxes as their closed faces, drums as their mantle (48 quads) and closed
 * caps (one polygon each), meshes as their facets at the current pose;
 * cell data: wall index and wall force. */
sd_status sd_vtk_write_walls(FILE *fp, const sd_world *w, double plane_side, sd_error *err);

/* The true shapes of a frame's particles (shapes_NNNNNN.vtp): each
 * template's surface (shape/surface.h, `resolution` directions per turn)
 * built once on first use, posed per particle; cell data = the particle
 * frame's point data of the cell's particle. */
typedef struct sd_vtk_shapes sd_vtk_shapes;
struct sd_surface;
sd_status sd_vtk_shapes_make(const sd_world *w, int resolution, sd_vtk_shapes **out, sd_error *err);
void sd_vtk_shapes_free(sd_vtk_shapes *t);
/* Template `shape`'s surface in its principal frame (-1: the unit ball of
 * plain spheres), built the first time it is asked for. */
sd_status sd_vtk_shapes_surface(sd_vtk_shapes *t, const sd_world *w, int shape, const struct sd_surface **out,
                                sd_error *err);
sd_status sd_vtk_write_shapes(FILE *fp, const sd_world *w, sd_vtk_shapes *t, sd_error *err);

typedef struct sd_vtk_dataset {
    double time;       /* s */
    int part;          /* 0 particles, 1 walls, 2 shapes */
    const char *file;  /* relative to the .pvd */
} sd_vtk_dataset;

sd_status sd_vtk_write_collection(FILE *fp, size_t n, const sd_vtk_dataset *sets, sd_error *err);

#endif
