/* fsw_linalg: the shared numerical kernels of docs/fsw/core.md, "Kernels".
 * K1 fsw_minnorm_solve: x = A^T (A A^T)^-1 b with a scale-invariant rank test.
 * K2 fsw_null_projector: [tau] = I - Q^T Q, a true projector onto null([G])
 *    for any rank of [G].
 * K4 fsw_bounded_minnorm_solve: the least-squares solution of A x = b
 *    within box bounds with the smallest norm (deterministic active set),
 *    the exact mode of thr_map (docs/fsw/thr_map.md, "NNLS mode").  (K3 is the MRP
 *    addition of fsw_attitude.h.)
 * Matrices with up to FSW_MAX_EFF columns are stored row-major in arrays of
 * FSW_MAX_EFF columns; only the leading m x n block is read. */
#ifndef FSW_LINALG_H
#define FSW_LINALG_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* K1.  A is m x n (1 <= m <= 3, 0 <= n <= FSW_MAX_EFF), b has m entries,
 * x receives n entries.  Forms M = A A^T, factors it by Cholesky in fixed
 * order and fails when a pivot is <= FSW_RANK_TOL * max_j M_jj, when n < m or
 * when max_j M_jj == 0.  It then checks the delivered residual: if
 * |b - A x| > FSW_RESID_TOL |b| it refines once (z += (A A^T)^-1 r) and
 * fails if the residual is still above (a near-singular A whose last pivot
 * is rounding noise just above the floor).  Both tests depend only on the
 * shape of A, not on its units: scaling A or b by any c != 0 never changes
 * the decision (docs/fsw-conventions.md, "Rank test").
 * Returns FSW_OK (x finite, |A x - b| <= FSW_RESID_TOL |b|); FSW_E_SINGULAR
 * (x = 0) when rank deficient; FSW_E_CAPACITY (x = 0) when m or n is out of
 * range; FSW_E_BAD_INPUT (x = 0) when A or b hold NaN or Inf, or x
 * overflows the real type (finite but huge b); FSW_E_NULL_ARG on NULL
 * pointers.
 * x[0..n-1] is always fully written (when x is not NULL). */
FswStatus fsw_minnorm_solve(fsw_real x[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                            const fsw_real b[3], int m, int n);

/* K1 in two parts, for a caller that solves with one A for several b (a
 * refinement step, or an A that changes only with a wheel mask):
 * fsw_minnorm_factor does the part of fsw_minnorm_solve that depends on A
 * alone (its checks of A, the power-of-two scaling, M and its Cholesky
 * factor with the pivot test) and fsw_minnorm_solve_factored the rest, so
 * that factor + solve_factored gives bit for bit what fsw_minnorm_solve
 * gives (fsw_minnorm_solve is written as exactly that).  `status` is what
 * the solve returns for any finite b when it is not FSW_OK (FSW_E_CAPACITY,
 * FSW_E_BAD_INPUT for non-finite or subnormal-scaled A, FSW_E_SINGULAR);
 * fsw_minnorm_solve_factored checks b first (FSW_E_BAD_INPUT), as the
 * one-call solve does.  A must be unchanged between the two calls. */
typedef struct {
  int m, n;          /* [-] the shape factored */
  FswStatus status;  /* FSW_OK, or the solve's answer for any finite b */
  fsw_real s;        /* [-] power of two scaling A (0 unless status OK) */
  fsw_real L[3][3];  /* Cholesky factor of (s A)(s A)^T (m x m, lower) */
} FswMinnormFactor;
/* Returns f->status (FSW_E_NULL_ARG and nothing written when f is NULL). */
FswStatus fsw_minnorm_factor(FswMinnormFactor *f, const fsw_real A[3][FSW_MAX_EFF], int m, int n);
/* As fsw_minnorm_solve(x, A, b, f->m, f->n) for the A that f was formed
 * from; x[0..f->n-1] is always fully written (when x is not NULL). */
FswStatus fsw_minnorm_solve_factored(fsw_real x[FSW_MAX_EFF], const FswMinnormFactor *f,
                                     const fsw_real A[3][FSW_MAX_EFF], const fsw_real b[3]);

/* K2.  G is 3 x n.  tau (n x n, rows/columns beyond n untouched) becomes
 * I - Q^T Q, Q an orthonormal basis of the row space of G by modified
 * Gram-Schmidt over the rows in index order (one re-orthogonalisation pass),
 * dropping a row whose residual is <= FSW_NULL_TOL x its original norm.
 * `avail` (n entries; may be NULL = all available) masks columns: an UNAVAILABLE column
 * is treated as absent and its row and column of tau are exactly 0.
 * `rank` (may be NULL) receives the rank found (0..3).
 * Returns FSW_OK; FSW_E_CAPACITY (tau = 0) if n is out of range;
 * FSW_E_BAD_INPUT (tau = 0) if G holds NaN or Inf. */
FswStatus fsw_null_projector(fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF],
                             const fsw_real G[3][FSW_MAX_EFF], int n,
                             const uint8_t *avail, int *rank);

/* K4.  Bounded least squares, then least norm:
 *   phase 1: minimise |A x - b| subject to lo <= x <= hi (Lawson-Hanson /
 *            BVLS style, from x = 0; the free set keeps at most m
 *            independent columns);
 *   phase 2: keeping A x at its phase-1 value, minimise |x| within the
 *            bounds (primal active set, stepping in the null space of the
 *            free columns, so A x never changes).
 * So x solves A x = b with minimum norm whenever an admissible solution
 * exists, and otherwise delivers the least-squares A x.  Deterministic: at
 * most 3 n subproblem solves (both phases together), ties to the lowest
 * index; small subproblems by LDL^T in fixed order, dropping pivots <=
 * FSW_RANK_TOL x max diag (rank-deficient A is fine).
 * A is m x n (1 <= m <= 3, 0 <= n <= FSW_MAX_EFF); b has m entries; lo and
 * hi have n entries with lo_i <= hi_i and 0 one of the two (the start x = 0
 * is a vertex of the box: [0, F_max] or [-F_max, 0]; lo_i = hi_i = 0 fixes
 * x_i = 0).  x receives n entries, always within [lo, hi].
 * `iterations` (may be NULL) receives the subproblem solves used.
 * Returns FSW_OK; FSW_E_CAPACITY (x = 0) when m or n is out of range;
 * FSW_E_BAD_INPUT (x = 0) when A, b, lo or hi hold NaN/Inf or a bound pair
 * breaks the rule above; FSW_E_NULL_ARG on NULL pointers (iterations
 * excepted).  x[0..n-1] is always fully written (when x is not NULL). */
FswStatus fsw_bounded_minnorm_solve(fsw_real x[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                                    const fsw_real b[3], int m, int n,
                                    const fsw_real lo[FSW_MAX_EFF], const fsw_real hi[FSW_MAX_EFF],
                                    int *iterations);

#ifdef __cplusplus
}
#endif

#endif /* FSW_LINALG_H */
