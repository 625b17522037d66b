/* gb_case_internal — what the scene reader's two files share: gb_case.c reads keys by its table, gb_case_check.c
 * judges what no single key can say (the body, the combinations of keys, the records' memory, λ's record). Not
 * installed, not exported. */
#ifndef GB_CASE_INTERNAL_H
#define GB_CASE_INTERNAL_H

#include "gb_case.h"

#include <stddef.h>

/* The keys of the table, and every key (the table's, then each contact law's own, gb_dynamics_law_key_at). */
size_t gb_case_table_key_count(void);
size_t gb_case_key_total(void);

/* The index of key [section] name in the table, -1 when there is none. */
int gb_case_key_index(const char *section, const char *name);

/* The scene's keys read from text over the defaults, then the overrides set (gb_case.c); no check across keys yet. */
int gb_case_read_keys(const char *name, const char *text, size_t size, const gb_case_override *overrides, size_t count,
                      gb_case *scene);

/* Every check that needs the whole scene, once every key is read: the body made from its keys (gb_body.h), the
 * combinations of keys, the memory its records would take, λ's record (gb_case_lyapunov_check). GB_EDOM naming the
 * key (its line, or the file that set it over the scene) and the allowed combination. */
int gb_case_cross_check(const char *path, gb_case *c);

#endif
