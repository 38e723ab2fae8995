/* mesh.h — reads a triangle mesh from an STL (binary or ASCII) or a
 * Wavefront OBJ file: the vertices, the file's faces and their triangles.
 *
 * Context-free: a path in, an sd_mesh and an sd_error out. It knows
 * nothing of scenes; the polyhedron shapes' `file:` (io/scene_shapes.c)
 * and, next, the triangle-mesh walls of seed 000 §2.3 read their files
 * through it, each adding its own checks (a polyhedron's convexity is the
 * shape side's business, not the mesh's).
 *
 * Output format: an indexed mesh. vertices[] holds every vertex of the
 * file, in file order (OBJ: the `v` lines; STL: three per facet, repeated
 * as the file repeats them, not welded). A face is one `f` line (OBJ) or
 * one facet (STL), as a run of vertex indices (face_start / corners, CSR).
 * triangles[] is the faces fanned from their first corner, in face order,
 * each an index triple into vertices[] in the face's winding, with
 * triangle_face[t] the face it came from; a triangle face gives one
 * triangle. Nothing is welded, oriented or checked for closure here.
 *
 * Invariant: sd_mesh_read returns SD_OK with every coordinate finite and
 * every index < vertex_count, or an error and an empty mesh (nothing
 * allocated). Error messages are complete sentences that name the file
 * and, where there is one, its line (text files) or facet (binary STL);
 * err->file is the mesh path and err->line the line (0 for binary STL or
 * whole-file errors), err->key is "".
 */
#ifndef SD_IO_MESH_H
#define SD_IO_MESH_H

#include <stddef.h>
#include <stdint.h>

#include <shapedem/shapedem.h>

/* The largest mesh file read (bytes): a 5-million-facet binary STL. */
#define SD_MESH_MAX_BYTES (1L << 28)

typedef struct sd_mesh {
    size_t vertex_count;
    sd_v3d *vertices;          /* in the file's units */
    size_t face_count;
    size_t *face_start;        /* face_count + 1 entries: face f is corners[face_start[f] ..] */
    uint32_t *corners;         /* vertex indices of the faces, in order */
    size_t triangle_count;
    uint32_t (*triangles)[3];  /* vertex index triples, the faces fanned */
    uint32_t *triangle_face;   /* face of each triangle */
} sd_mesh;

/* Reads path (.obj, .stl, either case of the extension) into *out. */
sd_status sd_mesh_read(const char *path, sd_mesh *out, sd_error *err);
void sd_mesh_free(sd_mesh *m);

/* The centre (mean of its corners, summed in order) of face f. */
sd_v3d sd_mesh_face_centre(const sd_mesh *m, size_t f);

#endif
