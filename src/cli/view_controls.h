/*
 * What shadowvol view's keys and mouse change (issue 30), with no window
 * in it: the orbit camera, the picked light and where it was dragged, the
 * clock's pause and single step, and the switches (the stencil mode, the
 * stencil pass's method, the caster rule, each of frame.h's shortcuts,
 * the on-screen line and the overlays). The window (view_cli.cpp) turns
 * SDL's events into these calls; --script's events go through SDL's queue
 * to the same calls.
 *
 * Keys (SDL's key names, as --script writes them):
 *   M        stencil mode: zpass, zfail, auto
 *   T        stencil pass: bf, db, hier
 *   C        caster rule: auto, closed, general
 *   1 .. 6   shortcut 1 .. 6 of frame.h (light reach, view reach, culling
 *            where straddling, z-pass when safe, no directional dark cap,
 *            static reuse) off and on
 *   H        the on-screen line; O stencil counts; B boundary tiles (hier);
 *            V volumes as wireframe (the picked light's, else light 0's)
 *   Space    pause; . (period) one frame on, while paused
 *   L        pick the next light (none after the last): the right mouse
 *            button drags it
 *   W A S D  move the camera forward, left, back, right; Q E down, up
 *   R        the scene's camera again; P print the state line
 *   Escape   quit
 * Mouse: left button orbits the camera about its target, the wheel
 * zooms, the right button drags the picked light across the view.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_CONTROLS_H
#define SV_CLI_VIEW_CONTROLS_H

#include <string>
#include <vector>

#include "frame.h"
#include "shadowvol_scene.h"

namespace svcli {

struct ViewSwitches {
    sv::render::ModeChoice mode = sv::render::ModeChoice::automatic;
    sv::render::StencilMethod stencil = sv::render::StencilMethod::brute_force;
    sv::CasterRule caster_rule = sv::CasterRule::automatic;
    sv::render::Shortcuts shortcuts;
    bool hud = true;
    bool overlay_stencil = false, overlay_tiles = false, overlay_wireframe = false;
    bool paused = false;
};

class ViewControls {
public:
    /* HEIGHT: the frame's, in pixels (a light dragged follows the pointer). */
    ViewControls(const ViewSwitches &start, int height);

    /* A key by SDL's name ("M", "Space", "1"); false for a key that means
     * nothing here. */
    bool key(const std::string &name);
    /* The mouse moved by (DX, DY) pixels with BUTTON held (1 left, 3
     * right). */
    void drag(int button, int dx, int dy);
    /* The wheel: positive zooms in. */
    void wheel(int amount);

    /* Before each frame: the scene's own camera and lights at this time
     * (SceneSequence::set_time's); after it, SCENE has the view's camera
     * (once the user moved it) and the dragged lights. */
    void apply(sv::Scene &scene);

    const ViewSwitches &switches() const { return switches_; }
    bool quit() const { return quit_; }
    /* Frames the paused clock is to move on (the . key), taken once. */
    int take_steps();
    bool print_requested();
    int picked_light() const { return picked_; }
    /* The light the overlays show: the picked one, else 0. */
    int shown_light() const { return picked_ < 0 ? 0 : picked_; }

    /* The camera as --camera writes it, each number exact (%.17g). */
    static std::string camera_text(const sv::Camera &c);
    /* The switches as one line of words: "mode zpass stencil bf caster
     * auto shortcuts 123456 hud on overlays -". */
    std::string switches_text() const;

private:
    void orbit_from(const sv::Camera &c);
    sv::Camera orbit_camera() const;

    ViewSwitches switches_;
    int height_;
    bool quit_ = false, print_ = false;
    int steps_ = 0;
    /* The orbit camera: TARGET, DISTANCE from it, YAW and PITCH (radians)
     * of the eye about it; taken from the scene's camera at the first
     * move, the scene's again after R. */
    bool camera_moved_ = false, camera_known_ = false;
    sv::Camera base_;
    sv::Vec3d target_{};
    double distance_ = 1, yaw_ = 0, pitch_ = 0;
    /* Lights: which is picked (-1: none) and where each was dragged. */
    int picked_ = -1, lights_ = 0;
    std::vector<char> light_moved_;
    std::vector<sv::SceneLight> light_;
};

} // namespace svcli

#endif
