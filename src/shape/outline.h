/* outline.h — closed 2D outlines (host code): reading them from CSV, and
 * seeded generators of irregular outlines for tests and examples.
 *
 * An outline is a closed polygon of boundary points (traced from an image,
 * say), the input of the Fourier fit (shape/fourier.h, seed 002 §2.3).
 * Invariant: every outline returned here has at least 3 finite points; the
 * generators are deterministic for a given seed on every platform (core/rng.h).
 */
#ifndef SD_SHAPE_OUTLINE_H
#define SD_SHAPE_OUTLINE_H

#include <stddef.h>
#include <stdint.h>

#include "core/vec2.h"

#include <shapedem/shapedem.h>

/* Reads "x,y" per line (m). Blank lines and lines starting with '#' are
 * skipped; the first data line may be a header of two words ("x,y"). A bad
 * row is SD_ERR_INPUT naming the file and line; a missing file SD_ERR_IO.
 * *pts is allocated (sd_free it); at least 3 points. */
sd_status sd_outline_read_csv(const char *path, sd_vec2 **pts, size_t *n, sd_error *err);

/* Limits of sd_outline_check: the span (larger side of the bounding box,
 * m) and the least area relative to span² (below it the outline is flat). */
#define SD_OUTLINE_SPAN_MIN SD_R(1e-145)
#define SD_OUTLINE_SPAN_MAX SD_R(1e145)
#define SD_OUTLINE_FLAT     SD_R(1e-9)

/* Checks that pts[0 .. n) (the closing point may repeat the first) is an
 * outline a fit can measure itself against: finite, a span whose square
 * neither over- nor underflows, not too far from the origin for its size
 * (at least 7 significant digits of its shape), a simple closed curve (no
 * crossing, touching, repeated vertex or turning back; consecutive repeated
 * points are allowed), and not flat. O(n log n) (a Shamos–Hoey sweep).
 * SD_ERR_INPUT with a message naming the points; SD_ERR_MEMORY. */
sd_status sd_outline_check(const sd_vec2 *pts, size_t n, sd_error *err);

/* A rock-like outline: radius R (1 + Σ_{k=2}^{8} A_k cos(kφ + φ_k)) with
 * seeded amplitudes A_k ∝ roughness · k^-1.2 and phases, and an aspect ratio
 * (x stretched) — star-shaped, concave where roughness is large. n points
 * counter-clockwise. Returns n. */
size_t sd_outline_rock(uint64_t seed, sd_real R, sd_real aspect, sd_real roughness, sd_vec2 *out, size_t n);

/* A convex polygon of `sides` sides (circumradius R, stretched by aspect
 * along x, turned by rot) with corners rounded by radius r (< the inradius),
 * sampled with `per_corner` points on each corner arc and `per_edge` on each
 * edge. Returns the number of points written (sides * (per_corner + per_edge)). */
size_t sd_outline_rounded_polygon(int sides, sd_real R, sd_real aspect, sd_real rot, sd_real r, int per_corner,
                                  int per_edge, sd_vec2 *out);

/* The polygon poly[0 .. np) with every edge split into `per_edge` pieces. */
size_t sd_outline_densify(const sd_vec2 *poly, size_t np, int per_edge, sd_vec2 *out);

#endif
