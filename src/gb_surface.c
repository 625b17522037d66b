#include "gb_surface.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* Morphology I: χ₁ = θ − 5φ (eq 8); ∂φχ₁ = −5, ∂θχ₁ = 1 (eq 18). */
static void phase_one(double phi, double theta, gb_phase_value *v)
{
    v->chi = theta - 5.0 * phi;
    v->chi_phi = -5.0;
    v->chi_theta = 1.0;
    v->chi_phiphi = v->chi_phitheta = v->chi_thetatheta = 0.0;
}

/* Morphology II: χ₂ = θ − (3π/2)(cos φ − cos³φ/3) (eq 9); ∂φχ₂ = (3π/2) sin³φ, which is eq 19's
 * −(3π/2)(cos²φ sin φ − sin φ) simplified; ∂φφχ₂ = (9π/2) sin²φ cos φ. */
static void phase_two(double phi, double theta, gb_phase_value *v)
{
    const double c = cos(phi), s = sin(phi);
    v->chi = theta - 1.5 * M_PI * (c - c * c * c / 3.0);
    v->chi_phi = 1.5 * M_PI * s * s * s;
    v->chi_theta = 1.0;
    v->chi_phiphi = 4.5 * M_PI * s * s * c;
    v->chi_phitheta = v->chi_thetatheta = 0.0;
}

/* The symmetry axes: for I the map (φ,θ) → (π−φ, 3π−θ) keeps χ₁ mod 2π and sends u to the rotation
 * of u by π about e_y; for II, (φ,θ) → (π−φ, −θ) keeps χ₂ (its φ-part is odd in cos φ) and rotates
 * u by π about e_x. Both axes pass through the minimum of sinφ cosχ (φ = π/2, χ = π). */
static const gb_morphology morphologies[] = {
    {"I", "theta - 5 phi", "3, 4, 8, 18", phase_one, {0.0, -1.0, 0.0}},
    {"II", "theta - (3 pi / 2)(cos phi - cos^3 phi / 3)", "5, 6, 9, 19", phase_two,
     {-1.0, 0.0, 0.0}},
};

size_t gb_surface_morphology_count(void) { return sizeof morphologies / sizeof morphologies[0]; }

const gb_morphology *gb_surface_morphology_at(size_t index)
{
    return index < gb_surface_morphology_count() ? &morphologies[index] : NULL;
}

const gb_morphology *gb_surface_morphology_find(const char *name)
{
    for (size_t i = 0; name && i < gb_surface_morphology_count(); i++)
        if (strcmp(morphologies[i].name, name) == 0) return &morphologies[i];
    return NULL;
}

int gb_surface_init(gb_surface *surface, const char *morphology, double beta)
{
    const gb_morphology *m = gb_surface_morphology_find(morphology);
    if (!m)
        return gb_error_set(GB_EINVAL, "morphology '%s' is unknown (allowed: I, II)",
                            morphology ? morphology : "(null)");
    if (!(beta >= 0.0 && beta < GB_SURFACE_BETA_MAX))
        return gb_error_set(GB_EDOM,
                            "beta = %.17g is outside [0, 0.25): r^4 = 1 + 4 beta sin(phi) cos(chi) "
                            "must stay positive on the whole sphere",
                            beta);
    surface->morphology = m;
    surface->beta = beta;
    return GB_OK;
}

void gb_surface_direction(double phi, double theta, double u[3])
{
    const double s = sin(phi);
    u[0] = s * cos(theta);
    u[1] = s * sin(theta);
    u[2] = cos(phi);
}

void gb_surface_eval(const gb_surface *surface, double phi, double theta, gb_surface_point *p)
{
    const double beta4 = 4.0 * surface->beta;
    const double sp = sin(phi), cp = cos(phi), st = sin(theta), ct = cos(theta);
    gb_phase_value *v = &p->phase;
    surface->morphology->phase(phi, theta, v);
    const double sc = sin(v->chi), cc = cos(v->chi);

    p->phi = phi;
    p->theta = theta;
    /* Kernel and its derivatives (eqs 11, 13; second order by differentiating eq 13 again). */
    p->S = 1.0 + beta4 * sp * cc;
    p->S_phi = beta4 * (cp * cc - sp * sc * v->chi_phi);
    p->S_theta = -beta4 * sp * sc * v->chi_theta;
    p->S_phiphi = beta4 * (-sp * cc * (1.0 + v->chi_phi * v->chi_phi) - 2.0 * cp * sc * v->chi_phi -
                           sp * sc * v->chi_phiphi);
    p->S_phitheta = beta4 * (-cp * sc * v->chi_theta - sp * cc * v->chi_phi * v->chi_theta -
                             sp * sc * v->chi_phitheta);
    p->S_thetatheta = -beta4 * sp * (cc * v->chi_theta * v->chi_theta + sc * v->chi_thetatheta);

    /* Radius (eq 12, 14): r_a = ¼ S^(-3/4) S_a, r_ab = ¼ S^(-3/4) S_ab − (3/16) S^(-7/4) S_a S_b. */
    p->r = pow(p->S, 0.25);
    const double d1 = 0.25 * p->r / p->S;                 /* ¼ S^(-3/4) */
    const double d2 = -0.1875 * p->r / (p->S * p->S);     /* −(3/16) S^(-7/4) */
    p->r_phi = d1 * p->S_phi;
    p->r_theta = d1 * p->S_theta;
    p->r_phiphi = d1 * p->S_phiphi + d2 * p->S_phi * p->S_phi;
    p->r_phitheta = d1 * p->S_phitheta + d2 * p->S_phi * p->S_theta;
    p->r_thetatheta = d1 * p->S_thetatheta + d2 * p->S_theta * p->S_theta;

    /* Unit direction and its derivatives (eqs 1, 10); u_φφ = −u. */
    const double u[3] = {sp * ct, sp * st, cp};
    const double u_phi[3] = {cp * ct, cp * st, -sp};
    const double u_theta[3] = {-sp * st, sp * ct, 0.0};
    const double u_phitheta[3] = {-cp * st, cp * ct, 0.0};
    const double u_thetatheta[3] = {-sp * ct, -sp * st, 0.0};
    for (int i = 0; i < 3; i++) {
        p->u[i] = u[i];
        p->u_phi[i] = u_phi[i];
        p->u_theta[i] = u_theta[i];
        p->u_phiphi[i] = -u[i];
        p->u_phitheta[i] = u_phitheta[i];
        p->u_thetatheta[i] = u_thetatheta[i];
        /* Surface point and tangents (eqs 2, 15) and their derivatives. */
        p->x[i] = p->r * u[i];
        p->x_phi[i] = p->r_phi * u[i] + p->r * u_phi[i];
        p->x_theta[i] = p->r_theta * u[i] + p->r * u_theta[i];
        p->x_phiphi[i] = p->r_phiphi * u[i] + 2.0 * p->r_phi * u_phi[i] - p->r * u[i];
        p->x_phitheta[i] = p->r_phitheta * u[i] + p->r_phi * u_theta[i] + p->r_theta * u_phi[i] +
                           p->r * u_phitheta[i];
        p->x_thetatheta[i] =
            p->r_thetatheta * u[i] + 2.0 * p->r_theta * u_theta[i] + p->r * u_thetatheta[i];
    }
    /* Normal (eqs 16, 17). */
    gb_vec_cross(p->x_phi, p->x_theta, p->n);
    const double norm = sqrt(p->n[0] * p->n[0] + p->n[1] * p->n[1] + p->n[2] * p->n[2]);
    for (int i = 0; i < 3; i++) p->n_hat[i] = norm > 0.0 ? p->n[i] / norm : 0.0;
}

double gb_surface_kernel(const gb_surface *surface, double phi, double theta)
{
    gb_phase_value v;
    surface->morphology->phase(phi, theta, &v);
    return 1.0 + 4.0 * surface->beta * sin(phi) * cos(v.chi);
}

double gb_surface_radius(const gb_surface *surface, double phi, double theta)
{
    return pow(gb_surface_kernel(surface, phi, theta), 0.25);
}

void gb_surface_position(const gb_surface *surface, double phi, double theta, double x[3])
{
    const double r = gb_surface_radius(surface, phi, theta);
    gb_surface_direction(phi, theta, x);
    for (int i = 0; i < 3; i++) x[i] *= r;
}

double gb_surface_radius_dbeta(const gb_surface *surface, double phi, double theta)
{
    gb_phase_value v;
    surface->morphology->phase(phi, theta, &v);
    const double S = 1.0 + 4.0 * surface->beta * sin(phi) * cos(v.chi);
    return sin(phi) * cos(v.chi) / pow(S, 0.75); /* eq 66 */
}

void gb_surface_position_dbeta(const gb_surface *surface, double phi, double theta, double dx[3])
{
    const double dr = gb_surface_radius_dbeta(surface, phi, theta);
    gb_surface_direction(phi, theta, dx);
    for (int i = 0; i < 3; i++) dx[i] *= dr; /* eq 67 */
}

double gb_surface_height_dbeta(const gb_surface *surface, double phi, double theta,
                               const double zb[3])
{
    double dx[3];
    gb_surface_position_dbeta(surface, phi, theta, dx);
    return zb[0] * dx[0] + zb[1] * dx[1] + zb[2] * dx[2]; /* eq 68 */
}
