// What the report's pointing error measures (docs/harness.md, "The
// reference of pointing_error_deg"): the truth attitude against the
// reference the flight software is commanded to track.  The title of its
// plot names it from the run's FSW mode (meta.fsw_mode) or, when an event
// commanded the FSW's mode or reference during the run, says that the
// reference in force is the one of the last such command.
export function pointingTitle(D) {
  const events = D && Array.isArray(D.events) ? D.events : [];
  const commanded = events.some((e) => /\bfsw (mode_|reference_)/.test(String((e && e.actions) || '')));
  if (commanded) return 'Pointing error (from the reference in force: the FSW commands of the events)';
  const mode = D && D.meta ? D.meta.fsw_mode : undefined;
  if (mode === 'sun_safe') return 'Pointing error: Sun-axis angle (sun_axis_B from the Sun direction)';
  if (mode === 'nadir') return 'Pointing error (principal angle from the orbit frame)';
  if (mode === 'inertial') return 'Pointing error (principal angle from the inertial reference)';
  if (mode === 'detumble') return 'Pointing error (from the reference of the mode it leaves detumbling for)';
  return 'Pointing error';
}
