#include "gb_massprops.h"


#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

/* Which surface integral: ∫ r^power / power · weight(u) dΩ, weight one of 1, u_i, u_i u_j. */
typedef struct integrand {
    int power;
    int axis_a, axis_b; /* −1 for "no factor" */
} integrand;

typedef struct nested {
    const gb_surface *surface;
    integrand what;
    const gb_massprops_def *def;
    double epsabs; /* def->epsabs in the integrand's units */
    gsl_integration_workspace *inner_ws;
    double theta;
    double inner_err_max;
    size_t evaluations;
    int status;
} nested;

static double inner_integrand(double phi, void *params)
{
    nested *n = params;
    double u[3];
    n->evaluations++;
    gb_surface_direction(phi, n->theta, u);
    const double r = gb_surface_radius(n->surface, phi, n->theta);
    double value = pow(r, n->what.power) / n->what.power * sin(phi);
    if (n->what.axis_a >= 0) value *= u[n->what.axis_a];
    if (n->what.axis_b >= 0) value *= u[n->what.axis_b];
    return value;
}

static double outer_integrand(double theta, void *params)
{
    nested *n = params;
    gsl_function f = {inner_integrand, n};
    double result = 0.0, abserr = 0.0;
    n->theta = theta;
    int status = gsl_integration_qag(&f, 0.0, M_PI, n->epsabs, n->def->epsrel, n->def->limit,
                                     GSL_INTEG_GAUSS21, n->inner_ws, &result, &abserr);
    if (status != GSL_SUCCESS && n->status == GSL_SUCCESS) n->status = status;
    if (abserr > n->inner_err_max) n->inner_err_max = abserr;
    return result;
}

static int surface_integral(const gb_surface *surface, const gb_massprops_def *def, double scale,
                            integrand what, double *value, double *error, size_t *evaluations)
{
    /* the absolute target in the integrand's own units: epsabs times scale^power, r ~ scale */
    const double epsabs = def->epsabs * pow(scale, what.power);
    gsl_integration_workspace *inner = gsl_integration_workspace_alloc(def->limit);
    gsl_integration_workspace *outer = gsl_integration_workspace_alloc(def->limit);
    if (!inner || !outer) {
        gsl_integration_workspace_free(inner);
        gsl_integration_workspace_free(outer);
        return gb_error_set(GB_ENOMEM, "massprops: cannot allocate quadrature workspaces");
    }
    nested n = {surface, what, def, epsabs, inner, 0.0, 0.0, 0, GSL_SUCCESS};
    gsl_function f = {outer_integrand, &n};
    double abserr = 0.0;
    int status = gsl_integration_qag(&f, 0.0, 2.0 * M_PI, epsabs, def->epsrel, def->limit,
                                     GSL_INTEG_GAUSS21, outer, value, &abserr);
    gsl_integration_workspace_free(inner);
    gsl_integration_workspace_free(outer);
    *evaluations += n.evaluations;
    if (status == GSL_SUCCESS) status = n.status;
    if (status != GSL_SUCCESS)
        return gb_error_set(GB_ENOCONV,
                            "massprops: nested quadrature of r^%d failed (%s) at epsrel = %g, "
                            "epsabs = %g, limit = %zu",
                            what.power, gsl_strerror(status), def->epsrel, def->epsabs,
                            def->limit);
    *error = abserr + 2.0 * M_PI * n.inner_err_max;
    return GB_OK;
}

gb_massprops_def gb_massprops_default_def(void)
{
    /* 1e-11 relative per 1-D integral: three orders above the round-off floor of a 21-point rule
     * summed over ~10² panels, and far below what any later use needs (L enters as a scale). */
    return (gb_massprops_def){.mass = 1.0, .epsabs = 1e-13, .epsrel = 1e-11, .limit = 2000};
}

int gb_massprops_compute(const gb_surface *surface, const gb_massprops_def *def, gb_massprops *out)
{
    if (!(def->mass > 0.0 && isfinite(def->mass)))
        return gb_error_set(GB_EDOM, "mass = %.17g must be positive and finite", def->mass);
    if (!(def->epsabs >= 0.0 && def->epsrel >= 0.0 && def->epsabs + def->epsrel > 0.0 &&
          def->limit > 0))
        return gb_error_set(GB_EDOM,
                            "massprops tolerances must be non-negative, not both zero, with "
                            "limit > 0 (got epsabs = %g, epsrel = %g, limit = %zu)",
                            def->epsabs, def->epsrel, def->limit);
    *out = (gb_massprops){0};
    if (surface->morphology->massprops) /* a body kind's own (a mesh's closed form, gb_body.c) */
        return surface->morphology->massprops(surface->morphology, def->mass, out);
    int status;
    double first[3], first_err[3], second[3][3], second_err[3][3], l_sum, l_err;
    /* the body's scale: the power of two nearest its radius at (pi/2, 0), so that an integral of r^p meets an
     * absolute target of epsabs scale^p whatever the body's size (r = 1e3 m failed on round-off against 1e-13);
     * a power of two scales exactly, and a body of unit size (the paper's: r within 0.88 .. 1.13) keeps scale 1 */
    const double r0 = gb_surface_radius(surface, 0.5 * M_PI, 0.0);
    const double scale = r0 > 0.0 && isfinite(r0) ? ldexp(1.0, (int)lround(log2(r0))) : 1.0;
    if ((status = surface_integral(surface, def, scale, (integrand){3, -1, -1}, &out->volume,
                                   &out->volume_err, &out->evaluations)))
        return status;
    for (int i = 0; i < 3; i++)
        if ((status = surface_integral(surface, def, scale, (integrand){4, i, -1}, &first[i],
                                       &first_err[i], &out->evaluations)))
            return status;
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
            if ((status = surface_integral(surface, def, scale, (integrand){5, i, j}, &second[i][j],
                                           &second_err[i][j], &out->evaluations)))
                return status;
            second[j][i] = second[i][j];
            second_err[j][i] = second_err[i][j];
        }
    if ((status = surface_integral(surface, def, scale, (integrand){1, -1, -1}, &l_sum, &l_err,
                                   &out->evaluations)))
        return status;

    out->mass = def->mass;
    out->density = def->mass / out->volume;
    out->L = l_sum / (4.0 * M_PI); /* eq 53 */
    out->L_err = l_err / (4.0 * M_PI);
    double c2 = 0.0, chart_centroid[3]; /* the centroid from the chart's origin, where the moments are taken */
    for (int i = 0; i < 3; i++) {
        chart_centroid[i] = first[i] / out->volume;
        out->centroid_err[i] = first_err[i] / out->volume +
                               fabs(first[i]) * out->volume_err / (out->volume * out->volume);
        c2 += chart_centroid[i] * chart_centroid[i];
        /* in the body's axes: a body moved to its centroid (gb_morphology.origin) has it at 0 to rounding */
        out->centroid[i] = surface->morphology->moved ? chart_centroid[i] + surface->morphology->origin[i] : chart_centroid[i];
    }
    /* I_O = ρ (tr M δ − M) with M = ∫ x xᵀ dV; then the parallel-axis shift to the centroid. */
    const double trace = second[0][0] + second[1][1] + second[2][2];
    const double trace_err = second_err[0][0] + second_err[1][1] + second_err[2][2];
    const double rel_density_err = out->volume_err / out->volume;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double delta = i == j ? 1.0 : 0.0;
            const double origin = out->density * (trace * delta - second[i][j]);
            out->inertia[i][j] =
                origin - def->mass * (c2 * delta - chart_centroid[i] * chart_centroid[j]);
            out->inertia_err[i][j] = out->density * (trace_err * delta + second_err[i][j]) +
                                     fabs(origin) * rel_density_err;
        }
    return GB_OK;
}
