/* gb_proof_body_arcs — H's Taylor coefficients over fixed cells of q, enclosed once and shared by every
 * integration of one definition (gb_proof_body.h; docs/proofs.md, "The reduced field's Taylor coefficients").
 *
 * Cell i is the arc [i w, (i + 1) w], w = 2^−level (its ends exact doubles). Its coefficients H_0 … H_n (n the table's
 * order) are gb_proof_body_jet_enclose's over that arc: each holds H⁽ᵏ⁾(q)/k! at every q of the cell. An arc [lo, hi] lies in the
 * union of the cells from ⌊lo/w⌋ to ⌊hi/w⌋, so the hull of their coefficients holds H⁽ᵏ⁾(q)/k! at every q of the arc:
 * an enclosure of the same thing as the arc's own, possibly a little wider at its ends (the cells stick out by less
 * than w) and often narrower inside (small cells wrap less). A cell that cannot be enclosed (it holds a tie, or its
 * boxes stay in two charts) is remembered as refused, and an arc touching it is left to the caller's own enclosure.
 * The table is a hash of the cells' indices under one mutex; a cell is enclosed outside it, so that two threads may
 * both enclose one cell (the same numbers: the first kept). What a cell holds depends only on the definition and the
 * cell, never on which thread or which integration asked first. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_proof_body_arcs_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* An arc of at most SPAN_MAX cells is served; its coefficients above the second only when it spans SPAN_HIGH cells or
 * more (a narrow ball's, as at a step's centre, would lose its narrowness to the cells' width). */
enum { SPAN_MAX = 64, SPAN_HIGH = 4, SLOTS_MAX = 1 << 17 };

enum { SLOT_EMPTY = 0, SLOT_ENCLOSED, SLOT_REFUSED };

typedef struct slot {
    int64_t cell;
    int state;
    gb_proof_interval *H; /* order + 1 coefficients when enclosed */
} slot;

struct gb_proof_body_arcs {
    gb_proof_body_def def; /* the definition the cells are of (its arcs NULL) */
    int level, order;
    double width;
    pthread_mutex_t lock;
    slot *slots;
    size_t capacity, used;
    gb_proof_body_arcs_stats stats;
};

static int same_def(const gb_proof_body_def *a, const gb_proof_body_def *b)
{
    return a->surface == b->surface && a->mass == b->mass && a->g == b->g && a->rocking[0] == b->rocking[0] &&
           a->rocking[1] == b->rocking[1] && a->rocking[2] == b->rocking[2] && a->inertia.lo == b->inertia.lo &&
           a->inertia.hi == b->inertia.hi && a->origin == b->origin && a->cut == b->cut &&
           a->resolution == b->resolution && a->precision == b->precision;
}

int gb_proof_body_arcs_create(const gb_proof_body_def *def, int level, int order, gb_proof_body_arcs **out)
{
    *out = NULL;
    if (!def || !def->surface) return gb_error_set(GB_EINVAL, "the arcs' definition has no surface");
    if (!(level >= GB_PROOF_BODY_ARCS_LEVEL_MIN && level <= GB_PROOF_BODY_ARCS_LEVEL_MAX))
        return gb_error_set(GB_EDOM, "level = %d is out of range (allowed: %d to %d: cells 2^-level wide)", level,
                            GB_PROOF_BODY_ARCS_LEVEL_MIN, GB_PROOF_BODY_ARCS_LEVEL_MAX);
    if (!(order >= 1 && order <= GB_PROOF_BODY_JET_ORDER_MAX))
        return gb_error_set(GB_EDOM, "order = %d is out of range (allowed: 1 to %d)", order,
                            GB_PROOF_BODY_JET_ORDER_MAX);
    int status = gb_proof_check_precision(def->precision);
    if (status) return status;
    gb_proof_body_arcs *A = calloc(1, sizeof *A);
    if (A) A->capacity = 1024, A->slots = calloc(A->capacity, sizeof *A->slots);
    if (!A || !A->slots) {
        free(A);
        return gb_error_set(GB_ENOMEM, "the arcs' table: no memory");
    }
    A->def = *def;
    A->def.arcs = NULL;
    A->level = level, A->order = order;
    A->width = ldexp(1.0, -level);
    pthread_mutex_init(&A->lock, NULL);
    *out = A;
    return GB_OK;
}

void gb_proof_body_arcs_free(gb_proof_body_arcs *A)
{
    if (!A) return;
    pthread_mutex_destroy(&A->lock);
    for (size_t k = 0; k < A->capacity; k++) free(A->slots[k].H);
    free(A->slots);
    free(A);
}

void gb_proof_body_arcs_get_stats(gb_proof_body_arcs *A, gb_proof_body_arcs_stats *out)
{
    pthread_mutex_lock(&A->lock);
    *out = A->stats;
    pthread_mutex_unlock(&A->lock);
}

static size_t hash(int64_t cell, size_t capacity)
{
    return (size_t)(((uint64_t)cell * 0x9E3779B97F4A7C15ULL) >> 20) & (capacity - 1);
}

/* The slot of `cell`, or the empty one where it would go (under the lock). */
static slot *find(gb_proof_body_arcs *A, int64_t cell)
{
    size_t k = hash(cell, A->capacity);
    while (A->slots[k].state != SLOT_EMPTY && A->slots[k].cell != cell) k = (k + 1) & (A->capacity - 1);
    return &A->slots[k];
}

/* Doubles the table (under the lock); 0 when it is at its largest or no memory is left: then nothing more is kept. */
static int grow(gb_proof_body_arcs *A)
{
    if (2 * A->capacity > SLOTS_MAX) return 0;
    slot *old = A->slots;
    const size_t old_capacity = A->capacity;
    slot *slots = calloc(2 * old_capacity, sizeof *slots);
    if (!slots) return 0;
    A->slots = slots, A->capacity = 2 * old_capacity;
    for (size_t k = 0; k < old_capacity; k++)
        if (old[k].state != SLOT_EMPTY) *find(A, old[k].cell) = old[k];
    free(old);
    return 1;
}

/* Cell i's coefficients (A->order + 1) into H: 1 when enclosed, 0 when refused. */
static int cell_jet(gb_proof_body_arcs *A, int64_t i, gb_proof_interval *H)
{
    const size_t bytes = (size_t)(A->order + 1) * sizeof *H;
    pthread_mutex_lock(&A->lock);
    const slot *s = find(A, i);
    const int known = s->state;
    if (known == SLOT_ENCLOSED) memcpy(H, s->H, bytes);
    pthread_mutex_unlock(&A->lock);
    if (known != SLOT_EMPTY) return known == SLOT_ENCLOSED;
    gb_proof_body_jet jet;
    const double lo = (double)i * A->width, hi = (double)(i + 1) * A->width;
    const int enclosed = gb_proof_body_jet_enclose(&A->def, lo, hi, A->order, &jet) == GB_OK;
    if (!enclosed) gb_error_clear(); /* the caller encloses its arc itself and says why if that fails */
    if (enclosed) memcpy(H, jet.H, bytes);
    gb_proof_interval *kept = enclosed ? malloc(bytes) : NULL;
    if (kept) memcpy(kept, H, bytes);
    pthread_mutex_lock(&A->lock);
    slot *t = find(A, i);
    if (t->state == SLOT_EMPTY && (!enclosed || kept) &&
        (2 * (A->used + 1) <= A->capacity || (grow(A) && (t = find(A, i))))) {
        t->cell = i, t->state = enclosed ? SLOT_ENCLOSED : SLOT_REFUSED;
        t->H = kept, kept = NULL;
        A->used++;
        A->stats.cells += enclosed, A->stats.refused += !enclosed;
        A->stats.seconds += jet.seconds;
    }
    pthread_mutex_unlock(&A->lock);
    free(kept); /* another thread's came first, or the table is full */
    return enclosed;
}

int gb_proof_body_arcs_jet(gb_proof_body_arcs *A, const gb_proof_body_def *def, double q_lo, double q_hi, int order,
                           gb_proof_interval *H)
{
    if (!A || order > A->order || !(q_lo <= q_hi) || !same_def(&A->def, def)) return 0;
    const double first = floor(q_lo / A->width), last = floor(q_hi / A->width);
    if (!(last - first < SPAN_MAX) || (order > 2 && last - first + 1 < SPAN_HIGH)) return 0;
    gb_proof_interval hull[GB_PROOF_BODY_JET_ORDER_MAX + 1], c[GB_PROOF_BODY_JET_ORDER_MAX + 1];
    for (int64_t i = (int64_t)first; i <= (int64_t)last; i++) {
        if (!cell_jet(A, i, c)) {
            pthread_mutex_lock(&A->lock);
            A->stats.declined++;
            pthread_mutex_unlock(&A->lock);
            return 0;
        }
        for (int k = 0; k <= order; k++)
            hull[k] =
                i == (int64_t)first ? c[k] : (gb_proof_interval){fmin(hull[k].lo, c[k].lo), fmax(hull[k].hi, c[k].hi)};
    }
    memcpy(H, hull, (size_t)(order + 1) * sizeof *H);
    pthread_mutex_lock(&A->lock);
    A->stats.served++;
    pthread_mutex_unlock(&A->lock);
    return 1;
}
