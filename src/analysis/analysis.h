/* Private interface of src/analysis (counting, critical friction). */
#ifndef US_ANALYSIS_PRIV_H
#define US_ANALYSIS_PRIV_H

#include "core/core.h"

#endif
