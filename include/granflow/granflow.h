// SPDX-License-Identifier: MIT
// granflow: the whole public API.
#ifndef GRANFLOW_H
#define GRANFLOW_H
#include "granflow/bench.h"
#include "granflow/config.h"
#include "granflow/core.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "granflow/draw.h"
#include "granflow/exit.h"
#include "granflow/lga.h"
#include "granflow/packing.h"
#include "granflow/particles.h"
#include "granflow/render.h"
#include "granflow/report.h"
#include "granflow/run.h"
#include "granflow/sim.h"
#endif
