/* libFuzzer target: the journal reader of `gomboc scan --resume` (gb_scan_journal_read) on arbitrary
 * lines after a valid header.
 *
 * The scan is fixed (3 x 2 points over forcing.omega and forcing.A1). When the input's first byte is
 * odd, every complete line of the rest is given its valid seal first (under the fuzzing process's key,
 * as a forger with the key could), so that the row parser, the round trip and the coordinate check meet
 * the input, not only the seal. Beyond not crashing, an
 * accepted journal must hold only points of the scan with their own coordinates, the count of points
 * read must match the marks, and only a half-written last line may be left out. */
#include "gb_error.h"
#include "gb_scan_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void require(int condition)
{
    if (!condition) abort();
}

static const char scan_text[] = "[scan]\nbase = base.ini\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n"
                                "[y]\nkey = forcing.A1\nfrom = 0.5\nto = 1.5\ncount = 2\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_scan scan;
    require(gb_scan_parse("fuzz-scan.ini", scan_text, sizeof scan_text - 1, &scan) == GB_OK);
    char header[160];
    gb_scan_journal_header(&scan, 0x0123456789abcdefull, header, sizeof header);
    const int sign = size > 0 && (data[0] & 1);
    if (size) data++, size--;
    /* The journal: the header, then the input (its complete lines signed when `sign`). */
    const size_t cap = strlen(header) + 66 * size + 64; /* a sealed line grows by ",<64 hex>" */
    char *text = malloc(cap), *line = malloc(size + 2), *signed_line = malloc(size + 80);
    require(text && line && signed_line);
    size_t used = strlen(header);
    memcpy(text, header, used);
    for (size_t at = 0; at < size;) {
        const uint8_t *end = memchr(data + at, '\n', size - at);
        const size_t n = end ? (size_t)(end - (data + at)) + 1 : size - at;
        memcpy(line, data + at, n);
        line[n] = '\0';
        if (sign && end && !memchr(line, '\0', n) && gb_scan_journal_line(header, line, signed_line, size + 80) == GB_OK) {
            const size_t m = strlen(signed_line);
            memcpy(text + used, signed_line, m), used += m;
        } else {
            memcpy(text + used, data + at, n), used += n;
        }
        at += n;
    }
    gb_scan_metrics results[6];
    unsigned char done[6] = {0};
    size_t count = 0, keep = 0;
    const int status = gb_scan_journal_read(&scan, "fuzz.journal", header, text, used, results, done, &count, &keep);
    if (status) {
        require(status == GB_EINVAL && gb_error_message()[0] != '\0');
    } else {
        size_t marked = 0;
        for (size_t k = 0; k < 6; k++) {
            if (!done[k]) continue;
            marked++;
            double x, y;
            gb_scan_coordinates(&scan, k, &x, &y);
            require(results[k].x == x && results[k].y == y);
        }
        require(marked == count && keep <= used && keep >= strlen(header));
        require(keep == used || memchr(text + keep, '\n', used - keep) == NULL); /* only a last line without '\n' dropped */
    }
    free(text), free(line), free(signed_line);
    gb_scan_free(&scan);
    return 0;
}
