/*
 * shadowvol view's parts with no window (issue 30): the --script reader
 * (events sorted by frame, each malformed line refused naming the file and
 * line), the controls (each key changes its own switch and nothing else;
 * the camera and lights stay the scene's until the mouse moves them), and
 * the font (glyph pixels inside the line's band only).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "view_controls.h"
#include "view_font.h"
#include "view_script.h"

namespace {

using namespace svcli;

TEST(ViewScript, EventsSortedByFrameInTheirOrder) {
    const std::vector<ScriptEvent> e = parse_view_script("# a comment\n"
                                                         "3 snap a.png\n"
                                                         "1 key M   # switch the mode\n"
                                                         "\n"
                                                         "3 print\n"
                                                         "1 drag right 1 2 3 4\n"
                                                         "2 wheel -2\n"
                                                         "4 quit\n",
                                                         "s");
    ASSERT_EQ(e.size(), 6u);
    EXPECT_EQ(e[0].kind, ScriptEvent::key);
    EXPECT_EQ(e[0].text, "M");
    EXPECT_EQ(e[0].line, 3);
    EXPECT_EQ(e[1].kind, ScriptEvent::drag);
    EXPECT_EQ(e[1].button, 3);
    EXPECT_EQ(e[1].y1, 4);
    EXPECT_EQ(e[2].amount, -2);
    EXPECT_EQ(e[3].kind, ScriptEvent::snap);
    EXPECT_EQ(e[3].text, "a.png");
    EXPECT_EQ(e[4].kind, ScriptEvent::print);
    EXPECT_TRUE(e[5].after_frame());
    EXPECT_FALSE(e[0].after_frame());
}

TEST(ViewScript, MalformedLinesAreRefusedByFileAndLine) {
    const char *bad[] = {"x key M",
                         "-1 key M",
                         "1",
                         "1 key",
                         "1 key M N",
                         "1 jump",
                         "1 drag up 1 2 3 4",
                         "1 drag left 1 2 3",
                         "1 wheel 1.5",
                         "1 print now",
                         "99999999999 quit",
                         "1 snap"};
    for (const char *line : bad) {
        try {
            parse_view_script(std::string("0 print\n") + line + "\n", "my.script");
            ADD_FAILURE() << "accepted: " << line;
        } catch (const std::runtime_error &e) {
            EXPECT_EQ(std::string(e.what()).rfind("my.script:2: ", 0), 0u) << e.what();
        }
    }
    EXPECT_THROW(read_view_script("/nonexistent/dir/view.script"), std::runtime_error);
}

/* The words of the switches line that differ between A and B, "word value". */
std::vector<std::string> changed(const std::string &a, const std::string &b) {
    std::istringstream sa(a), sb(b);
    std::vector<std::string> out;
    std::string ka, va, kb, vb;
    while (sa >> ka >> va && sb >> kb >> vb) {
        EXPECT_EQ(ka, kb);
        if (va != vb) out.push_back(kb + " " + vb);
    }
    return out;
}

sv::Scene two_lights() {
    sv::Scene s;
    s.camera.eye = {0, 2, 5};
    s.camera.target = {0, 1, 0};
    sv::SceneLight p;
    p.position = {1, 3, 1};
    sv::SceneLight d;
    d.kind = sv::LightKind::directional;
    d.direction = {0, -1, 0};
    s.lights = {p, d};
    return s;
}

TEST(ViewControls, EachKeyChangesItsSwitchAndNothingElse) {
    struct Step {
        const char *key, *change;
    } steps[] = {{"M", "mode zpass"},
                 {"M", "mode zfail"},
                 {"M", "mode auto"},
                 {"T", "stencil db"},
                 {"T", "stencil hier"},
                 {"T", "stencil auto"},
                 {"T", "stencil bf"},
                 {"C", "caster closed"},
                 {"C", "caster general"},
                 {"C", "caster auto"},
                 {"1", "shortcuts -23456"},
                 {"1", "shortcuts 123456"},
                 {"4", "shortcuts 123-56"},
                 {"6", "shortcuts 123-5-"},
                 {"H", "hud off"},
                 {"O", "overlays stencil"},
                 {"B", "overlays stencil,tiles"},
                 {"V", "overlays stencil,tiles,wireframe"},
                 {"Space", "paused yes"},
                 {"L", "light 0"},
                 {"L", "light 1"},
                 {"L", "light -"}};
    ViewControls c(ViewSwitches{}, 128);
    sv::Scene scene = two_lights();
    c.apply(scene); /* the lights are known: L can pick */
    for (const Step &s : steps) {
        const std::string before = c.switches_text();
        EXPECT_TRUE(c.key(s.key)) << s.key;
        EXPECT_EQ(changed(before, c.switches_text()), std::vector<std::string>{s.change})
            << "key " << s.key << ": " << before << " -> " << c.switches_text();
    }
    const std::string before = c.switches_text();
    EXPECT_FALSE(c.key("F12"));
    EXPECT_TRUE(c.key("P"));
    EXPECT_TRUE(c.print_requested());
    EXPECT_FALSE(c.print_requested()) << "taken once";
    EXPECT_EQ(c.switches_text(), before);
    EXPECT_FALSE(c.quit());
    c.key("Escape");
    EXPECT_TRUE(c.quit());
}

TEST(ViewControls, TheSceneCameraAndLightsUntilTheMouseMovesThem) {
    ViewControls c(ViewSwitches{}, 128);
    sv::Scene scene = two_lights();
    const sv::Scene original = scene;
    c.apply(scene);
    EXPECT_EQ(ViewControls::camera_text(scene.camera), ViewControls::camera_text(original.camera));
    c.drag(3, 10, 0); /* no light picked: nothing */
    c.apply(scene);
    EXPECT_EQ(scene.lights[0].position.x, original.lights[0].position.x);

    /* Orbit: the eye moves about the target, at the same distance. */
    c.drag(1, 30, -10);
    sv::Scene orbited = original;
    c.apply(orbited);
    const sv::Camera &o = orbited.camera;
    EXPECT_NE(ViewControls::camera_text(o), ViewControls::camera_text(original.camera));
    EXPECT_EQ(o.target.y, original.camera.target.y);
    auto dist = [](const sv::Camera &k) {
        return std::hypot(k.eye.x - k.target.x, k.eye.y - k.target.y, k.eye.z - k.target.z);
    };
    EXPECT_NEAR(dist(o), dist(original.camera), 1e-12);
    c.wheel(3);
    sv::Scene zoomed = original;
    c.apply(zoomed);
    EXPECT_NEAR(dist(zoomed.camera), dist(original.camera) * std::pow(0.9, 3), 1e-12);
    c.key("R");
    sv::Scene reset = original;
    c.apply(reset);
    EXPECT_EQ(ViewControls::camera_text(reset.camera), ViewControls::camera_text(original.camera));

    /* A picked light is dragged; the other stays the file's. */
    c.key("L");
    c.drag(3, 16, 0);
    sv::Scene dragged = original;
    c.apply(dragged);
    EXPECT_NE(dragged.lights[0].position.x, original.lights[0].position.x);
    EXPECT_EQ(dragged.lights[0].position.y, original.lights[0].position.y) << "a sideways drag";
    EXPECT_EQ(dragged.lights[1].direction.y, original.lights[1].direction.y);
    /* It stays where it was put in later frames (the file's pose again). */
    sv::Scene later = original;
    c.apply(later);
    EXPECT_EQ(later.lights[0].position.x, dragged.lights[0].position.x);
    /* A directional light turns, its direction still of unit length. */
    c.key("L");
    c.drag(3, 20, 15);
    c.apply(later);
    const sv::Vec3d &d = later.lights[1].direction;
    EXPECT_NE(d.y, -1.0);
    EXPECT_NEAR(d.x * d.x + d.y * d.y + d.z * d.z, 1.0, 1e-12);
}

TEST(ViewControls, PeriodStepsOnlyWhilePaused) {
    ViewControls c(ViewSwitches{}, 128);
    c.key(".");
    EXPECT_EQ(c.take_steps(), 0);
    c.key("Space");
    c.key(".");
    c.key(".");
    EXPECT_EQ(c.take_steps(), 2);
    EXPECT_EQ(c.take_steps(), 0) << "taken once";
}

TEST(ViewFont, GlyphsInsideTheBandOnly) {
    sv::render::Image img(64, 20);
    for (auto &b : img.rgb) b = 90;
    draw_text(img, 2, 3, "A1~", 1, 255, 255, 255);
    const int w = text_width("A1~", 1);
    EXPECT_EQ(w, 17);
    int lit = 0;
    for (int y = 0; y < img.height; y++) {
        for (int x = 0; x < img.width; x++) {
            const uint8_t v = img.at(x, y)[0];
            const bool inside = x >= 1 && x < 2 + w + 1 && y >= 2 && y < 3 + 8;
            if (v == 255) lit++;
            if (inside) {
                EXPECT_TRUE(v == 255 || v == 30) << x << "," << y;
            } else {
                EXPECT_EQ(v, 90) << x << "," << y;
            }
        }
    }
    /* A: 18 pixels, 1: 10, the unknown ~ a box of 20. */
    EXPECT_EQ(lit, 18 + 10 + 20);
    draw_text(img, 60, 18, "clipped", 2, 1, 2, 3); /* off the edge: no crash */
}

} // namespace
