/*
 * shadowvol view's command line (view_args.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_args.h"

#include "cli_args.h"

namespace svcli {

ViewArgs parse_view_args(int argc, char **argv, bool &help) {
    ViewArgs v;
    SharedSceneOptions shared;
    ArgReader a(argc, argv);
    while (a.next()) {
        if (a.is_flag("--help") || a.is_flag("-h")) {
            help = true;
            return v;
        } else if (shared.read(a, v.scene)) {
            /* scene's: FILE, --add, ..., --fps, --size */
        } else if (a.is("--script")) {
            v.script = a.value();
            if (v.script.empty()) usage_error("--script needs a file name");
        } else if (a.is_flag("--no-hud")) {
            v.hud = false;
        } else if (a.is("--frames") || a.is("--time") || a.is("--out") || a.is("--json") ||
                   a.is("--webp") || a.is("--no-check") || a.is("--no-truth")) {
            usage_error(a.opt() + " is shadowvol scene's; the view plays the scene live");
        } else {
            usage_error("unknown option '" + quoted(a.arg()) + "'");
        }
    }
    shared.finish(v.scene);
    return v;
}

} // namespace svcli
