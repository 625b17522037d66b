/* libFuzzer target: the scene reader (gb_case_load_text) on arbitrary bytes.
 *
 * Beyond not crashing (ASan, UBSan), a scene the reader accepts must lie inside every range the
 * reader documents: a value that slipped past its check is a misread, and aborts here. */
#include "gb_body.h"
#include "gb_case.h"
#include "gb_error.h"

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
    gb_case c;
    if (gb_case_load_text("fuzz.ini", (const char *)data, size, &c) != GB_OK) {
        require(gb_error_message()[0] != '\0'); /* every refusal says why */
        gb_body_release();
        return 0;
    }
    const gb_dynamics_def *d = &c.dynamics;
    require(c.body.morphology != NULL && c.body.beta >= 0.0 && c.body.beta < 0.25);
    require(d->mass >= 1e-6 && d->mass <= 1e6);
    require(d->forcing.g >= 0.0 && d->forcing.g <= 1000.0);
    require(fabs(c.A1) <= 1000.0 && fabs(c.A2) <= 1000.0 && isfinite(d->forcing.a1) && isfinite(d->forcing.a2));
    require(d->forcing.omega >= 0.01 && d->forcing.omega <= 10000.0 && fabs(d->forcing.psi) <= 1000.0);
    require(d->damping >= 0.0 && d->damping <= 1000.0);
    require(c.integrate.steps_per_period >= 1 && c.integrate.periods > 0.0 && c.integrate.periods <= 1e7);
    require(c.integrate.sample_every >= 1);
    require(c.integrate.method == GB_INTEGRATOR_RK4 || d->contact == GB_CONTACT_MODEL_CONTINUOUS);
    for (int k = 0; k < 3; k++) require(fabs(c.omega0[k]) <= 1000.0);
    for (int k = 0; k < 9; k++) require(isfinite(c.attitude[k]));
    require(memchr(c.description, '\0', sizeof c.description) != NULL);
    for (const unsigned char *p = (const unsigned char *)c.description; *p; p++) require((*p >= 0x20 || *p == '\t') && *p != 0x7F);
    gb_body_release(); /* a body of one's own the scene made (mesh, expression): not kept from input to input */
    return 0;
}
