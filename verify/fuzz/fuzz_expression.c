/* libFuzzer target: a body given by an expression (gb_body_expression: GNU libmatheval's parser, its
 * symbolic derivatives, and the checks of the surface on the sphere).
 *
 * The input's first byte picks r or chi and β (the byte halved, modulo 25, in hundredths: 0 to 0.24); the rest, up to
 * 200 bytes and cut at its first NUL, is the expression. Beyond not crashing (ASan, UBSan): an accepted body
 * has r > 0 and finite at the poles and the equator, and its mass properties are finite and positive; a
 * refused expression says why. Every body made is released after the input. */
#include "gb_body.h"
#include "gb_error.h"
#include "gb_massprops.h"

#include <gsl/gsl_errno.h>
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
    if (size < 1) return 0;
    gsl_set_error_handler_off(); /* as the command: GSL's failures are statuses, not aborts */
    char text[201];
    const size_t n = size - 1 < 200 ? size - 1 : 200;
    memcpy(text, data + 1, n);
    text[n] = '\0';
    const gb_body_expression_kind kind = data[0] & 1 ? GB_BODY_PHASE : GB_BODY_RADIUS;
    const double beta = (double)((data[0] >> 1) % 25) / 100.0;
    gb_surface s;
    const int status = gb_body_expression(kind, text, beta, &s);
    if (status) {
        require(gb_error_message()[0] != '\0');
        gb_error_clear();
        return 0;
    }
    for (int k = 0; k <= 2; k++) {
        const double r = gb_surface_radius(&s, M_PI * k / 2.0, 1.0);
        require(isfinite(r) && r > 0.0);
    }
    gb_massprops_def def = gb_massprops_default_def();
    def.limit = 50; /* a fuzzed body need not converge: only a finite answer or a clear refusal */
    gb_massprops m;
    if (gb_massprops_compute(&s, &def, &m) == GB_OK) require(m.volume > 0.0 && isfinite(m.volume));
    else gb_error_clear();
    gb_body_release();
    return 0;
}
