/* fsw_config: build-time configuration of the Kestrel flight library.
 * Real type, capacities, numerical tolerances and the math-function names
 * that go with the real type.  Every value can be overridden with -D; the
 * CMake build exports the overrides to consumers so the library and its
 * users always agree on structure layouts. */
#ifndef FSW_CONFIG_H
#define FSW_CONFIG_H

#include <math.h>

/* ---- Real type -----------------------------------------------------------
 * FSW_USE_FLOAT = 0 (default): fsw_real is double.
 * FSW_USE_FLOAT = 1: fsw_real is float (for FPUs without double support).
 * Never mix the two in one build: the value is part of the ABI. */
#ifndef FSW_USE_FLOAT
#define FSW_USE_FLOAT 0
#endif

#if FSW_USE_FLOAT
typedef float fsw_real;
#define FSW_R(lit) (lit##f) /* typed literal: FSW_R(0.5) is 0.5f */
#define FSW_SQRT sqrtf
#define FSW_FABS fabsf
#define FSW_SIN sinf
#define FSW_COS cosf
#define FSW_TAN tanf
#define FSW_ACOS acosf
#define FSW_ATAN atanf
#define FSW_ATAN2 atan2f
#define FSW_FLOOR floorf
#define FSW_RINT rintf
#define FSW_FREXP frexpf
#define FSW_LDEXP ldexpf
#define FSW_REAL_EPS FSW_R(1.1920929e-07)
/* Pivot tolerance of the minimum-norm solve (docs/fsw/core.md, "Kernels" K1),
 * relative to the largest diagonal of A A^T.  1e-12 in double; in single
 * precision the Schur complement of an exactly singular M carries round-off
 * of order 1e-7, so the threshold is raised to 1e-5. */
#define FSW_RANK_TOL FSW_R(1e-5)
/* Row-drop tolerance of the null-space projector (K2), relative to the
 * original row norm: 1e-9 in double, 1e-4 in single precision. */
#define FSW_NULL_TOL FSW_R(1e-4)
/* Delivered-residual tolerance of the minimum-norm solve (K1), relative to
 * |b|: about sqrt(FSW_RANK_TOL) (docs/fsw-conventions.md, "Rank test"). */
#define FSW_RESID_TOL FSW_R(3e-3)
#else
typedef double fsw_real;
#define FSW_R(lit) (lit)
#define FSW_SQRT sqrt
#define FSW_FABS fabs
#define FSW_SIN sin
#define FSW_COS cos
#define FSW_TAN tan
#define FSW_ACOS acos
#define FSW_ATAN atan
#define FSW_ATAN2 atan2
#define FSW_FLOOR floor
#define FSW_RINT rint
#define FSW_FREXP frexp
#define FSW_LDEXP ldexp
#define FSW_REAL_EPS 2.220446049250313e-16
#define FSW_RANK_TOL 1e-12
#define FSW_NULL_TOL 1e-9
#define FSW_RESID_TOL 1e-6
#endif

/* ---- Capacities -----------------------------------------------------------
 * Fixed array sizes of every FSW struct, all of them here (a build sets any
 * of them with -D).  Memory cost grows linearly (per
 * wheel/thruster arrays) and quadratically (the wheel null-space projector,
 * FSW_MAX_EFF^2 reals = 10.4 KiB at 36 in double). */
#ifndef FSW_MAX_RW
#define FSW_MAX_RW 36 /* [-] reaction wheels, allowed 3..64 */
#endif
#ifndef FSW_MAX_THR
#define FSW_MAX_THR 36 /* [-] thrusters, allowed 1..64 (Basilisk MAX_EFF_CNT) */
#endif

#ifndef FSW_MAX_CSS
#define FSW_MAX_CSS 32 /* [-] coarse sun sensors per estimator, allowed 3..64 (5 reals + 1 byte each) */
#endif
#ifndef FSW_MAX_MTQ
#define FSW_MAX_MTQ 8 /* [-] magnetorquer rods, allowed 1..64 */
#endif
#ifndef FSW_LINK_NODE_MAX_REPLIES
#define FSW_LINK_NODE_MAX_REPLIES 3 /* [-] packets one link-node receive may answer with (fsw_link_node.h) */
#endif

#if FSW_MAX_RW < 3 || FSW_MAX_RW > 64
#error "FSW_MAX_RW must be in 3..64"
#endif
#if FSW_MAX_THR < 1 || FSW_MAX_THR > 64
#error "FSW_MAX_THR must be in 1..64"
#endif
#if FSW_MAX_MTQ < 1 || FSW_MAX_MTQ > 64
#error "FSW_MAX_MTQ must be in 1..64"
#endif
#if FSW_MAX_CSS < 3 || FSW_MAX_CSS > 64
#error "FSW_MAX_CSS must be in 3..64"
#endif

/* Column capacity of the shared kernels (K1, K2): the larger of the two. */
#if FSW_MAX_RW > FSW_MAX_THR
#define FSW_MAX_EFF FSW_MAX_RW
#else
#define FSW_MAX_EFF FSW_MAX_THR
#endif

/* ---- Stages of fsw_acs ------------------------------------------------------
 * FSW_CFG_<stage> = 1 (default): fsw_acs can run the stage.  0: fsw_acs is
 * built without it, so a program that links fsw_acs does not link the
 * stage's module either (docs/flight-footprint.md).  fsw_acs_check (and so
 * fsw_acs_init) rejects a configuration whose flag asks for a stage left
 * out with FSW_E_UNSUPPORTED and the flag's name in *bad_field; init then
 * leaves the state not ready, so every cycle gives the safe output.  The
 * modules themselves, the structure layouts and the configuration image
 * are the same in every selection.
 *   FSW_CFG_MTQ           has_mtq: mtq_map, bdot (DETUMBLE), mtq_desat
 *   FSW_CFG_MTQ_DESAT     use_mtq_desat: the MAGNETORQUERS policy
 *   FSW_CFG_ORBIT         has_orbit: guid_orbit (NADIR)
 *   FSW_CFG_THR_MOM       use_thr_mom: the THRUSTERS policy (thr_momentum)
 *   FSW_CFG_RW_BIAS       use_bias: rw_bias
 *   FSW_CFG_RW_NULL       use_null: rw_null
 *   FSW_CFG_RW_VOLT       use_volt: rw_volt
 *   FSW_CFG_SPEED_FILTER  use_speed_filter: rw_speed_filter
 *   FSW_CFG_LPF           use_lpf: trq_lpf
 *   FSW_CFG_PULSE_SCHMITT pulser = FSW_ACS_PULSE_SCHMITT: thr_pulse_schmitt
 *   FSW_CFG_THR_NNLS      thr_map.mode = FSW_THR_MAP_NNLS: thr_map's bounded
 *                         solve, fsw_bounded_minnorm_solve, which thr_map
 *                         itself then refuses with FSW_E_UNSUPPORTED (thr_map.h) */
#ifndef FSW_CFG_MTQ
#define FSW_CFG_MTQ 1
#endif
#ifndef FSW_CFG_MTQ_DESAT
#define FSW_CFG_MTQ_DESAT FSW_CFG_MTQ
#endif
#ifndef FSW_CFG_ORBIT
#define FSW_CFG_ORBIT 1
#endif
#ifndef FSW_CFG_THR_MOM
#define FSW_CFG_THR_MOM 1
#endif
#ifndef FSW_CFG_RW_BIAS
#define FSW_CFG_RW_BIAS 1
#endif
#ifndef FSW_CFG_RW_NULL
#define FSW_CFG_RW_NULL 1
#endif
#ifndef FSW_CFG_RW_VOLT
#define FSW_CFG_RW_VOLT 1
#endif
#ifndef FSW_CFG_SPEED_FILTER
#define FSW_CFG_SPEED_FILTER 1
#endif
#ifndef FSW_CFG_LPF
#define FSW_CFG_LPF 1
#endif
#ifndef FSW_CFG_PULSE_SCHMITT
#define FSW_CFG_PULSE_SCHMITT 1
#endif
#ifndef FSW_CFG_THR_NNLS
#define FSW_CFG_THR_NNLS 1
#endif
#if FSW_CFG_MTQ_DESAT && !FSW_CFG_MTQ
#error "FSW_CFG_MTQ_DESAT needs FSW_CFG_MTQ"
#endif
#if FSW_CFG_RW_BIAS && !FSW_CFG_RW_NULL
#error "FSW_CFG_RW_BIAS needs FSW_CFG_RW_NULL"
#endif

/* Availability flags (docs/fsw-conventions.md, "Frames, units and signs"): zero-initialised = available. */
#define FSW_AVAILABLE 0
#define FSW_UNAVAILABLE 1

/* C99 has no way to pass a non-const 2-D array to a const 2-D parameter
 * without a diagnostic under -pedantic.  These add the qualifier explicitly
 * (adding const is always safe). */
#define FSW_CM33(a) ((const fsw_real(*)[3])(a))
#define FSW_CM3N(a) ((const fsw_real(*)[FSW_MAX_EFF])(a))

#endif /* FSW_CONFIG_H */
