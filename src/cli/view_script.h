/*
 * shadowvol view --script FILE (issue 30): key and mouse events keyed to
 * frame numbers, so that a test drives the window the same way on a
 * loaded machine as on an idle one (under --script the clock moves one
 * frame per frame drawn). One event a line, '#' starts a comment:
 *
 *   FRAME key NAME                     a key by SDL's name (M, Space, 1, .)
 *   FRAME drag left|right X0 Y0 X1 Y1  press at (X0, Y0), move to (X1, Y1), release
 *   FRAME wheel N                      the wheel N notches (positive: in)
 *   FRAME snap FILE                    the window read back from the X server, as PNG
 *   FRAME print                        the state line on stdout
 *   FRAME quit                         close the window
 *
 * key, drag and wheel go into SDL's event queue before frame FRAME is
 * drawn (so FRAME shows them); snap and print come after it is shown.
 * Frames count from 0; the events of one frame keep their order.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_SCRIPT_H
#define SV_CLI_VIEW_SCRIPT_H

#include <string>
#include <vector>

namespace svcli {

struct ScriptEvent {
    enum Kind { key, drag, wheel, snap, print, quit } kind = key;
    long frame = 0;
    std::string text; /* key: the name; snap: the file */
    int button = 0;   /* drag: 1 left, 3 right */
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int amount = 0; /* wheel */
    int line = 0;   /* in the script, for messages */
    /* Drawn after the frame is shown (snap, print, quit), not before. */
    bool after_frame() const { return kind == snap || kind == print || kind == quit; }
};

/* The events of the script at PATH, sorted by frame (stable). Throws
 * std::runtime_error naming the file and line of a malformed event, or
 * the file when it cannot be read. */
std::vector<ScriptEvent> read_view_script(const std::string &path);

/* The same, from TEXT (NAME in the messages). */
std::vector<ScriptEvent> parse_view_script(const std::string &text, const std::string &name);

} // namespace svcli

#endif
