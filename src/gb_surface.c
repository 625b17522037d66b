#include "gb_surface_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Morphology I: χ₁ = θ − 5φ (eq 8); ∂φχ₁ = −5, ∂θχ₁ = 1 (eq 18). */
static void phase_one(const gb_morphology *self, double phi, double theta, gb_phase_value *v)
{
    (void)self;
    v->chi = theta - 5.0 * phi;
    v->chi_phi = -5.0;
    v->chi_theta = 1.0;
    v->chi_phiphi = v->chi_phitheta = v->chi_thetatheta = 0.0;
}

/* Morphology II: χ₂ = θ − (3π/2)(cos φ − cos³φ/3) (eq 9); ∂φχ₂ = (3π/2) sin³φ, which is eq 19's
 * −(3π/2)(cos²φ sin φ − sin φ) simplified; ∂φφχ₂ = (9π/2) sin²φ cos φ. */
static void phase_two_at(double theta, double s, double c, gb_phase_value *v)
{
    v->chi = theta - 1.5 * M_PI * (c - c * c * c / 3.0);
    v->chi_phi = 1.5 * M_PI * s * s * s;
    v->chi_theta = 1.0;
    v->chi_phiphi = 4.5 * M_PI * s * s * c;
    v->chi_phitheta = v->chi_thetatheta = 0.0;
}

static void phase_two(const gb_morphology *self, double phi, double theta, gb_phase_value *v)
{
    (void)self;
    phase_two_at(theta, sin(phi), cos(phi), v);
}

/* The same with sin χ and cos χ from the sines and cosines of φ and θ, for gb_surface_eval: one
 * sincos of φ and one of θ serve u, the kernel and (for I) χ, by cos χ = cos θ cos f + sin θ sin f and
 * sin χ = sin θ cos f − cos θ sin f with χ = θ − f(φ). I: cos 5φ = T₅(cos φ), sin 5φ = sin φ U₄(cos φ)
 * (no trigonometric call); II: one sincos of f. */
static void phase_one_eval(const gb_morphology *self, double phi, double theta, double sp, double cp, double st, double ct, gb_phase_value *v,
                           double *sin_chi, double *cos_chi)
{
    phase_one(self, phi, theta, v);
    const double c2 = cp * cp;
    const double cf = cp * (5.0 + c2 * (-20.0 + 16.0 * c2)), sf = sp * (1.0 + c2 * (-12.0 + 16.0 * c2));
    *cos_chi = ct * cf + st * sf;
    *sin_chi = st * cf - ct * sf;
}

static void phase_two_eval(const gb_morphology *self, double phi, double theta, double sp, double cp, double st, double ct, gb_phase_value *v,
                           double *sin_chi, double *cos_chi)
{
    (void)self, (void)phi;
    phase_two_at(theta, sp, cp, v);
    double sf, cf;
    sincos(1.5 * M_PI * (cp - cp * cp * cp / 3.0), &sf, &cf); /* f, as phase_two_at subtracts it from θ */
    *cos_chi = ct * cf + st * sf;
    *sin_chi = st * cf - ct * sf;
}

/* The kernel's angular part sinφ cos χ written through the unit direction s = (s_x, s_y, s_z), for the
 * interval enclosures of gb_surface_enclose (which also work in a chart without the (φ, θ) poles).
 * Both phases are χ = θ − f(φ), so sinφ cos χ = s_x cos f + s_y sin f (sinφ cosθ = s_x, sinφ sinθ = s_y).
 * I: f = 5φ, cos 5φ = T₅(s_z) and sin 5φ = sinφ U₄(s_z) (Chebyshev), sinφ = √(s_x² + s_y²); the term
 * s_y √(s_x² + s_y²) makes the body C¹,¹ but not C² at the poles s = ±e_z (its Hessian is bounded and
 * jumps there). Returns 1 when the jet is of a C² function over the box, 0 when its second
 * derivatives only enclose the Hessian where one exists. */
static int kernel_jet_one(const gb_jet s[3], gb_jet *k)
{
    static const double T5[] = {0.0, 5.0, 0.0, -20.0, 0.0, 16.0}, U4[] = {1.0, 0.0, -12.0, 0.0, 16.0};
    *k = gb_jet_add(gb_jet_mul(s[0], gb_jet_poly(s[2], T5, 5)),
                    gb_jet_mul(gb_jet_y_hypot(s[0], s[1]), gb_jet_poly(s[2], U4, 4)));
    return gb_interval_add(gb_interval_sqr(s[0].v), gb_interval_sqr(s[1].v)).lo > 0.0;
}

/* II: f = (3π/2)(s_z − s_z³/3), a polynomial in s_z: smooth everywhere. */
static int kernel_jet_two(const gb_jet s[3], gb_jet *k)
{
    static const double F[] = {0.0, 1.5 * M_PI, 0.0, -0.5 * M_PI};
    const gb_jet f = gb_jet_poly(s[2], F, 3);
    *k = gb_jet_add(gb_jet_mul(s[0], gb_jet_cos(f)), gb_jet_mul(s[1], gb_jet_sin(f)));
    return 1;
}

/* The symmetry axes: for I the map (φ,θ) → (π−φ, 3π−θ) keeps χ₁ mod 2π and sends u to the rotation
 * of u by π about e_y; for II, (φ,θ) → (π−φ, −θ) keeps χ₂ (its φ-part is odd in cos φ) and rotates
 * u by π about e_x. Both axes pass through the minimum of sinφ cosχ (φ = π/2, χ = π). */
static const gb_morphology morphologies[] = {
    {"I", "theta - 5 phi", "3, 4, 8, 18", phase_one, phase_one_eval, kernel_jet_one, {0.0, -1.0, 0.0}, NULL, NULL, NULL, {0.0, 0.0, 0.0}, 0, NULL},
    {"II", "theta - (3 pi / 2)(cos phi - cos^3 phi / 3)", "5, 6, 9, 19", phase_two, phase_two_eval,
     kernel_jet_two, {-1.0, 0.0, 0.0}, NULL, NULL, NULL, {0.0, 0.0, 0.0}, 0, NULL},
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
    if (!m) {
        char allowed[128] = "";
        size_t used = 0;
        for (size_t k = 0; k < gb_surface_morphology_count() && used < sizeof allowed; k++)
            used += (size_t)snprintf(allowed + used, sizeof allowed - used, "%s%s", k ? ", " : "", morphologies[k].name);
        return gb_error_set(GB_EINVAL, "morphology '%s' is unknown (allowed: %s)", morphology ? morphology : "(null)", allowed);
    }
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
    gb_surface_eval_jet(surface, phi, theta, p);
    gb_surface_normal(p);
}

void gb_surface_normal(gb_surface_point *p)
{
    /* Normal (eqs 16, 17). */
    gb_vec_cross(p->x_phi, p->x_theta, p->n);
    const double norm = sqrt(p->n[0] * p->n[0] + p->n[1] * p->n[1] + p->n[2] * p->n[2]);
    for (int i = 0; i < 3; i++) p->n_hat[i] = norm > 0.0 ? p->n[i] / norm : 0.0;
}

static void kernel_from_phase(double beta4, double sp, double cp, double sc, double cc, const gb_phase_value *v,
                              gb_surface_point *p);
static void surface_from_kernel(double sp, double cp, double st, double ct, gb_surface_point *p);

void gb_surface_eval_jet(const gb_surface *surface, double phi, double theta, gb_surface_point *p)
{
    const double beta4 = 4.0 * surface->beta;
    double sp, cp, st, ct, sc, cc;
    sincos(phi, &sp, &cp);
    sincos(theta, &st, &ct);
    gb_phase_value *v = &p->phase;
    p->phi = phi;
    p->theta = theta;
    if (surface->morphology->kernel) { /* a body given by r (gb_body.h): no phase */
        double S[6];
        memset(v, 0, sizeof *v);
        surface->morphology->kernel(surface->morphology, surface->beta, phi, theta, S);
        p->S = S[0], p->S_phi = S[1], p->S_theta = S[2], p->S_phiphi = S[3], p->S_phitheta = S[4], p->S_thetatheta = S[5];
    } else {
        surface->morphology->phase_eval(surface->morphology, phi, theta, sp, cp, st, ct, v, &sc, &cc);
        kernel_from_phase(beta4, sp, cp, sc, cc, v, p);
    }
    surface_from_kernel(sp, cp, st, ct, p);
    if (surface->morphology->moved) /* about the centroid; the tangents and their derivatives do not move */
        for (int i = 0; i < 3; i++) p->x[i] += surface->morphology->origin[i];
}

/* Kernel and its derivatives (eqs 11, 13; second order by differentiating eq 13 again). */
static void kernel_from_phase(double beta4, double sp, double cp, double sc, double cc, const gb_phase_value *v,
                              gb_surface_point *p)
{
    p->S = 1.0 + beta4 * sp * cc;
    p->S_phi = beta4 * (cp * cc - sp * sc * v->chi_phi);
    p->S_theta = -beta4 * sp * sc * v->chi_theta;
    p->S_phiphi = beta4 * (-sp * cc * (1.0 + v->chi_phi * v->chi_phi) - 2.0 * cp * sc * v->chi_phi -
                           sp * sc * v->chi_phiphi);
    p->S_phitheta = beta4 * (-cp * sc * v->chi_theta - sp * cc * v->chi_phi * v->chi_theta -
                             sp * sc * v->chi_phitheta);
    p->S_thetatheta = -beta4 * sp * (cc * v->chi_theta * v->chi_theta + sc * v->chi_thetatheta);
}

/* r, u, x and their derivatives from the kernel's (eqs 1, 2, 10, 12, 14, 15). */
static void surface_from_kernel(double sp, double cp, double st, double ct, gb_surface_point *p)
{
    /* Radius (eq 12, 14): r_a = ¼ S^(-3/4) S_a, r_ab = ¼ S^(-3/4) S_ab − (3/16) S^(-7/4) S_a S_b. */
    p->r = sqrt(sqrt(p->S)); /* S^(1/4): two correctly rounded square roots, cheaper than pow */
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
}

double gb_surface_kernel(const gb_surface *surface, double phi, double theta)
{
    if (surface->morphology->kernel) {
        double S[6];
        surface->morphology->kernel(surface->morphology, surface->beta, phi, theta, S);
        return S[0];
    }
    gb_phase_value v;
    surface->morphology->phase(surface->morphology, phi, theta, &v);
    return 1.0 + 4.0 * surface->beta * sin(phi) * cos(v.chi);
}

double gb_surface_radius(const gb_surface *surface, double phi, double theta)
{
    return sqrt(sqrt(gb_surface_kernel(surface, phi, theta)));
}

void gb_surface_position(const gb_surface *surface, double phi, double theta, double x[3])
{
    const double r = gb_surface_radius(surface, phi, theta);
    gb_surface_direction(phi, theta, x);
    for (int i = 0; i < 3; i++) x[i] *= r;
    if (surface->morphology->moved)
        for (int i = 0; i < 3; i++) x[i] += surface->morphology->origin[i];
}

double gb_surface_radius_dbeta(const gb_surface *surface, double phi, double theta)
{
    if (surface->morphology->kernel) return NAN; /* r given as an expression: β enters it as the user wrote it */
    gb_phase_value v;
    surface->morphology->phase(surface->morphology, phi, theta, &v);
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

/* ---------------------------------------------------------------- enclosures over chart boxes */

static void chart_direction(gb_surface_chart chart, double a, double b, double u[3])
{
    const double sa = sin(a), ca = cos(a), sb = sin(b), cb = cos(b);
    if (chart == GB_SURFACE_CHART_POLAR_Z)
        u[0] = sa * cb, u[1] = sa * sb, u[2] = ca;
    else
        u[0] = ca, u[1] = sa * cb, u[2] = sa * sb;
}

void gb_surface_chart_coordinates(gb_surface_chart chart, double phi, double theta, double *a, double *b)
{
    if (chart == GB_SURFACE_CHART_POLAR_Z) {
        *a = phi, *b = theta;
        return;
    }
    double u[3];
    gb_surface_direction(phi, theta, u);
    *a = acos(fmax(-1.0, fmin(1.0, u[0])));
    *b = atan2(u[2], u[1]);
    if (*b < 0.0) *b += 2.0 * M_PI;
}

void gb_surface_chart_angles(gb_surface_chart chart, double a, double b, double *phi, double *theta)
{
    if (chart == GB_SURFACE_CHART_POLAR_Z) {
        *phi = a, *theta = b;
    } else {
        double u[3];
        chart_direction(chart, a, b, u);
        *phi = acos(fmax(-1.0, fmin(1.0, u[2])));
        *theta = atan2(u[1], u[0]);
    }
    *theta = fmod(*theta, 2.0 * M_PI);
    if (*theta < 0.0) *theta += 2.0 * M_PI;
}

/* x = r(s)·s over the box as jets: s from the chart, S = 1 + 4β sinφ cos χ (eq 11), r = S^(1/4) (eq 12). */
static int position_jets(const gb_surface *surface, gb_surface_chart chart, gb_jet a, gb_jet b, gb_jet x[3])
{
    const gb_jet sa = gb_jet_sin(a), ca = gb_jet_cos(a), sb = gb_jet_sin(b), cb = gb_jet_cos(b);
    gb_jet s[3];
    if (chart == GB_SURFACE_CHART_POLAR_Z)
        s[0] = gb_jet_mul(sa, cb), s[1] = gb_jet_mul(sa, sb), s[2] = ca;
    else
        s[0] = ca, s[1] = gb_jet_mul(sa, cb), s[2] = gb_jet_mul(sa, sb);
    gb_jet k;
    const int smooth = surface->morphology->kernel_jet(s, &k);
    const gb_jet r = gb_jet_root4(gb_jet_add_const(1.0, gb_jet_scale(4.0 * surface->beta, k)));
    for (int i = 0; i < 3; i++) x[i] = gb_jet_mul(r, s[i]);
    return smooth;
}

/* The midpoint of a point computation's enclosure: within a few ulps of the exact value. */
static double centre(gb_interval v) { return 0.5 * v.lo + 0.5 * v.hi; }

void gb_surface_eval_chart(const gb_surface *surface, gb_surface_chart chart, double a, double b, gb_surface_point *p)
{
    memset(p, 0, sizeof *p);
    chart_direction(chart, a, b, p->u);
    gb_surface_chart_angles(chart, a, b, &p->phi, &p->theta);
    if (surface->beta == 0.0 && chart == GB_SURFACE_CHART_POLAR_X) {
        /* the sphere: r ≡ 1 and x = u(a, b) = (cos a, sin a cos b, sin a sin b), derivatives in closed form */
        const double sa = sin(a), ca = cos(a), sb = sin(b), cb = cos(b);
        const double xa[3] = {-sa, ca * cb, ca * sb}, xb[3] = {0.0, -sa * sb, sa * cb};
        const double xab[3] = {0.0, -ca * sb, ca * cb}, xbb[3] = {0.0, -sa * cb, -sa * sb};
        for (int i = 0; i < 3; i++) {
            p->x[i] = p->u[i], p->x_phi[i] = xa[i], p->x_theta[i] = xb[i];
            p->x_phiphi[i] = -p->u[i], p->x_phitheta[i] = xab[i], p->x_thetatheta[i] = xbb[i];
        }
        p->r = 1.0;
        return;
    }
    gb_jet x[3];
    position_jets(surface, chart, gb_jet_param_a(a, a), gb_jet_param_b(b, b), x);
    for (int i = 0; i < 3; i++) {
        p->x[i] = centre(x[i].v);
        p->x_phi[i] = centre(x[i].a), p->x_theta[i] = centre(x[i].b);
        p->x_phiphi[i] = centre(x[i].aa), p->x_phitheta[i] = centre(x[i].ab), p->x_thetatheta[i] = centre(x[i].bb);
    }
    p->r = sqrt(p->x[0] * p->x[0] + p->x[1] * p->x[1] + p->x[2] * p->x[2]);
}

/* Offsets of the box from its centre, as intervals. */
static gb_interval offset(double lo, double hi, double centre)
{
    return gb_interval_make(lo - centre, hi - centre);
}

void gb_surface_enclose(const gb_surface *surface, gb_surface_chart chart, double a_lo, double a_hi, double b_lo,
                        double b_hi, gb_surface_enclosure *out)
{
    gb_jet box[3], mid[3];
    out->smooth = position_jets(surface, chart, gb_jet_param_a(a_lo, a_hi), gb_jet_param_b(b_lo, b_hi), box);
    const double ac = 0.5 * (a_lo + a_hi), bc = 0.5 * (b_lo + b_hi);
    position_jets(surface, chart, gb_jet_first_order(gb_jet_param_a(ac, ac)), gb_jet_first_order(gb_jet_param_b(bc, bc)), mid);
    const gb_interval da = offset(a_lo, a_hi, ac), db = offset(b_lo, b_hi, bc);
    const gb_interval da2 = gb_interval_sqr(da), db2 = gb_interval_sqr(db), dadb = gb_interval_mul(da, db);
    out->da = da, out->db = db;
    for (int i = 0; i < 3; i++) {
        out->x_c[i] = mid[i].v, out->x_a_c[i] = mid[i].a, out->x_b_c[i] = mid[i].b;
        /* Second-order Taylor form with the box Hessian as Lagrange remainder, met with the direct
         * enclosure; first-order form for the tangents. */
        gb_interval taylor = gb_interval_add(mid[i].v, gb_interval_add(gb_interval_mul(mid[i].a, da), gb_interval_mul(mid[i].b, db)));
        const gb_interval second =
            gb_interval_add(gb_interval_add(gb_interval_mul(box[i].aa, da2), gb_interval_mul(box[i].bb, db2)),
                            gb_interval_scale(2.0, gb_interval_mul(box[i].ab, dadb)));
        taylor = gb_interval_add(taylor, gb_interval_scale(0.5, second));
        out->x[i] = gb_interval_meet(box[i].v, taylor);
        out->x_a[i] = gb_interval_meet(
            box[i].a, gb_interval_add(mid[i].a, gb_interval_add(gb_interval_mul(box[i].aa, da), gb_interval_mul(box[i].ab, db))));
        out->x_b[i] = gb_interval_meet(
            box[i].b, gb_interval_add(mid[i].b, gb_interval_add(gb_interval_mul(box[i].ab, da), gb_interval_mul(box[i].bb, db))));
        out->x_aa[i] = box[i].aa;
        out->x_ab[i] = box[i].ab;
        out->x_bb[i] = box[i].bb;
    }
}
