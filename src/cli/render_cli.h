/*
 * shadowvol render (issue 12): see render_cli.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_RENDER_CLI_H
#define SV_CLI_RENDER_CLI_H

#include <cstdio>
#include <string>

namespace svbench {
class JsonWriter;
}
namespace sv::raster {
struct PassCounters;
}

namespace svcli {

/* Shared with shadowvol scene: --size WxH (throws UsageError), the output
 * folder (false when it cannot be made), a pass's counters as JSON. */
bool make_dir(const std::string &dir);
void counters_json(svbench::JsonWriter &j, const sv::raster::PassCounters &c);

int render_main(int argc, char **argv);
void render_usage(FILE *out);

} // namespace svcli

#endif
