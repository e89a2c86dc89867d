/*
 * The options of `render` and `scene` that choose the shadow volumes and
 * their stencil operation (issue 31, seed 002): --volume, --stencil-op,
 * --extrude-to.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VOLUME_ARGS_H
#define SV_CLI_VOLUME_ARGS_H

#include <string>

#include "frame.h"

namespace svcli {

class ArgReader;

struct VolumeArgs {
    sv::render::VolumeSource volume = sv::render::VolumeSource::silhouette;
    /* "saturate", "wrap", or "" (the volume's own: saturate for the seed's
     * volumes, its effect file's IncrSat/DecrSat; wrap for the paper's). */
    std::string stencil_op;
    bool extrude_to_infinity = false;
};

/* --volume silhouette|extrude, --stencil-op saturate|wrap, --extrude-to
 * range|infinity. Consumes A's value and returns true when A is one of
 * them; false (nothing consumed) otherwise. Throws UsageError naming the
 * value. */
bool parse_volume_option(ArgReader &a, VolumeArgs &v);

/* V into OPT (volume, stencil_saturate, extrude_to_infinity). */
void apply_volume_args(const VolumeArgs &v, sv::render::RenderOptions &opt);

/* The options' lines for --help. */
const char *volume_options_help();

} // namespace svcli

#endif
