/* gb_dynamics_stepping_rotation — the rotation of one time-stepping step (internal): its free angular velocity and
 * rotational mass, linearised as gomboc does or as Siconos's MoreauJeanOSI does, and the attitude after a step, by the
 * exact quaternion exponential or by Siconos's. docs/stepping.md, docs/siconos.md. */
#include "gb_dynamics_stepper_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* A⁻¹ (A = I + hθc, the rotational mass of a step) as a matrix, by columns. */
static int rotational_mass_inverse(double A[3][3], double out[3][3])
{
    for (int j = 0; j < 3; j++) {
        const double e[3] = {j == 0, j == 1, j == 2};
        double x[3];
        const int status = gb_dyn_solve3(A, e, x);
        if (status) return status;
        for (int i = 0; i < 3; i++) out[i][j] = x[i];
    }
    return GB_OK;
}

/* The rotation's free velocity ω_f of a step (no contact), its rotational mass A and A⁻¹. Ours: the damping torque −cω
 * θ-implicit, the gyroscopic term explicit, (I + hθc) ω_f = Iω − h ω × Iω − h(1 − θ) c ω. Siconos's (`siconos`): the
 * forces f(ω) = ω × Iω + cω θ-implicit linearised at the step's start, (I + hθJ)(ω_f − ω) = −h f(ω), J = ∂f/∂ω =
 * [ω]× I − [Iω]× + c 1 (its MoreauJeanOSI on a NewtonEulerDS; A is not symmetric then). */
int gb_dyn_stepping_free_rotation(double I[3][3], double c, const double w[3], double h, double th, int siconos,
                                  double A[3][3], double Ainv[3][3], double wf[3])
{
    double Iw[3], f[3], b[3];
    gb_dyn_mat_vec(I, w, Iw);
    gb_vec_cross(w, Iw, f);
    const double W[3][3] = {{0.0, -w[2], w[1]}, {w[2], 0.0, -w[0]}, {-w[1], w[0], 0.0}};
    const double L[3][3] = {{0.0, -Iw[2], Iw[1]}, {Iw[2], 0.0, -Iw[0]}, {-Iw[1], Iw[0], 0.0}};
    memcpy(A, I, 9 * sizeof **A);
    for (int i = 0; i < 3; i++) A[i][i] += h * th * c;
    for (int i = 0; i < 3 && siconos; i++)
        for (int j = 0; j < 3; j++) {
            double J = -L[i][j];
            for (int k = 0; k < 3; k++) J += W[i][k] * I[k][j];
            A[i][j] += h * th * J;
        }
    const int status = rotational_mass_inverse(A, Ainv);
    if (status) return status;
    if (siconos) {
        for (int i = 0; i < 3; i++) b[i] = -h * (f[i] + c * w[i]);
        gb_dyn_mat_vec(Ainv, b, wf);
        for (int i = 0; i < 3; i++) wf[i] += w[i];
    } else {
        for (int i = 0; i < 3; i++) b[i] = Iw[i] - h * f[i] - h * (1.0 - th) * c * w[i];
        gb_dyn_mat_vec(Ainv, b, wf);
    }
    return GB_OK;
}

/* q ⊗ exp(h ω / 2): the attitude after a step of h turning at ω (body axes), normalised. */
void gb_dyn_stepping_attitude(const double q[4], const double w[3], double h, double out[4])
{
    const double angle = gb_vec_norm(w) * h;
    double dq[4] = {1.0, 0.0, 0.0, 0.0};
    if (angle > 0.0) {
        const double sn = sin(angle / 2.0) / (angle / h);
        dq[0] = cos(angle / 2.0), dq[1] = sn * w[0], dq[2] = sn * w[1], dq[3] = sn * w[2];
    }
    gb_vec_quaternion_product(q, dq, out);
    const double norm = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
    for (int k = 0; k < 4; k++) out[k] /= norm;
}

/* The attitude Siconos's step predicts, q ⊗ (cos(a/2), h ω sinc(a/2)/2) with a = h|ω|: its quaternion exponential
 * (RotationQuaternion.cpp, quaternionFromTwistVector) evaluates sin(x)/x by a series for |x| ≤ 1e-3, and that series is
 * tan(x)/x's (1 + x²/3 + 2x⁴/15 + …), so below that half-angle the step turns by 2 atan(tan(a/2)/cos(a/2)) = a + a³/8 + …
 * (docs/siconos.md). Followed here to compare one step with Siconos's; gomboc's own steps use gb_dyn_stepping_attitude. */
void gb_dyn_stepping_siconos_attitude(const double q[4], const double w[3], double h, double out[4])
{
    const double angle = gb_vec_norm(w) * h, x = angle / 2.0, x2 = x * x;
    const double sinc = fabs(x) <= 1e-3 ? 1.0 + x2 / 3.0 + x2 * x2 * 2.0 / 15.0 + x2 * x2 * x2 * 17.0 / 315.0 +
                                              x2 * x2 * x2 * x2 * 62.0 / 2835.0
                                        : sin(x) / x;
    const double f = 0.5 * h * sinc, dq[4] = {cos(x), f * w[0], f * w[1], f * w[2]};
    gb_vec_quaternion_product(q, dq, out);
}
