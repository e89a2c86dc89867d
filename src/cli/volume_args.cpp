/*
 * --volume, --stencil-op, --extrude-to (volume_args.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "volume_args.h"

#include "cli_args.h"
#include "extruded_volumes.h"

namespace svcli {

bool parse_volume_option(ArgReader &a, VolumeArgs &v) {
    if (a.is("--volume")) {
        const std::string s = a.value();
        if (!sv::render::volume_source_by_name(s, v.volume))
            usage_error("--volume needs silhouette or extrude, not '" + quoted(s) + "'");
    } else if (a.is("--stencil-op")) {
        const std::string s = a.value();
        if (s != "saturate" && s != "wrap")
            usage_error("--stencil-op needs saturate or wrap, not '" + quoted(s) + "'");
        v.stencil_op = s;
    } else if (a.is("--extrude-to")) {
        const std::string s = a.value();
        if (s != "range" && s != "infinity")
            usage_error("--extrude-to needs range or infinity, not '" + quoted(s) + "'");
        v.extrude_to_infinity = s == "infinity";
    } else {
        return false;
    }
    return true;
}

void apply_volume_args(const VolumeArgs &v, sv::render::RenderOptions &opt) {
    opt.volume = v.volume;
    opt.stencil_saturate = v.stencil_op.empty() ? v.volume == sv::render::VolumeSource::extrude
                                                : v.stencil_op == "saturate";
    opt.extrude_to_infinity = v.extrude_to_infinity;
}

const char *volume_options_help() {
    return "  --volume V        the shadow volumes: silhouette (the paper's silhouette quads\n"
           "                    and caps; default) or extrude (seed 002: every surface's\n"
           "                    shadow mesh, a degenerate quad per edge, through its vertex\n"
           "                    program on the CPU, drawn whole in z-fail; docs/EXTRUSION.md)\n"
           "  --stencil-op OP   saturate (the seed's IncrSat/DecrSat; the default with\n"
           "                    --volume extrude) or wrap (additions modulo 256; the default\n"
           "                    with silhouette)\n"
           "  --extrude-to T    --volume extrude: range (the seed's clamp0(range - |vLP|) for\n"
           "                    a light with a range; default) or infinity (w = 0, as the\n"
           "                    paper's)\n";
}

} // namespace svcli
