/*
 * The scaling run as a picture: `shadowvol bench --scaling --plot FILE`.
 *
 * One panel per routine, the volume first: ticks per element (the median)
 * against triangles on a log axis, a polyline per variant through the
 * generated meshes (one family of shapes, differing in size alone) and
 * hollow markers of the same colour for the real characters (other shapes
 * and vertex orders: points, not a line). Dashed vertical lines mark the
 * L1D, L2 and L3 at the triangle count whose working set fills them, the
 * working set being the routine's bytes per triangle at the paper's ratios
 * (working_set.h), stated in the panel's caption.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCALING_PLOT_H
#define SV_BENCH_SCALING_PLOT_H

#include <string>

#include "scaling.h"

namespace svbench {

/* The SVG document. */
std::string scaling_svg(const ScalingRun &run);

} // namespace svbench

#endif
