/* gb_scan_rows — a scan's CSV rows (one list of columns makes the header, the row, its parser and a failed
 * point's NaNs) and the journal of an interrupted scan, sealed line by line (gb_scan_internal.h). */
#include "gb_scan_internal.h"

#include "gb_error.h"
#include "gb_seal.h"

#include <inttypes.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int gb_scan_csv_header(const gb_scan *scan, char *out, size_t size)
{
    const int n = snprintf(out, size, "index,%s.%s,%s.%s,%s", scan->axis[0].section, scan->axis[0].key, scan->axis[1].section,
                           scan->axis[1].key, gb_scan_csv_metric_columns());
    return n > 0 && (size_t)n < size ? GB_OK : gb_error_set(GB_EINVAL, "the scan's CSV header does not fit %zu bytes", size);
}

/* The CSV's numeric columns after index, x and y, from one list: the column's name and its field, in row
 * order. A new metric is a field of gb_scan_metrics and a line here; the header, the row, its parser and the
 * NaNs of a failed point follow. certificate_undecided (a count) and the two fingerprints (hex) close every
 * row. */
#define SCAN_COLUMNS(X)                                                                                                \
    X(omega_rms, omega_rms)                                                                                            \
    X(switch_rate, switch_rate)                                                                                        \
    X(strobe_sd, strobe_sd)                                                                                            \
    X(mean_height, mean_height)                                                                                        \
    X(geff_nonpositive_fraction, geff_nonpositive)                                                                     \
    X(lift_off_fraction, lift_off)                                                                                     \
    X(lambda_max, lambda)                                                                                              \
    X(lambda_error, lambda_error)                                                                                      \
    X(lambda_first_half, lambda_early)                                                                                 \
    X(lambda_second_half, lambda_late)                                                                                 \
    X(chaos_lifetime_periods, chaos_lifetime)                                                                          \
    X(melnikov_margin, melnikov_margin)                                                                                \
    X(melnikov_margin_eq93, melnikov_margin_eq93)                                                                      \
    X(one_point_fraction, one_point)                                                                                   \
    X(two_point_fraction, two_point)                                                                                   \
    X(rest_fraction, at_rest)                                                                                          \
    X(flight_fraction, in_flight)                                                                                      \
    X(sliding_fraction, sliding)                                                                                       \
    X(impacts_per_period, impacts_per_period)                                                                          \
    X(landings_per_period, landings_per_period)                                                                        \
    X(energy_lost_per_period, energy_lost_per_period)                                                                  \
    X(end_contacts, end_contacts)                                                                                      \
    X(stepped_fraction, stepped)
#define COLUMN_OFFSET(name, field) offsetof(gb_scan_metrics, field),
#define COLUMN_NAME(name, field) #name ","
static const size_t column_offsets[] = {SCAN_COLUMNS(COLUMN_OFFSET)};
enum { COLUMN_COUNT = sizeof column_offsets / sizeof column_offsets[0] };

static double *column(gb_scan_metrics *m, size_t k) { return (double *)((char *)m + column_offsets[k]); }
static double column_of(const gb_scan_metrics *m, size_t k) { return *(const double *)((const char *)m + column_offsets[k]); }

const char *gb_scan_csv_metric_columns(void)
{
    return SCAN_COLUMNS(COLUMN_NAME) "certificate_undecided,state_fingerprint,switch_fingerprint\n";
}

void gb_scan_failed_metrics(const gb_scan *scan, size_t index, gb_scan_metrics *out)
{
    memset(out, 0, sizeof *out);
    gb_scan_coordinates(scan, index, &out->x, &out->y);
    for (size_t k = 0; k < COLUMN_COUNT; k++) *column(out, k) = NAN;
}

int gb_scan_csv_row(const gb_scan_metrics *m, size_t index, char *out, size_t size)
{
    size_t n = (size_t)snprintf(out, size, "%zu,%.17g,%.17g", index, m->x, m->y);
    for (size_t k = 0; k < COLUMN_COUNT && n < size; k++) n += (size_t)snprintf(out + n, size - n, ",%.17g", column_of(m, k));
    if (n < size)
        n += (size_t)snprintf(out + n, size - n, ",%zu,%016" PRIx64 ",%016" PRIx64 "\n", m->certificate_undecided,
                              m->state_fingerprint, m->switch_fingerprint);
    return n < size ? GB_OK : gb_error_set(GB_EINVAL, "a scan row does not fit %zu bytes", size);
}

int gb_scan_csv_parse(const char *line, size_t *index, gb_scan_metrics *out)
{
    gb_scan_metrics m;
    double *fields[2 + COLUMN_COUNT] = {&m.x, &m.y};
    for (size_t k = 0; k < COLUMN_COUNT; k++) fields[2 + k] = column(&m, k);
    char *end;
    const char *p = line;
    if (*p < '0' || *p > '9') return GB_EINVAL; /* digits only: strtoull would take "-1" or " 7" */
    const unsigned long long i = strtoull(p, &end, 10);
    if (end == p || *end != ',') return GB_EINVAL;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        p = end + 1;
        *fields[k] = strtod(p, &end);
        if (end == p || *end != ',') return GB_EINVAL;
    }
    p = end + 1;
    if (*p < '0' || *p > '9') return GB_EINVAL;
    m.certificate_undecided = (size_t)strtoull(p, &end, 10);
    if (end == p || *end != ',') return GB_EINVAL;
    p = end + 1;
    m.state_fingerprint = strtoull(p, &end, 16);
    if (end != p + 16 || *end != ',') return GB_EINVAL;
    p = end + 1;
    m.switch_fingerprint = strtoull(p, &end, 16);
    if (end != p + 16 || (*end != '\n' && *end != '\0')) return GB_EINVAL;
    *index = (size_t)i;
    *out = m;
    return GB_OK;
}

/* ---- the journal --------------------------------------------------------------------------------- */

void gb_scan_journal_header(const gb_scan *scan, uint64_t binary, char *out, size_t size)
{
    char identity[GB_SEAL_HEX];
    gb_seal_hex(scan->identity, identity);
    snprintf(out, size, "gomboc scan journal 3: scan %s, binary %016" PRIx64 ", %zu points\n", identity, binary,
             gb_scan_points(scan));
}

/* The seal of a row: gb_seal of the header and the row (without its '\n'). */
static int row_seal(const char *header, const char *row, size_t length, unsigned char seal[GB_SEAL_BYTES])
{
    const gb_seal_piece pieces[2] = {{header, strlen(header)}, {row, length}};
    return gb_seal_compute(pieces, 2, seal);
}

int gb_scan_journal_line(const char *header, const char *row, char *out, size_t size)
{
    const size_t length = strcspn(row, "\n");
    unsigned char seal[GB_SEAL_BYTES];
    char hex[GB_SEAL_HEX];
    const int status = row_seal(header, row, length, seal);
    if (status) return gb_error_set(status, "cannot seal a journal line: %s", gb_error_message());
    gb_seal_hex(seal, hex);
    const int n = snprintf(out, size, "%.*s,%s\n", (int)length, row, hex);
    return n > 0 && (size_t)n < size ? GB_OK : gb_error_set(GB_EINVAL, "a journal line does not fit %zu bytes", size);
}

/* A journal's first line as it may be quoted: printable ASCII, at most 100 characters. */
static void quoted(const char *text, size_t length, char *out, size_t size)
{
    size_t n = 0;
    for (size_t k = 0; k < length && n + 4 < size && k < 100; k++)
        out[n++] = text[k] >= 0x20 && text[k] < 0x7f ? text[k] : '?';
    if (length > 100 && n + 4 < size) memcpy(out + n, "...", 3), n += 3;
    out[n] = '\0';
}

/* One complete line (without its '\n') of the journal: GB_OK with the point in *index and *m, or
 * GB_EINVAL with the reason. */
static int journal_row(const gb_scan *scan, const char *header, const char *line, size_t length, size_t *index,
                       gb_scan_metrics *m)
{
    if (memchr(line, '\0', length)) return gb_error_set(GB_EINVAL, "a NUL byte");
    if (length > GB_SCAN_JOURNAL_LINE_MAX) return gb_error_set(GB_EINVAL, "%zu bytes long", length);
    char row[GB_SCAN_JOURNAL_LINE_MAX + 2];
    const size_t tail = 2 * GB_SEAL_BYTES + 1; /* ",<64 hexadecimal digits>" */
    if (length < tail + 1 || line[length - tail] != ',') return gb_error_set(GB_EINVAL, "no seal at its end");
    const size_t row_length = length - tail;
    unsigned char seal[GB_SEAL_BYTES];
    if (!gb_seal_from_hex(line + row_length + 1, seal) ||
        !gb_seal_verify((const gb_seal_piece[2]){{header, strlen(header)}, {line, row_length}}, 2, seal))
        return gb_error_set(GB_EINVAL, "its seal does not verify: edited, damaged, or written under another key (see "
                            "GOMBOC_KEY)");
    memcpy(row, line, row_length);
    row[row_length] = '\n', row[row_length + 1] = '\0';
    if (gb_scan_csv_parse(row, index, m)) return gb_error_set(GB_EINVAL, "not a row of this command");
    if (*index >= gb_scan_points(scan))
        return gb_error_set(GB_EINVAL, "point %zu of a scan of %zu points", *index, gb_scan_points(scan));
    /* Every value must read back to the same text, and the coordinates must be the point's own. */
    double x, y;
    gb_scan_coordinates(scan, *index, &x, &y);
    m->x = x, m->y = y;
    char again[GB_SCAN_JOURNAL_LINE_MAX + 2];
    if (gb_scan_csv_row(m, *index, again, sizeof again) || strcmp(again, row))
        return gb_error_set(GB_EINVAL, "its values do not read back to the same row (the coordinates of point %zu are x = "
                            "%.17g, y = %.17g)", *index, x, y);
    return GB_OK;
}

int gb_scan_journal_read(const gb_scan *scan, const char *name, const char *header, const char *text, size_t size,
                         gb_scan_metrics *results, unsigned char *done, size_t *count, size_t *keep)
{
    static const char *const allowed = "(allowed: a journal this command wrote for this scan file, base scene and binary; "
                                       "remove it to start again)";
    *count = 0, *keep = 0;
    const char *newline = memchr(text, '\n', size);
    const size_t header_length = strlen(header);
    if (!size) return GB_OK; /* an empty journal (from a kill before its header): no points, the header written anew */
    if (!newline) return gb_error_set(GB_EINVAL, "%s: %s %s", name, "an incomplete first line", allowed);
    if ((size_t)(newline - text) + 1 != header_length || memcmp(text, header, header_length)) {
        char have[128], want[128];
        quoted(text, (size_t)(newline - text), have, sizeof have);
        quoted(header, header_length - 1, want, sizeof want);
        return gb_error_set(GB_EINVAL, "%s:1: not this scan's journal (its header: '%s'; this scan and binary: '%s') %s", name,
                            have, want, allowed);
    }
    size_t at = header_length;
    int number = 1;
    while (at < size) {
        number++;
        const char *line = text + at, *end = memchr(line, '\n', size - at);
        if (!end) break; /* a half-written last line: dropped */
        const size_t length = (size_t)(end - line);
        size_t index;
        gb_scan_metrics m;
        if (journal_row(scan, header, line, length, &index, &m))
            return gb_error_set(GB_EINVAL, "%s:%d: %s %s", name, number, gb_error_message(), allowed);
        if (done[index]) {
            char first[GB_SCAN_JOURNAL_LINE_MAX + 2], again[GB_SCAN_JOURNAL_LINE_MAX + 2];
            gb_scan_csv_row(&results[index], index, first, sizeof first);
            gb_scan_csv_row(&m, index, again, sizeof again);
            if (strcmp(first, again))
                return gb_error_set(GB_EINVAL, "%s:%d: point %zu a second time, with other values %s", name, number, index,
                                    allowed);
        } else {
            results[index] = m, done[index] = 1;
            ++*count;
        }
        at += length + 1;
    }
    *keep = at;
    return GB_OK;
}
