/* mesh.h — the world's triangle-mesh walls (host side): the prepared mesh
 * of each (geom/trimesh.h, mesh frame), its facet bins, its motion and the
 * views the broad phase and the items read (dynamics/meshwall.h).
 *
 * Invariant: mesh k belongs to wall meshes[k].wall, whose geometry
 * (sd_wall_geom kind SD_WALL_MESH, mesh = k) carries the pose; the view
 * w->mesh_views[k] points into meshes[k]'s arrays and is refreshed
 * whenever they change (add, bins rebuilt).
 */
#ifndef SD_WORLD_MESH_H
#define SD_WORLD_MESH_H

#include <shapedem/shapedem.h>

#include "dynamics/meshwall.h"
#include "geom/trimesh.h"

typedef struct sd_mesh_store {
    int wall;                  /* the wall index of this mesh */
    sd_trimesh m;              /* mesh frame = world frame at t = 0 */
    double *vertices_d;        /* m, the welded vertices as doubles (sd_world_get_mesh) */
    sd_vec3 bb_lo, bb_hi;      /* m, mesh frame bounding box */
    int closed_side;           /* closed meshes: SD_TRIMESH_INSIDE (a container) or SD_TRIMESH_OUTSIDE (an
                                * obstacle), the side particles are on; 0 for a mesh with open edges */
    /* facet bins (dynamics/meshwall.h) */
    sd_real h;                 /* m, cell edge, 0 before the first rebuild */
    int coarse;                /* 1: h was made coarser than asked (key range, entry cap) */
    sd_vec3 origin;
    size_t entry_count;
    uint64_t *entry_key;
    uint32_t *entry_tri;
    /* motion */
    sd_mesh_motion_def motion;
    double *table;             /* copied rows of a TABLE motion */
    sd_vec3 ref0;              /* m, reference point at t = 0 (rotation centre) */
    sd_real extent;            /* m, the farthest vertex from ref0 (skin test of rotations) */
    sd_vec3 trans_ref;         /* pose at the last rebuild */
    sd_quat q_ref;
} sd_mesh_store;

struct sd_world;
/* Builds (or rebuilds) the facet bins of every mesh at cell edge 2 h_min
 * (h_min: m, the largest particle reach, radius plus skin) when their
 * cells are finer than h_min or coarser than 4 h_min; refreshes the views. */
sd_status sd_world_meshes_bins(struct sd_world *w, sd_real h_min);
/* Pose and velocities of every mesh wall at time t (s). */
void sd_world_meshes_pose(struct sd_world *w, double t);
/* 1 when some mesh moved more than lim (m) at any of its points since the
 * last mark; marks the poses. */
int sd_world_meshes_moved(const struct sd_world *w, sd_real lim);
void sd_world_meshes_mark(struct sd_world *w);
/* After a checkpoint restore (world/snapshot.c), which puts back each
 * mesh's pose at the last rebuild and its facet bins' cell edge h: bins
 * the facets again at that h, so the broad phase finds the near facets in
 * the order the saved run did; SD_ERR_MEMORY when out of memory. */
sd_status sd_world_meshes_resumed(struct sd_world *w);
void sd_world_meshes_free(struct sd_world *w);
/* 1 when a sphere of radius b (m) at x (m, world) may be placed among the
 * mesh walls at their present pose: it overlaps no facet, and lies inside
 * every closed container and outside every closed obstacle (world/mesh_clear.c). */
int sd_world_meshes_clear(const struct sd_world *w, sd_v3d x, double b);

#endif
