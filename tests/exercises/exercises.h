/* exercises.h: the functions the walkthroughs' build exercises (★★★) ask a student to write, and the
 * checks that grade them.
 *
 * make exercises (tests/exercises/runner/run.sh) grades each exercise whose function common/ defines,
 * by linking a small program that runs the check below on it (runner/exercise.c); until the function
 * exists it says where to start. Exercise 2.4 is a whole kind of shape: its check starts once its table,
 * disc_kind, exists. Each check returns true, or false with a message in the student's terms: the
 * input, what was expected, what came back. tests/exercises/solutions.c holds one correct answer to each
 * and one wrong one, which make test uses to prove that every check passes the first and fails the
 * second (test_exercise_proof.c). */
#ifndef WHITTED_EXERCISES_H
#define WHITTED_EXERCISES_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "aabb.h"
#include "mesh.h"
#include "ray.h"
#include "shape.h"

/* Exercise 2.4 (common/disc.h and common/disc.c, and &disc_kind in the list of kinds of each chapter that
 * draws discs): the disc, a new kind of shape, read from the scene line `disc centre X Y Z normal X Y Z
 * radius R [material NAME]`. Its check grades the kind's tables: its syntax (keyword "disc"; a zero
 * normal or a radius <= 0 is refused, the normal is made unit length), its POV-Ray form `disc {
 * <centre>, <normal>, radius`, and its ray queries: the nearest hit among several discs (t, the disc's
 * unit normal, the material, its index in the array; the rim counts), the crossings and the bounding
 * box. */
extern const struct shape_kind disc_kind;
bool check_disc(const struct shape_kind *kind, char *why, size_t why_size);

/* Exercise 3.4 (common/mesh_normals.c): a unit normal for every vertex of m, the average of the normals
 * of the faces around it weighted by their areas (the cross product of two edges, unnormalised, does
 * both at once); (0, 0, 0) for a vertex no face uses. normals has m->vertex_count entries. */
void mesh_vertex_normals(const struct mesh *m, vec3 *normals);
typedef void (*vertex_normals_fn)(const struct mesh *, vec3 *);
bool check_vertex_normals(vertex_normals_fn f, char *why, size_t why_size);

/* Exercise 4.4 (common/cylinder.c): where r meets the side of the open cylinder of `radius` whose axis
 * runs from `base` up the +y axis for `height`, with t_min < t < t_max (no caps). */
bool cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max,
                        double *t);
typedef bool (*cylinder_fn)(vec3, double, double, const ray *, double, double, double *);
bool check_cylinder(cylinder_fn f, char *why, size_t why_size);

/* Exercise 5.4 (common/bounding_sphere.c): a sphere that holds every vertex of m, no larger than the
 * sphere around m's bounding box. */
void mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius);
typedef void (*bounding_sphere_fn)(const struct mesh *, vec3 *, double *);
bool check_bounding_sphere(bounding_sphere_fn f, char *why, size_t why_size);

/* Exercise 6.4 (common/phong.c): Blinn's highlight, max(0, N · H)^exponent with H the unit half vector
 * between the unit vectors towards the light and towards the eye; 0 when the light is behind. */
double phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent);
typedef double (*blinn_fn)(vec3, vec3, vec3, double);
bool check_blinn(blinn_fn f, char *why, size_t why_size);

/* Exercise 7.4 (common/shadow.c): the share of a rectangular area light (corner, edges edge_u and
 * edge_v) visible from `point`: the light is cut into n x n equal cells, one shadow ray to each cell's
 * centre (shadow_opaque), and the result is the fraction that arrive. `world` is a struct world. */
double shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n);
typedef double (*area_fraction_fn)(const void *, vec3, vec3, vec3, vec3, int);
bool check_area_fraction(area_fraction_fn f, char *why, size_t why_size);

/* Exercise 8.4 (common/whitted.c): Schlick's approximation of the share of light a surface between media
 * n1 (the ray's side) and n2 reflects, for a ray whose angle to the normal has cosine cos_incident:
 * R0 + (1 - R0)(1 - c)^5 with R0 = ((n1 - n2) / (n1 + n2))^2, where c is the cosine on the denser
 * side; 1 when the ray cannot leave (total internal reflection). */
double whitted_schlick(double cos_incident, double n1, double n2);
typedef double (*schlick_fn)(double, double, double);
bool check_schlick(schlick_fn f, char *why, size_t why_size);

/* Exercise 9.4 (common/grid.c): the cells of a uniform grid that r crosses, in order, for t >= 0. The
 * grid divides the box [lo, hi] into `cells` equal cells per axis. Writes up to `max` cells as
 * {x, y, z} indices into out and returns how many the ray crosses (3D-DDA, Amanatides and Woo 1987). */
int grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max);
typedef int (*grid_walk_fn)(vec3, vec3, int, const ray *, int (*)[3], int);
bool check_grid_walk(grid_walk_fn f, char *why, size_t why_size);

/* Exercise 10.4 (common/bvh.c): the SAH cost of splitting the n boxes at `plane` on `axis`: boxes whose
 * centre is below the plane go left, the rest right; cost = 1 + (area(L) * count(L) + area(R) *
 * count(R)) / area(all), with a side's area that of the union of its boxes (0 when it is empty). */
double bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane);
typedef double (*split_cost_fn)(const struct aabb *, int, int, double);
bool check_split_cost(split_cost_fn f, char *why, size_t why_size);

/* Exercise 11.4 (common/fast_bvh_build.c): a binary BVH collapsed into a 4-wide one, as rung 2 does. A child
 * is written as an int: k >= 0 for node k of the same tree, -1 - L for leaf L (BVH_LEAF(L)). */
#define BVH_LEAF(l) (-1 - (l))
#define BVH4_NONE INT_MIN /* an unused slot of a 4-wide node */
struct bvh2_node {
    struct aabb box[2]; /* the two children's boxes */
    int child[2];
};
struct bvh4_node {
    int child[4]; /* the used slots first, then BVH4_NONE */
};
/* Writes the 4-wide tree made from binary node `root` of `tree` into out, its root in out[0], and
 * returns how many 4-wide nodes it has (writing only the first `max`). Each 4-wide node starts with its
 * binary node's two children and, while it has fewer than four, replaces the interior (not leaf) child
 * with the largest surface area by that child's two children; every interior child left becomes a
 * 4-wide node of its own in the same way. */
int bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max);
typedef int (*collapse_fn)(const struct bvh2_node *, int, struct bvh4_node *, int);
bool check_collapse(collapse_fn f, char *why, size_t why_size);

/* Exercise 12.4 (common/supersample.c): n-rooks sampling, n rays a pixel where the grid takes n x n.
 * Writes n points of pixel (i, j) into x[0..n) and y[0..n), each in [0, 1) across the pixel, so that
 * each of the n columns [c / n, (c + 1) / n) and each of the n rows holds exactly one point (n rooks on
 * an n x n board, none attacking another), at a random place within its cell. The places and which
 * column goes with which row come from sample_hash(i, j, index, seed) alone: the same pixel and seed
 * give the same points, other pixels other pairings. */
void supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y);
typedef void (*rooks_fn)(int, int, int, uint32_t, double *, double *);
bool check_rooks(rooks_fn f, char *why, size_t why_size);

/* Exercise 13.4 (common/thin_lens.c): Shirley and Chiu's concentric map from the unit square to the
 * unit disc, for spreading lens samples. Maps (u, v) in [0, 1] x [0, 1] to (x, y) with x^2 + y^2 <= 1:
 * with a = 2u - 1 and b = 2v - 1, the square of half-side max(|a|, |b|) goes to the circle of that
 * radius, each of its four sides to a quarter of the circle (where |a| > |b|: r = a, angle pi/4 * b / a;
 * otherwise r = b, angle pi/2 - pi/4 * a / b; (0, 0) for the centre). Areas are kept: uniform points in
 * the square give uniform points in the disc, and stratified ones stay stratified. */
void thin_lens_concentric(double u, double v, double *x, double *y);
typedef void (*concentric_fn)(double, double, double *, double *);
bool check_concentric(concentric_fn f, char *why, size_t why_size);

/* Exercise 14.4 (common/image_map.c): POV-Ray's cylindrical map (map_type 2), a picture wrapped once
 * round the y axis. Stores in *u the longitude of the point q seen from the y axis as a share of a turn,
 * in [0, 1): 0 towards +x, 1/4 towards +z, 1/2 towards -x; and in *v its height q.y as it is (the
 * caller folds it into the picture). Returns false on the y axis itself, where the longitude has no
 * value (POV-Ray shows nothing there). */
bool image_map_cylindrical(vec3 q, double *u, double *v);
typedef bool (*cylindrical_fn)(vec3, double *, double *);
bool check_cylindrical(cylindrical_fn f, char *why, size_t why_size);

/* Exercise 15.4 (common/sampling.c): a ball of light sampled by the cone it fills. Seen from `point`
 * outside the ball of `radius` around `centre`, the ball fills the cone about the direction to its centre
 * whose half-angle theta_max has sin(theta_max) = radius / distance. Stores in *direction a unit vector
 * uniformly distributed over that cone's solid angle, made from two uniform numbers (cos theta uniform in
 * [cos theta_max, 1] by u1, the angle about the axis 2 pi u2), and in *density its density per unit solid
 * angle, 1 / (2 pi (1 - cos theta_max)). Returns false, storing nothing, when the point is inside the ball
 * or on it. */
bool sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,
                          double *density);
typedef bool (*cone_fn)(vec3, double, vec3, double, double, vec3 *, double *);
bool check_cone(cone_fn f, char *why, size_t why_size);

/* Exercise 16.4 (common/keyframes.c): spherical linear interpolation of two rotations (Shoemake 1985),
 * the way a key's turn can be made at constant speed about one axis where chapter 16's keys blend each
 * angle apart. q0 and q1 are unit quaternions (w, x, y, z): the turn by angle a about the unit axis u is
 * (cos a/2, u sin a/2), and q and -q are the same turn. Stores in out the unit quaternion a fraction t in
 * [0, 1] of the way from q0 to q1 along the shorter arc: q0 at t = 0, q1 at t = 1 (-q1 when q0 . q1 < 0,
 * the same turn the short way), turning at a constant angular speed, so that the turn from q0 to out(t)
 * is t times the whole turn. Where q0 and q1 are nearly the same (q0 . q1 above 0.9995 after the flip),
 * the normalised linear blend, which is then as good and avoids dividing by the sine of a tiny angle. */
void keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]);
typedef void (*slerp_fn)(const double *, const double *, double, double *);
bool check_slerp(slerp_fn f, char *why, size_t why_size);
/* Exercise 17.5 (common/microfacet.c): sampling the GGX distribution's normals themselves (Walter et al.
 * 2007), the sampler that came before the visible normals of microfacet_ggx_sample_visible. Returns a
 * unit microfacet normal m (m.z > 0) drawn from two uniform numbers in [0, 1) with the density
 * D(m) cos(theta_m) per unit solid angle, D = microfacet_ggx_d of width alpha: tan^2 theta =
 * alpha^2 u1 / (1 - u1), the angle about the normal 2 pi u2. */
vec3 microfacet_ggx_sample_normal(double alpha, double u1, double u2);
typedef vec3 (*ggx_normal_fn)(double, double, double);
bool check_ggx_normals(ggx_normal_fn f, char *why, size_t why_size);

#endif
