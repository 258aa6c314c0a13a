/* rw_sat: reaction-wheel torque saturation (docs/fsw/rw_sat.md).
 *   FSW_RW_SAT_SCALE (default): s = max_i |u_i|/u_max_i over the available
 *       wheels; if s > 1 every torque is divided by s (the torque direction
 *       is kept, as in thr_map's saturation scaling).
 *   FSW_RW_SAT_CLIP: u_i = clamp(u_i, -u_max_i, u_max_i) (what Basilisk's
 *       plant does; changes the torque direction).
 * Unavailable wheels get exactly 0.  Stateless apart from health.
 * Units: SI.  Safe output (bad input, not initialised): u = 0. */
#ifndef FSW_RW_SAT_H
#define FSW_RW_SAT_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { FSW_RW_SAT_SCALE = 0, FSW_RW_SAT_CLIP = 1 } FswRwSatMode;

typedef struct {
  int num_rw;                 /* [-]   1..FSW_MAX_RW                 */
  fsw_real u_max[FSW_MAX_RW]; /* [N*m] (num_rw) torque limits, > 0   */
  int mode;                   /* [-]   FswRwSatMode                  */
} FswRwSatConfig;

typedef struct {
  int ready;
  FswHealth health;
} FswRwSatState;

typedef struct {
  fsw_real u_s[FSW_MAX_RW]; /* [N*m] (num_rw) commanded torques          */
  uint8_t avail[FSW_MAX_RW]; /* [-]  (num_rw) 0 available, 1 unavailable */
} FswRwSatIn;

typedef struct {
  fsw_real u_s[FSW_MAX_RW]; /* [N*m] (num_rw) limited torques; 0 beyond num_rw */
} FswRwSatOut;

FswStatus fsw_rw_sat_check(const FswRwSatConfig *cfg);
FswStatus fsw_rw_sat_init(FswRwSatState *st, const FswRwSatConfig *cfg);
void fsw_rw_sat_reset(FswRwSatState *st);
/* FSW_OK; FSW_W_SAT (a limit changed the output); FSW_E_BAD_INPUT (u = 0)
 * for non-finite torques or a mask entry other than 0/1; FSW_E_NOT_INIT. */
FswStatus fsw_rw_sat_update(FswRwSatState *st, const FswRwSatConfig *cfg, const FswRwSatIn *in,
                            FswRwSatOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_SAT_H */
