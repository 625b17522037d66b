/* gb_contact_tracker — the exact trajectory tracker for the grid contact: the leaves that can hold
 * the lowest node for any vertical within delta_max of a reference, searched by bound (see
 * gb_contact.h). It returns the brute-force node bit for bit. */
#include "gb_contact_internal.h"

#include "gb_error.h"

#include <stdlib.h>
#include <string.h>

struct gb_contact_tracker {
    const gb_contact_grid *grid;
    double delta_max, r_max;
    int have_reference;
    double reference[3];
    int32_t *leaves;      /* candidate leaves, lowest bound at the reference first */
    double *leaf_bound;   /* scratch for sorting */
    size_t leaf_count, leaf_capacity;
    size_t last_index;    /* the previous answer: a warm start for the next full search */
};

int gb_contact_tracker_create(const gb_contact_grid *grid, double delta_max, gb_contact_tracker **out)
{
    *out = NULL;
    if (!(delta_max > 0.0 && delta_max <= 0.5))
        return gb_error_set(GB_EDOM, "tracker radius %g is out of range (allowed: 0 < delta_max <= 0.5)", delta_max);
    gb_contact_tracker *t = calloc(1, sizeof *t);
    if (!t) return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    t->grid = grid;
    t->last_index = SIZE_MAX;
    t->delta_max = delta_max;
    t->r_max = grid->patches[0].r_hi;
    t->leaf_capacity = grid->patch_count;
    t->leaves = malloc(t->leaf_capacity * sizeof *t->leaves);
    t->leaf_bound = malloc(t->leaf_capacity * sizeof *t->leaf_bound);
    if (!t->leaves || !t->leaf_bound) {
        free(t->leaves);
        free(t->leaf_bound);
        free(t);
        return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    }
    *out = t;
    return GB_OK;
}

void gb_contact_tracker_free(gb_contact_tracker *t)
{
    if (!t) return;
    free(t->leaves);
    free(t->leaf_bound);
    free(t);
}

/* New reference d: the exact lowest node, then every leaf whose bound is within the threshold. */
static int tracker_reference(gb_contact_tracker *t, const double d[3])
{
    gb_contact_node node;
    int status = gb_contact_grid_search(t->grid, d, t->last_index, &node);
    if (status) return status;
    const double threshold = node.height + 2.0 * t->delta_max * t->r_max + BOUND_MARGIN;
    int32_t stack[PATCH_STACK];
    int top = 0;
    stack[top++] = 0;
    t->leaf_count = 0;
    while (top > 0) {
        const patch *p = &t->grid->patches[stack[--top]];
        const double bound = patch_bound(p, d);
        if (bound > threshold) continue;
        if (p->child[0] < 0) {
            /* insertion by bound: the lowest first, so the scan finds a low node early and the
             * per-leaf bound test below skips most of the rest */
            size_t k = t->leaf_count++;
            while (k > 0 && t->leaf_bound[k - 1] > bound) {
                t->leaves[k] = t->leaves[k - 1];
                t->leaf_bound[k] = t->leaf_bound[k - 1];
                k--;
            }
            t->leaves[k] = (int32_t)(p - t->grid->patches);
            t->leaf_bound[k] = bound;
            continue;
        }
        if (top + 2 > PATCH_STACK) return gb_error_set(GB_ENUMERIC, "patch tree deeper than %d levels", PATCH_STACK / 2);
        stack[top++] = p->child[0];
        stack[top++] = p->child[1];
    }
    memcpy(t->reference, d, sizeof t->reference);
    t->have_reference = 1;
    return GB_OK;
}

int gb_contact_tracker_find(gb_contact_tracker *t, const double zb[3], gb_contact_node *out)
{
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    const double chord[3] = {d[0] - t->reference[0], d[1] - t->reference[1], d[2] - t->reference[2]};
    if (!t->have_reference || gb_vec_norm(chord) > t->delta_max) {
        status = tracker_reference(t, d);
        if (status) return status;
    }
    double best = INFINITY;
    size_t best_index = SIZE_MAX, visited = 0;
    for (size_t l = 0; l < t->leaf_count; l++) {
        const patch *p = &t->grid->patches[t->leaves[l]];
        if (l > 0 && patch_bound(p, d) > best) continue; /* every node of it is strictly higher */
        visited += scan_leaf(t->grid, p, d, &best, &best_index);
    }
    t->last_index = best_index;
    gb_contact_grid_fill_node(t->grid, best_index, best, visited, out);
    return GB_OK;
}

