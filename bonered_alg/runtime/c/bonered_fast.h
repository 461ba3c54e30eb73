/* bonered_alg compiled fast path: the per-pose algorithms of bonered_alg/runtime
 * (backsubstitution.py, model.py: solve, _pivot_check, _limit_check, jacobian_and_status)
 * for one pose at a time, included by every generated/<name>.c.  Written once, by hand;
 * tests/test_fast_path.py holds it against the numpy runtime, status codes included.
 *
 * Compiled without -ffast-math and with -ffp-contract=off: IEEE arithmetic in the order
 * the generated kernels write it, NaN and infinity as numpy has them.  The per-pose rules
 * are written without branches (selects), so that the block loops of generated/<name>.c
 * vectorize across poses; the elementary functions then come from glibc's vector math
 * library (libmvec, at most 4 ulp from the scalar libm, which numpy's own SIMD functions
 * are not equal to either), declared below where it has them. */
#ifndef BONERED_FAST_H
#define BONERED_FAST_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#if defined(__SSE2__) && !defined(BF_NO_STREAM)
#include <emmintrin.h>
#define BF_HAVE_STREAM 1
#endif

/* poses per block of the generated drivers: every intermediate array stays in L1/L2 */
#ifndef BF_BLOCK
#define BF_BLOCK 64
#endif

/* every block the drivers hand to a stage is a multiple of BF_LANES poses (the widest
 * vector of doubles, AVX-512's), so that each pose goes through the vectorized loop bodies
 * and never through their scalar remainder (scalar libm, up to 4 ulp from libmvec): a
 * pose's numbers do not depend on the batch it comes in.  A batch's last partial block is
 * computed as whole lanes overlapping the poses before it (bf_tail_blocks: those computed
 * again, to the same bits), a batch of fewer than BF_LANES poses padded with copies of its
 * last pose, and a scan's last block with copies of its last sample */
#ifndef BF_LANES
#define BF_LANES 8
#endif

#if defined(__GNUC__)
#define BF_INLINE static inline __attribute__((always_inline))
#else
#define BF_INLINE static inline
#endif

/* a function of the library that is no entry point (it may be defined in another of its
 * translation units: bonered_alg.runtime.compiled builds a file in parts) */
#if defined(__GNUC__)
#define BF_INTERNAL __attribute__((visibility("hidden")))
#else
#define BF_INTERNAL
#endif

/* the block functions of the drivers: compiled once, for any block size, and never
 * specialized to a call's constant size (inlined or cloned for the padded BF_LANES of a
 * small batch, gcc vectorized them otherwise: other libmvec widths, other last bits) */
#if defined(__GNUC__) && !defined(__clang__)
#define BF_NOIPA __attribute__((noipa))
#elif defined(__GNUC__)
#define BF_NOIPA __attribute__((noinline))
#else
#define BF_NOIPA
#endif

/* The blocks [start[b], start[b] + size[b]) that cover a batch's partial last block
 * [lo, n), n >= BF_LANES, in whole lanes: the batch's last ceil(m / BF_LANES) lanes, or,
 * where the batch is shorter than that (its only block), its first and its last
 * floor(n / BF_LANES) lanes.  Returns their number (1 or 2). */
BF_INLINE int bf_tail_blocks(long lo, long n, long *start, int *size)
{
    int m = (int)(n - lo);
    int e = (m + BF_LANES - 1) / BF_LANES * BF_LANES;
    if (e <= n) {
        start[0] = n - e;
        size[0] = e;
        return 1;
    }
    int f = (int)(n / BF_LANES * BF_LANES);
    start[0] = 0;
    size[0] = f;
    start[1] = n - f;
    size[1] = f;
    return 2;
}

/* status s replaced by code where cond (0 or 1), without a branch */
#define BF_SET(s, cond, code) ((s) + (cond) * ((code) - (s)))

/* finite, without a branch: NaN compares false, infinity is above DBL_MAX */
#define BF_FIN(x) (fabs(x) <= DBL_MAX)

/* glibc >= 2.35 has SIMD variants of these on x86-64 (libmvec; with -fopenmp-simd the
 * compiler calls them from vectorized loops).  They are declared under other names bound
 * to the libm symbols: the compiler then does not fuse sin and cos of one argument into
 * sincos, which it cannot vectorize. */
#if defined(__x86_64__) && defined(__GLIBC__) && defined(__GLIBC_MINOR__) && \
    (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35)) && !defined(BF_NO_VECTOR_MATH)
#define BF_VECTOR_MATH(name, args) \
    _Pragma("omp declare simd notinbranch") \
    extern double bf_##name args __asm__(#name) __attribute__((const, nothrow));
BF_VECTOR_MATH(sin, (double))
BF_VECTOR_MATH(cos, (double))
BF_VECTOR_MATH(tan, (double))
BF_VECTOR_MATH(asin, (double))
BF_VECTOR_MATH(acos, (double))
BF_VECTOR_MATH(atan, (double))
BF_VECTOR_MATH(exp, (double))
BF_VECTOR_MATH(log, (double))
BF_VECTOR_MATH(atan2, (double, double))
BF_VECTOR_MATH(pow, (double, double))
#define sin(x) bf_sin(x)
#define cos(x) bf_cos(x)
#define tan(x) bf_tan(x)
#define asin(x) bf_asin(x)
#define acos(x) bf_acos(x)
#define atan(x) bf_atan(x)
#define exp(x) bf_exp(x)
#define log(x) bf_log(x)
#define atan2(x, y) bf_atan2(x, y)
#define pow(x, y) bf_pow(x, y)
#endif

/* A Jacobian output of one call at least this large is written with non-temporal stores
 * (generated/<name>.c, where each pose's entries are an even number): it does not fit in
 * cache, and a plain store first reads the line it writes.  Measured on this project's
 * 2-vCPU machine in one process, planar_tripod IK + 6x6 Jacobian of 1e6 poses on two
 * threads: 50 ms with plain stores, 36 ms streamed; the joints (48 bytes a pose) streamed
 * too ran slower, so they are not. */
#ifndef BF_STREAM_BYTES
#define BF_STREAM_BYTES (8L << 20)
#endif

/* after a call's streamed stores: ordered before anything that follows */
BF_INLINE void bf_stream_done(int stream)
{
#ifdef BF_HAVE_STREAM
    if (stream)
        _mm_sfence();
#else
    (void)stream;
#endif
}

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

/* The per-pose rules below are arithmetic on 0/1 flags rather than branches or short
 * circuits, which compilers turn back into branches and then cannot vectorize. */

/* the status update of backsubstitute: the first failure wins, a failure overrides an
 * earlier ON_BOUNDARY */
BF_INLINE void bf_update(int *status, int code, int bad)
{
    int s = *status;
    int take = (s == BF_OK) | ((s == BF_ON_BOUNDARY) & bad);
    *status = BF_SET(s, take, code);
}

/* B q + C = 0 */
BF_INLINE double bf_linear(double b, double c, int *status, int *failed)
{
    double root = -c / b;
    int bad = !BF_FIN(root);
    /* bad: INPUT_SINGULAR where b = 0, else JOINT_AT_INFINITY */
    int code = bad * (BF_JOINT_AT_INFINITY + (b == 0.0) * (BF_INPUT_SINGULAR
                                                           - BF_JOINT_AT_INFINITY));
    bf_update(status, code, bad);
    *failed |= bad;
    return bad ? NAN : root;
}

/* A q^2 + B q + C = 0, the root of the mode's sign, in the form that never subtracts nearly
 * equal numbers */
BF_INLINE double bf_quadratic(double a, double b, double c, int minus, int *status,
                              int *failed)
{
    double sign = minus ? -1.0 : 1.0;
    double bb = b * b;
    double disc = bb - 4.0 * a * c;
    /* numpy.maximum(disc, 0.0): NaN stays NaN (and -0.0 for disc <= 0: the same roots) */
    double clipped = disc * (double)((disc > 0.0) | (disc != disc));
    double ssq = sign * sqrt(clipped);
    double near = (ssq - b) / (2.0 * a), far = (2.0 * c) / (-b - ssq);
    double root = (sign * b <= 0.0) ? near : far;
    int no_real = disc < -BF_DISC_RTOL * bb;
    int bad = no_real | !BF_FIN(root);
    int boundary = (1 - bad) & (fabs(disc) <= BF_DISC_RTOL * bb);
    /* NO_REAL_SOLUTION (1) where no real root, else JOINT_AT_INFINITY (2) where bad, else
     * ON_BOUNDARY (3) where the discriminant vanishes, else OK (0) */
    int code = bad * (BF_JOINT_AT_INFINITY - no_real * (BF_JOINT_AT_INFINITY
                                                        - BF_NO_REAL_SOLUTION))
               + boundary * BF_ON_BOUNDARY;
    bf_update(status, code, bad);
    *failed |= bad;
    return bad ? NAN : root;
}

#endif
