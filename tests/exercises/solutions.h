/* solutions.h: the model answers to the build exercises and one wrong answer to each (solutions.c). */
#ifndef WHITTED_EXERCISE_SOLUTIONS_H
#define WHITTED_EXERCISE_SOLUTIONS_H

#include "exercises.h"

/* Each solution_X keeps the contract of X in exercises.h; each wrong_X has its signature and the flaw
 * its comment in solutions.c names. */
extern const struct shape_kind solution_disc_kind, wrong_disc_kind; /* the wrong one forgets the radius */
void solution_mesh_vertex_normals(const struct mesh *m, vec3 *normals);
void wrong_mesh_vertex_normals(const struct mesh *m, vec3 *normals);
bool solution_cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max, double *t);
bool wrong_cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max, double *t);
void solution_mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius);
void wrong_mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius);
double solution_phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent);
double wrong_phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent);
double solution_shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n);
double wrong_shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n);
double solution_whitted_schlick(double cos_incident, double n1, double n2);
double wrong_whitted_schlick(double cos_incident, double n1, double n2);
int solution_grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max);
int wrong_grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max);
double solution_bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane);
double wrong_bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane);
int solution_bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max);
int wrong_bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max);
void solution_supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y);
void wrong_supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y);
void solution_thin_lens_concentric(double u, double v, double *x, double *y);
void wrong_thin_lens_concentric(double u, double v, double *x, double *y);
bool solution_image_map_cylindrical(vec3 q, double *u, double *v);
bool wrong_image_map_cylindrical(vec3 q, double *u, double *v);
bool solution_sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,
                                   double *density);
bool wrong_sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,
                                double *density);
void solution_keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]);
void wrong_keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]);

vec3 solution_microfacet_ggx_sample_normal(double alpha, double u1, double u2);
vec3 wrong_microfacet_ggx_sample_normal(double alpha, double u1, double u2);

#endif
