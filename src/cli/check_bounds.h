/* check_bounds.h — `shapedem check`'s proportion checks (issues 30, 31):
 * each mesh wall's facet count, bounding box and size against the
 * particles', with a warning when the two differ by so much that the
 * units are likely wrong (a mesh left in millimetres, a scale: meant for
 * another file); the analysis files' size; insertion regions that reach
 * outside the walls' box or cross a mesh wall.
 */
#ifndef SD_CLI_CHECK_BOUNDS_H
#define SD_CLI_CHECK_BOUNDS_H

#include <stdio.h>

#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

/* A mesh more than this many particle diameters across, or less than one
 * over SD_CHECK_MESH_SMALL of one, is reported as a likely unit mistake. */
#define SD_CHECK_MESH_LARGE 1000.0
#define SD_CHECK_MESH_SMALL 10.0

/* Prints one line per mesh wall of w and a warning for each whose size is
 * out of proportion with particles of radius rmin..rmax (m; rmax 0: no
 * particles known, no warning). Returns the number of warnings. */
int sd_check_print_meshes(FILE *f, const sd_world *w, double rmin, double rmax);

/* Analysis files larger than this (bytes) get a warning. */
#define SD_CHECK_ANALYSIS_LARGE 1e9

/* Prints the analysis files' estimated size for a run of `steps` steps
 * (nothing when the scene has none); returns 1 when it warned. */
int sd_check_print_analysis_size(FILE *f, const sd_scene *s, long steps);

/* Warns for each insertion whose region's box reaches beyond a closed face
 * of a box wall or behind a plane wall of w, or holds facets of a mesh
 * wall (the run places particles only inside the walls and clear of a
 * mesh's facets: such a region is used in part, or not at all). Returns
 * the number of warnings. */
int sd_check_print_regions(FILE *f, const sd_scene *s, const sd_world *w);

#endif
