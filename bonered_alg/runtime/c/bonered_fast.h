/* bonered_alg compiled fast path: the per-pose algorithms of bonered_alg/runtime
 * (backsubstitution.py, model.py: solve, _pivot_check, _limit_check, jacobian_and_status)
 * for one pose at a time, included by every generated/<name>.c.  Written once, by hand;
 * tests/test_fast_path.py holds it against the numpy runtime, status codes included.
 *
 * Compiled without -ffast-math and with -ffp-contract=off: IEEE arithmetic in the order
 * the generated kernels write it, NaN and infinity as numpy has them. */
#ifndef BONERED_FAST_H
#define BONERED_FAST_H

#include <math.h>

/* status codes: bonered_alg/runtime/status.py (tests/test_fast_path.py checks they agree) */
#define BF_OK 0
#define BF_NO_REAL_SOLUTION 1
#define BF_JOINT_AT_INFINITY 2
#define BF_ON_BOUNDARY 3
#define BF_INPUT_SINGULAR 4
#define BF_INVALID_INPUT 5
#define BF_STROKE_LIMIT 6
#define BF_PASSIVE_JOINT_LIMIT 7
#define BF_DISC_RTOL 1e-10
#define BF_DET_RTOL 1e-12

static inline int bf_all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* the status update of backsubstitute: the first failure wins, a failure overrides an
 * earlier ON_BOUNDARY */
static inline void bf_update(int *status, int code, int bad)
{
    if (*status == BF_OK || (*status == BF_ON_BOUNDARY && bad))
        *status = code;
}

/* B q + C = 0 */
static inline double bf_linear(double b, double c, int *status, int *failed)
{
    double root = -c / b;
    int bad = !isfinite(root);
    int code = bad ? (b == 0.0 ? BF_INPUT_SINGULAR : BF_JOINT_AT_INFINITY) : BF_OK;
    bf_update(status, code, bad);
    *failed |= bad;
    return bad ? NAN : root;
}

/* A q^2 + B q + C = 0, the root of the mode's sign, in the form that never subtracts nearly
 * equal numbers */
static inline double bf_quadratic(double a, double b, double c, int minus, int *status,
                                  int *failed)
{
    double sign = minus ? -1.0 : 1.0;
    double bb = b * b;
    double disc = bb - 4.0 * a * c;
    /* numpy.maximum(disc, 0.0): NaN stays NaN */
    double clipped = isnan(disc) ? disc : (disc > 0.0 ? disc : 0.0);
    double ssq = sign * sqrt(clipped);
    double root = (sign * b <= 0.0) ? (ssq - b) / (2.0 * a) : (2.0 * c) / (-b - ssq);
    int no_real = disc < -BF_DISC_RTOL * bb;
    int bad = no_real || !isfinite(root);
    int code = bad ? BF_JOINT_AT_INFINITY : BF_OK;
    if (no_real)
        code = BF_NO_REAL_SOLUTION;
    if (!bad && fabs(disc) <= BF_DISC_RTOL * bb)
        code = BF_ON_BOUNDARY;
    bf_update(status, code, bad);
    *failed |= bad;
    return bad ? NAN : root;
}

/* model._pivot_check: |d| <= DET_RTOL |scale| for any pivot (NaN is not singular here) */
static inline int bf_pivots_vanish(const double *v, int n)
{
    int singular = 0;
    for (int k = 0; k < n; k++)
        singular |= fabs(v[k]) <= BF_DET_RTOL * fabs(v[n + k]);
    return singular;
}

/* model.pivot_singular: not |d| > DET_RTOL scale (NaN is singular here) */
static inline int bf_pivots_singular(const double *v, int n)
{
    int singular = 0;
    for (int k = 0; k < n; k++)
        singular |= !(fabs(v[k]) > BF_DET_RTOL * v[n + k]);
    return singular;
}

static inline void bf_fill_nan(double *v, int n)
{
    for (int i = 0; i < n; i++)
        v[i] = NAN;
}

#endif
