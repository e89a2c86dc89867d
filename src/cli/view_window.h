/*
 * shadowvol view's window (issue 30): an SDL2 window the frames are shown
 * in, SDL's events turned into ViewControls calls, --script's events put
 * into SDL's queue, and the window read back from the X server
 * (XGetImage), so that a test compares what the server shows.
 *
 * Built with Debian's libsdl2-dev and libx11-dev (SV_LIBSDL2_FOUND); without
 * them, opening a window throws NoWindow saying so.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_WINDOW_H
#define SV_CLI_VIEW_WINDOW_H

#include <memory>
#include <stdexcept>
#include <string>

#include "images.h"
#include "view_controls.h"
#include "view_script.h"

namespace svcli {

/* No window can be opened: no display (SDL's reason), or a build without
 * SDL2. */
class NoWindow : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class ViewWindow {
public:
    ViewWindow(const std::string &title, int width, int height);
    ~ViewWindow();
    ViewWindow(const ViewWindow &) = delete;
    ViewWindow &operator=(const ViewWindow &) = delete;

    /* Shows IMAGE (the window's size) and waits until the display has it. */
    void show(const sv::render::Image &image);
    /* Every event in SDL's queue, given to CONTROLS (the window closed:
     * the Escape key). */
    void handle_events(ViewControls &controls);
    /* A key, drag or wheel event of --script into SDL's queue, as the
     * keyboard and mouse would put it. Throws std::runtime_error for a key
     * name SDL does not know. */
    void push(const ScriptEvent &s);
    /* The window's pixels as the X server holds them. Throws
     * std::runtime_error off X11 or for a visual that is not 8 bits per
     * channel. */
    sv::render::Image read_back();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace svcli

#endif
