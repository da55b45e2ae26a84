/* kdtree_check.c: checks a built kd-tree against its invariants, for the tests (chapter 9). It reads the
 * tree that kdtree.c built and calls nothing in it. */
#include "kdtree.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct check {
    const struct kdtree *k;
    unsigned char *seen_node;
    char *why;
    size_t why_size;
};

static bool check_fail(struct check *c, const char *message, size_t where) {
    snprintf(c->why, c->why_size, "%s (at %zu)", message, where);
    return false;
}

/* Checks the shape of the subtree at index: indices in range, each node reached once, leaves within
 * the references, depth within the walk's stack. */
static bool check_shape(struct check *c, uint32_t index, size_t depth) {
    const struct kdtree *k = c->k;
    if (depth >= KD_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (index >= k->info.nodes || c->seen_node[index]++)
        return check_fail(c, "node index out of range or reached twice", index);
    const struct kd_node *n = &k->nodes[index];
    if (n->axis == KD_LEAF) {
        if ((size_t)n->first + n->count > k->info.references)
            return check_fail(c, "leaf runs past the references", index);
        for (uint32_t i = 0; i < n->count; i++)
            if (k->refs[n->first + i] >= k->face_count)
                return check_fail(c, "reference to a face that does not exist", index);
        return true;
    }
    if (n->axis < 0 || n->axis > 2 || !(n->above > index + 1))
        return check_fail(c, "inner node with a bad axis, or its above child not after its below child", index);
    return check_shape(c, index + 1, depth + 1) && check_shape(c, n->above, depth + 1);
}

/* Checks that face is in every leaf under index whose region touches the box [lo, hi]. */
static bool check_face(struct check *c, uint32_t index, uint32_t face, const double lo[3], const double hi[3]) {
    const struct kd_node *n = &c->k->nodes[index];
    if (n->axis == KD_LEAF) {
        for (uint32_t i = 0; i < n->count; i++)
            if (c->k->refs[n->first + i] == face)
                return true;
        return check_fail(c, "face missing from a leaf its box touches", face);
    }
    if (lo[n->axis] <= n->split && !check_face(c, index + 1, face, lo, hi))
        return false;
    return !(hi[n->axis] >= n->split) || check_face(c, n->above, face, lo, hi);
}

bool kdtree_is_valid(const struct kdtree *k, const struct mesh *m, char *why, size_t why_size) {
    struct check c = {k, calloc(k->info.nodes + 1, 1), why, why_size};
    if (c.seen_node == NULL) {
        snprintf(why, why_size, "out of memory");
        return false;
    }
    bool ok = true;
    if (k->face_count != m->face_count)
        ok = check_fail(&c, "face count differs from the mesh's", k->face_count);
    if (ok && k->face_count > 0) {
        ok = check_shape(&c, 0, 0);
        for (size_t i = 0; ok && i < k->info.nodes; i++)
            if (!c.seen_node[i])
                ok = check_fail(&c, "node not reachable from the root", i);
    }
    for (size_t i = 0; ok && i < k->info.slivers; i++)
        if (k->slivers[i] >= k->face_count || (i > 0 && k->slivers[i] <= k->slivers[i - 1]))
            ok = check_fail(&c, "sliver list out of range or out of order", i);
    size_t next_sliver = 0;
    for (uint32_t f = 0; ok && f < k->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 corner[3] = {m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]]};
        const struct kd_triangle *t = &k->triangles[f];
        if (memcmp(&t->a, &corner[0], sizeof(vec3)) != 0 || memcmp(&t->b, &corner[1], sizeof(vec3)) != 0 ||
            memcmp(&t->c, &corner[2], sizeof(vec3)) != 0) {
            ok = check_fail(&c, "stored triangle differs from its face", f);
            break;
        }
        if (next_sliver < k->info.slivers && k->slivers[next_sliver] == f) {
            next_sliver++;
            continue; /* not in the tree */
        }
        double lo[3], hi[3];
        for (int axis = 0; axis < 3; axis++) {
            double x0 = vec3_axis(corner[0], axis), x1 = vec3_axis(corner[1], axis), x2 = vec3_axis(corner[2], axis);
            lo[axis] = fmin(x0, fmin(x1, x2)); /* fmin and fmax pass over a NaN corner; if all three */
            hi[axis] = fmax(x0, fmax(x1, x2)); /* are NaN, the build spans the whole axis: so do we */
            lo[axis] = lo[axis] == lo[axis] ? lo[axis] : -INFINITY;
            hi[axis] = hi[axis] == hi[axis] ? hi[axis] : INFINITY;
            if (!(lo[axis] >= vec3_axis(k->root.min, axis) && hi[axis] <= vec3_axis(k->root.max, axis)))
                ok = check_fail(&c, "root box does not hold a triangle", f);
        }
        ok = ok && check_face(&c, 0, f, lo, hi);
    }
    free(c.seen_node);
    return ok;
}
