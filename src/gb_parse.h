/* gb_parse — the one strict reader of numbers in text, for scene files and command options alike.
 *
 * Every parser reads a whole token: nothing may precede or follow it (no white space, no trailing
 * junk, no comment), so "0.1x", "pi/3junk", "+8x +9" and "0.1 # note" are refused, never read as a
 * prefix. Numbers are decimal only: [+-]digits[.digits][(e|E)[+-]digits] (at least one digit before
 * or after the point); no hexadecimal, no "inf", no "nan". A number too large for a double is
 * GB_PARSE_OVERFLOW; one too small is read as the nearest double (a subnormal, or zero), which is what
 * was written. Counts are digits only, with no sign.
 *
 * The parsers set no error message: the caller knows the key or option and its allowed range, and
 * says them. gb_parse_describe() gives the reason of a result in words for such a message. */
#ifndef GB_PARSE_H
#define GB_PARSE_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gb_parse_result {
    GB_PARSE_OK = 0,
    GB_PARSE_SYNTAX = 1,   /* not of the allowed form */
    GB_PARSE_OVERFLOW = 2, /* a number beyond the largest double (about 1.8e308) */
    GB_PARSE_LIMIT = 3     /* a count beyond the caller's maximum, or a list of the wrong length */
} gb_parse_result;

/* "not a number", "beyond the range of a double", ... for GB_PARSE_SYNTAX ("not " + what). */
GB_API const char *gb_parse_describe(gb_parse_result result, const char *what);

/* A decimal number, the whole of `text`. */
GB_API gb_parse_result gb_parse_double(const char *text, double *value);

/* A count: decimal digits only, at most `max` (else GB_PARSE_LIMIT). */
GB_API gb_parse_result gb_parse_count(const char *text, unsigned long long max, unsigned long long *value);

/* `n` numbers separated by commas; spaces or tabs may stand around each comma. */
GB_API gb_parse_result gb_parse_list(const char *text, double *values, int n);

/* An angle in radians: a number, or a multiple of pi written P*pi/Q, Ppi/Q, P*pi, pi/Q or pi, with P
 * and Q numbers (Q not zero), e.g. "pi/3", "2*pi/3", "-0.5pi". */
GB_API gb_parse_result gb_parse_angle(const char *text, double *value);

/* Two counts written AxB (e.g. "90x180"), each at most `max`. */
GB_API gb_parse_result gb_parse_pair(const char *text, unsigned long long max, unsigned long long *a, unsigned long long *b);

#ifdef __cplusplus
}
#endif

#endif
