/* check_mesh.h — what `shapedem check`'s run-time estimate adds for the
 * scene's mesh walls (cli/check_mesh.c): a timed trial of spheres resting
 * on the facets, and the particles of the run taken to lie against them.
 */
#ifndef SD_CLI_CHECK_MESH_H
#define SD_CLI_CHECK_MESH_H

#include <stddef.h>

#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

typedef struct sd_check_mesh_trial {
    int ok;                   /* 1: the trial ran (a scene with meshes and particles) */
    size_t meshes;            /* mesh walls */
    double area;              /* m^2, their facets' */
    size_t probes;            /* spheres timed on the facets */
    long steps;               /* steps timed */
    double seconds_per_pstep; /* s a particle-step that a mesh adds (against the same spheres alone; >= 0) */
    size_t against;           /* particles of the run against the facets (sd_check_mesh_part) */
    double seconds;           /* s, the run's steps of those particles (sd_check_mesh_part) */
} sd_check_mesh_trial;

/* Times spheres of radius r (m) and material `material` resting on the
 * facets of the scene's meshes, and the same spheres alone (nothing when
 * the scene has no mesh, or r <= 0). */
void sd_check_mesh_time(const sd_scene *s, double r, int material, sd_check_mesh_trial *m);

/* The run's particles against the facets (their area over (2 r)^2, at most
 * total) and the seconds the meshes add to their `steps` steps. */
void sd_check_mesh_part(sd_check_mesh_trial *m, double r, size_t total, long steps);

#endif
