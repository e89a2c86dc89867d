/*
 * The SDL2 window of view_window.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_window.h"

#include <cstdlib>

#include "shadowvol_gltf.h"

#if SV_LIBSDL2_FOUND
#include <SDL2/SDL.h>
#include <SDL2/SDL_syswm.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#endif

namespace svcli {

#if SV_LIBSDL2_FOUND

struct ViewWindow::Impl {
    SDL_Window *window = nullptr;
    int width = 0, height = 0;
    ~Impl() {
        if (window) SDL_DestroyWindow(window);
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
    }
};

ViewWindow::ViewWindow(const std::string &title, int width, int height)
    : impl_(std::make_unique<Impl>()) {
    impl_->width = width, impl_->height = height;
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
        throw NoWindow(std::string("no display to open a window on (SDL: ") + SDL_GetError() + ")");
    /* With no display SDL falls back to drawing nowhere (its offscreen
     * driver): not a window anyone sees, unless asked for by name. */
    const std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
    const char *asked = std::getenv("SDL_VIDEODRIVER");
    if ((driver == "offscreen" || driver == "dummy") && !(asked && driver == asked)) {
        throw NoWindow("no display to open a window on: DISPLAY is not set, or no X server or "
                       "Wayland compositor answers there (run it under X, or xvfb-run)");
    }
    impl_->window = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_UNDEFINED,
                                     SDL_WINDOWPOS_UNDEFINED, width, height, 0);
    if (!impl_->window)
        throw NoWindow(std::string("cannot open a window (SDL: ") + SDL_GetError() + ")");
}

ViewWindow::~ViewWindow() = default;

void ViewWindow::show(const sv::render::Image &image) {
    SDL_Surface *surface = SDL_GetWindowSurface(impl_->window);
    if (!surface) throw std::runtime_error(std::string("SDL: ") + SDL_GetError());
    if (surface->w != image.width || surface->h != image.height)
        throw std::runtime_error(
            "the window is not the frame's size (a window manager resized it)");
    if (SDL_ConvertPixels(image.width, image.height, SDL_PIXELFORMAT_RGB24, image.rgb.data(),
                          image.width * 3, surface->format->format, surface->pixels,
                          surface->pitch) != 0 ||
        SDL_UpdateWindowSurface(impl_->window) != 0) {
        throw std::runtime_error(std::string("SDL: ") + SDL_GetError());
    }
}

void ViewWindow::handle_events(ViewControls &controls) {
    SDL_Event e;
    while (SDL_PollEvent(&e)) {
        if (e.type == SDL_QUIT) {
            controls.key("Escape");
        } else if (e.type == SDL_KEYDOWN) {
            controls.key(SDL_GetKeyName(e.key.keysym.sym));
        } else if (e.type == SDL_MOUSEMOTION) {
            if (e.motion.state & SDL_BUTTON_LMASK) controls.drag(1, e.motion.xrel, e.motion.yrel);
            if (e.motion.state & SDL_BUTTON_RMASK) controls.drag(3, e.motion.xrel, e.motion.yrel);
        } else if (e.type == SDL_MOUSEWHEEL) {
            controls.wheel(e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e.wheel.y : e.wheel.y);
        }
    }
}

void ViewWindow::push(const ScriptEvent &s) {
    const Uint32 id = SDL_GetWindowID(impl_->window);
    SDL_Event e;
    auto send = [&]() {
        if (SDL_PushEvent(&e) < 0) throw std::runtime_error(std::string("SDL: ") + SDL_GetError());
    };
    if (s.kind == ScriptEvent::key) {
        const SDL_Keycode k = SDL_GetKeyFromName(s.text.c_str());
        if (k == SDLK_UNKNOWN) {
            throw std::runtime_error("line " + std::to_string(s.line) + ": SDL knows no key '" +
                                     sv::printable_text(s.text) + "'");
        }
        for (Uint32 type : {(Uint32)SDL_KEYDOWN, (Uint32)SDL_KEYUP}) {
            e = SDL_Event{};
            e.type = type;
            e.key.windowID = id;
            e.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
            e.key.keysym.sym = k;
            e.key.keysym.scancode = SDL_GetScancodeFromKey(k);
            send();
        }
    } else if (s.kind == ScriptEvent::drag) {
        const Uint8 button = s.button == 1 ? SDL_BUTTON_LEFT : SDL_BUTTON_RIGHT;
        e = SDL_Event{};
        e.type = SDL_MOUSEBUTTONDOWN;
        e.button.windowID = id, e.button.button = button, e.button.state = SDL_PRESSED;
        e.button.x = s.x0, e.button.y = s.y0, e.button.clicks = 1;
        send();
        e = SDL_Event{};
        e.type = SDL_MOUSEMOTION;
        e.motion.windowID = id, e.motion.state = SDL_BUTTON(button);
        e.motion.x = s.x1, e.motion.y = s.y1;
        e.motion.xrel = s.x1 - s.x0, e.motion.yrel = s.y1 - s.y0;
        send();
        e = SDL_Event{};
        e.type = SDL_MOUSEBUTTONUP;
        e.button.windowID = id, e.button.button = button, e.button.state = SDL_RELEASED;
        e.button.x = s.x1, e.button.y = s.y1, e.button.clicks = 1;
        send();
    } else if (s.kind == ScriptEvent::wheel) {
        e = SDL_Event{};
        e.type = SDL_MOUSEWHEEL;
        e.wheel.windowID = id, e.wheel.y = s.amount, e.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
        send();
    }
}

namespace {
int mask_shift(unsigned long mask) {
    int s = 0;
    while (mask && !(mask & 1)) mask >>= 1, s++;
    return mask == 0xff ? s : -1; /* 8 bits, or not readable here */
}
} // namespace

sv::render::Image ViewWindow::read_back() {
    SDL_SysWMinfo info;
    SDL_VERSION(&info.version);
    if (!SDL_GetWindowWMInfo(impl_->window, &info) || info.subsystem != SDL_SYSWM_X11)
        throw std::runtime_error("snap reads the window back from an X server: this window is "
                                 "not on one (SDL_VIDEODRIVER=x11)");
    Display *d = info.info.x11.display;
    /* Everything SDL sent has reached the server before the read. */
    XSync(d, False);
    XImage *x = XGetImage(d, info.info.x11.window, 0, 0, (unsigned)impl_->width,
                          (unsigned)impl_->height, AllPlanes, ZPixmap);
    if (!x) throw std::runtime_error("XGetImage failed (the window off the screen?)");
    const int rs = mask_shift(x->red_mask), gs = mask_shift(x->green_mask),
              bs = mask_shift(x->blue_mask);
    if (rs < 0 || gs < 0 || bs < 0) {
        XDestroyImage(x);
        throw std::runtime_error("the X server's visual is not 8 bits per channel (Xvfb: "
                                 "-screen 0 WxHx24)");
    }
    sv::render::Image out(impl_->width, impl_->height);
    for (int py = 0; py < impl_->height; py++) {
        for (int px = 0; px < impl_->width; px++) {
            const unsigned long p = XGetPixel(x, px, py);
            uint8_t *o = out.at(px, py);
            o[0] = (uint8_t)(p >> rs), o[1] = (uint8_t)(p >> gs), o[2] = (uint8_t)(p >> bs);
        }
    }
    XDestroyImage(x);
    return out;
}

#else

struct ViewWindow::Impl {};

ViewWindow::ViewWindow(const std::string &, int, int) {
    throw NoWindow("this shadowvol was built without SDL2 (Debian's libsdl2-dev and libx11-dev; "
                   "cmake -DSV_VIEW=ON finds them)");
}
ViewWindow::~ViewWindow() = default;
void ViewWindow::show(const sv::render::Image &) {}
void ViewWindow::handle_events(ViewControls &) {}
void ViewWindow::push(const ScriptEvent &) {}
sv::render::Image ViewWindow::read_back() { return {}; }

#endif

} // namespace svcli
