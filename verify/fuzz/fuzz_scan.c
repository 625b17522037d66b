/* libFuzzer target: the scan file reader (gb_scan_parse) on arbitrary bytes.
 *
 * Beyond not crashing (ASan, UBSan), a scan the reader accepts must be one the scan can run: two
 * different keys of the scene, each taking a number (or random attitudes), counts within their limits,
 * non-empty ranges, a transient shorter than the run, some metric, a base scene named. */
#include "gb_error.h"
#include "gb_scan_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void require(int condition)
{
    if (!condition) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_scan scan;
    if (gb_scan_parse("fuzz-scan.ini", (const char *)data, size, &scan) != GB_OK) {
        require(gb_error_message()[0] != '\0'); /* every refusal says why */
        return 0;
    }
    require(scan.base[0] != '\0' && memchr(scan.base, '\0', sizeof scan.base));
    require(scan.metrics != 0 && (scan.metrics & ~(unsigned)GB_SCAN_METRICS_ALL) == 0);
    require(scan.periods >= 1.0 && scan.periods <= 1e7 && (double)scan.transient_periods + 1.0 <= scan.periods);
    require(gb_scan_points(&scan) >= 1 && gb_scan_points(&scan) <= GB_SCAN_POINTS_MAX);
    require(strcmp(scan.axis[0].section, scan.axis[1].section) || strcmp(scan.axis[0].key, scan.axis[1].key));
    for (int k = 0; k < 2; k++) {
        const gb_scan_axis *a = &scan.axis[k];
        const int attitude = !strcmp(a->section, "initial") && !strcmp(a->key, "attitude");
        require(a->count >= 1 && a->count <= GB_SCAN_AXIS_MAX);
        require(attitude == (a->scale == GB_SCAN_RANDOM));
        require(attitude || gb_case_key_numeric(a->section, a->key) == 1);
        require(a->scale == GB_SCAN_RANDOM || (isfinite(a->from) && isfinite(a->to) && (a->count == 1 || a->to > a->from)));
    }
    return 0;
}
