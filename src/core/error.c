/* Errors: one table of names for us_Status and the message buffer helper.
 * Errors (no answer could be given) are never outcomes (stable, unstable,
 * plan found): those have their own enums in the public header. */
#include "core.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *const status_names[US_ERR_COUNT] = {
    "ok", "usage error", "i/o error", "parse error", "invalid input", "out of memory",
    "solver failure", "time limit",
};

const char *us_status_name(us_Status s) {
  if ((int)s < 0 || s >= US_ERR_COUNT) return "unknown status";
  return status_names[s];
}

us_Status us_error_set(us_Error *err, us_Status code, const char *fmt, ...) {
  if (!err) return code;
  err->code = code;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->msg, sizeof err->msg, fmt, ap);
  va_end(ap);
  return code;
}

void us_error_clear(us_Error *err) {
  if (!err) return;
  err->code = US_OK;
  err->msg[0] = '\0';
}
