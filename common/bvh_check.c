/* bvh_check.c: checking a bounding volume hierarchy against its invariants, for the tests (chapter 10).
 *
 * bvh_is_valid walks chapter 10's binary tree; bvh_check_triangles and bvh_check_faces check the
 * stored triangles, before and after such a walk, for chapter 11's 4-wide tree too (fast_bvh.c). */
#include "bvh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "triangle.h"

struct check {
    const struct bvh *b;
    const struct mesh *m;
    unsigned char *seen_triangle, *seen_node;
    char *why;
    size_t why_size;
};

static bool check_fail(struct check *c, const char *message, size_t where) {
    snprintf(c->why, c->why_size, "%s (at %zu)", message, where);
    return false;
}

/* Checks the subtree at node `index`, at the given depth. */
static bool check_node(struct check *c, uint32_t index, size_t depth) {
    if (depth > BVH_DEEPEST)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (index >= c->b->node_count || c->seen_node[index]++)
        return check_fail(c, "node index out of range or reached twice", index);
    const struct bvh_node *n = &c->b->nodes[index];
    if (n->count == 0) {
        if (n->left >= c->b->node_count || n->right >= c->b->node_count)
            return check_fail(c, "child index out of range", index);
        if (!aabb_holds(&n->box, &c->b->nodes[n->left].box) || !aabb_holds(&n->box, &c->b->nodes[n->right].box))
            return check_fail(c, "child box sticks out of its parent's", index);
        return check_node(c, n->left, depth + 1) && check_node(c, n->right, depth + 1);
    }
    return bvh_check_leaf(c->b->triangles, c->b->tree_count, n->first, n->count, &n->box, c->seen_triangle, c->why,
                          c->why_size);
}

bool bvh_is_valid(const struct bvh *b, const struct mesh *m, char *why, size_t why_size) {
    struct check c = {b, m, calloc(b->triangle_count + 1, 1), calloc(b->node_count + 1, 1), why, why_size};
    bool ok = c.seen_triangle != NULL && c.seen_node != NULL;
    if (!ok)
        snprintf(why, why_size, "out of memory");
    if (ok)
        ok = bvh_check_triangles(m, b->triangles, b->faces, b->triangle_count, why, why_size);
    if (ok && b->tree_count > 0)
        ok = check_node(&c, 0, 0);
    if (ok)
        ok = bvh_check_faces(m, b->faces, b->triangle_count, b->tree_count, c.seen_triangle, why, why_size);
    free(c.seen_triangle);
    free(c.seen_node);
    return ok;
}

bool bvh_check_leaf(const struct bvh_triangle *triangles, size_t tree_count, uint32_t first, uint32_t count,
                    const struct aabb *box, unsigned char *seen, char *why, size_t why_size) {
    const char *what = NULL;
    size_t where = first;
    if ((size_t)first + count > tree_count)
        what = "leaf runs past the triangles";
    for (uint32_t k = first; what == NULL && k < first + count; k++) {
        const struct bvh_triangle *t = &triangles[k];
        struct aabb corners = aabb_grow(aabb_grow(aabb_grow(aabb_empty(), t->a), t->b), t->c);
        where = k;
        if (seen[k]++)
            what = "triangle in two leaves";
        else if (!aabb_holds(box, &corners))
            what = "leaf box does not hold its triangle";
    }
    if (what != NULL)
        snprintf(why, why_size, "%s (at %zu)", what, where);
    return what == NULL;
}

bool bvh_check_triangles(const struct mesh *m, const struct bvh_triangle *triangles, const uint32_t *faces,
                         size_t triangle_count, char *why, size_t why_size) {
    const char *what = NULL;
    size_t where = triangle_count;
    if (triangle_count != m->face_count)
        what = "triangle count differs from the mesh's face count";
    for (size_t k = 0; what == NULL && k < triangle_count; k++) {
        where = k;
        if (faces[k] >= m->face_count) {
            what = "face number out of range";
            break;
        }
        const uint32_t *v = m->faces[faces[k]].v;
        const struct bvh_triangle *t = &triangles[k];
        if (memcmp(&t->a, &m->vertices[v[0]], sizeof t->a) != 0 || memcmp(&t->b, &m->vertices[v[1]], sizeof t->b) != 0 ||
            memcmp(&t->c, &m->vertices[v[2]], sizeof t->c) != 0)
            what = "stored triangle differs from its face";
    }
    if (what != NULL)
        snprintf(why, why_size, "%s (at %zu)", what, where);
    return what == NULL;
}

bool bvh_check_faces(const struct mesh *m, const uint32_t *faces, size_t triangle_count, size_t tree_count,
                     unsigned char *seen, char *why, size_t why_size) {
    const char *what = NULL;
    size_t where = 0;
    for (size_t k = 0; what == NULL && k < tree_count; k++)
        if (!seen[k])
            what = "triangle in no leaf", where = k;
    for (size_t k = 0; what == NULL && k < triangle_count; k++) {
        const uint32_t *v = m->faces[faces[k]].v;
        if (triangle_is_sliver(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]]) != (k >= tree_count))
            what = "sliver in the tree, or other triangle among the slivers", where = k;
    }
    if (what == NULL) { /* every face once: no face number repeats */
        memset(seen, 0, triangle_count + 1);
        for (size_t k = 0; what == NULL && k < triangle_count; k++)
            if (seen[faces[k]]++)
                what = "face stored twice", where = faces[k];
    }
    if (what != NULL)
        snprintf(why, why_size, "%s (at %zu)", what, where);
    return what == NULL;
}
