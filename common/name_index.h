/* name_index.h: finding a name among many in constant time, for the scene parser (chapter 1).
 *
 * A scene refers to its materials by name, once when a material is defined (is the name taken?) and
 * once for every shape that uses one. Searching the list each time costs the number of materials per
 * look-up, and a scene of 100,000 materials took 17 seconds to read. This is a hash table instead: the
 * name is hashed (FNV-1a) to a slot, and the slots after it are tried in turn until the name or an
 * empty slot is found. The table is kept at most half full, so a look-up tries about two slots. */
#ifndef WHITTED_NAME_INDEX_H
#define WHITTED_NAME_INDEX_H

#include <stdbool.h>
#include <stddef.h>

struct name_index {
    struct name_slot *slots; /* owned; `capacity` slots, a power of two, NULL while empty */
    size_t capacity, count;
};

/* Makes an empty index (no memory is taken until the first name). */
void name_index_init(struct name_index *ix);

/* Adds `name` (copied) with its `value` (>= 0). The name must not be in the index already. Returns
 * false when memory runs out (the index is unchanged). */
bool name_index_add(struct name_index *ix, const char *name, int value);

/* Returns the value added with `name`, or -1 when it is not in the index. */
int name_index_find(const struct name_index *ix, const char *name);

/* Frees the index and leaves it empty. */
void name_index_free(struct name_index *ix);

#endif
