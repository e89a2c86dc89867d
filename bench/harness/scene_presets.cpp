/*
 * The bench's preset scenes (scene_presets.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_presets.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "scene_options.h"
#include "sequence.h"
#include "shadowvol_scene.h"

namespace svbench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFrameSeconds = 1.0 / 8;

/* A point light circling the scene's centre at RADIUS, HEIGHT above the
 * ground, a turn every 16 s: the volumes change every frame. */
sv::Vec3d circling(const sv::Vec3d &centre, double radius, double height, int frame) {
    const double angle = 0.7 + 2 * kPi * frame * kFrameSeconds / 16;
    return {centre.x + radius * std::cos(angle), centre.y + height,
            centre.z + radius * std::sin(angle)};
}

/* An axis-aligned box, counter-clockwise seen from outside. */
sv::SceneSurface box(const std::string &name, double cx, double cz, double sx, double sy,
                     double sz) {
    const float x0 = (float)(cx - sx / 2), x1 = (float)(cx + sx / 2);
    const float z0 = (float)(cz - sz / 2), z1 = (float)(cz + sz / 2);
    const float y0 = 0, y1 = (float)sy;
    const float pos[] = {x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0,
                         x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1};
    const uint32_t idx[] = {0, 3, 2, 0, 2, 1, /* back (-z) */
                            4, 5, 6, 4, 6, 7, /* front (+z) */
                            0, 4, 7, 0, 7, 3, /* left (-x) */
                            1, 2, 6, 1, 6, 5, /* right (+x) */
                            3, 7, 6, 3, 6, 2, /* top (+y) */
                            0, 1, 5, 0, 5, 4 /* bottom (-y) */};
    sv::SceneSurface s;
    s.name = name;
    s.prepared = sv::prepare_surface(pos, 8, idx, 36);
    sv::update_bounds(s);
    return s;
}

class SimplePreset : public ScenePreset {
public:
    explicit SimplePreset(double aspect) {
        scene_.surfaces.push_back(box("box 1", -1.2, 0.0, 0.8, 1.2, 0.8));
        scene_.surfaces.push_back(box("box 2", 0.6, -0.6, 1.0, 0.6, 0.6));
        scene_.surfaces.push_back(box("box 3", 0.9, 1.0, 0.5, 1.5, 0.5));
        sv::add_ground(scene_);
        scene_.camera = sv::frame_camera(scene_, aspect);
        sv::SceneLight l;
        l.kind = sv::LightKind::point;
        l.position = circling({0, 0, 0}, 2.5, 4, 0);
        scene_.lights = {l};
        sv::default_intensity(scene_, scene_.lights[0]);
        sv::validate_scene(scene_);
    }
    const sv::Scene &at(int frame) override {
        scene_.lights[0].position = circling({0, 0, 0}, 2.5, 4, frame);
        return scene_;
    }
    std::string describe() const override {
        return "simple: 3 boxes on a ground plane, a point light circling above";
    }

private:
    sv::Scene scene_;
};

/* A file's scene in time (the demo scene, or any glTF scene), optionally
 * with its first light circling (knights). */
class SequencePreset : public ScenePreset {
public:
    SequencePreset(const sv::SequenceOptions &o, std::string what, bool circle)
        : seq_(o), what_(std::move(what)), circle_(circle) {
        sv::Vec3d lo, hi;
        seq_.scene().bounds(lo, hi, false);
        centre_ = {(lo.x + hi.x) / 2, lo.y, (lo.z + hi.z) / 2};
        radius_ = std::max(hi.x - lo.x, hi.z - lo.z) / 2;
        height_ = 2.2 * (hi.y - lo.y);
    }
    const sv::Scene &at(int frame) override {
        seq_.set_time(seq_.start() + frame * kFrameSeconds);
        if (circle_) {
            seq_.scene().lights[0].position = circling(centre_, radius_, height_, frame);
            sv::validate_scene(seq_.scene());
        }
        return seq_.scene();
    }
    std::string describe() const override { return what_; }

private:
    sv::SceneSequence seq_;
    std::string what_;
    bool circle_;
    sv::Vec3d centre_;
    double radius_ = 1, height_ = 4;
};

/* The height of FILE's surfaces at its animation's start. */
double model_height(const std::string &file) {
    sv::SequenceOptions o;
    o.file = file;
    o.lights = {sv::SceneLight{}};
    o.lights[0].position = {0, 1e3, 1e3};
    const sv::SceneSequence seq(o);
    sv::Vec3d lo, hi;
    seq.scene().bounds(lo, hi, false);
    return hi.y - lo.y;
}

std::unique_ptr<ScenePreset> knights(double aspect, const std::string &models_dir,
                                     const std::string &shared_dir) {
    namespace fs = std::filesystem;
    const std::string bundled = models_dir + "/character_1344.glb";
    /* The crowd's rows cycle through these; a model whose file is missing
     * is replaced by the bundled character. Fox is a knight's horse. */
    struct Kind {
        std::string file;
        double height;
    };
    std::vector<Kind> kinds = {{bundled, 1.8}};
    int animated = 0;
    for (const char *name :
         {"CesiumMan.glb", "RobotExpressive.glb", "RiggedFigure.glb", "Fox.glb"}) {
        const std::string f = shared_dir + "/" + name;
        if (shared_dir.empty() || !fs::exists(f)) continue;
        kinds.push_back({f, std::string(name) == "Fox.glb" ? 1.1 : 1.8});
        animated++;
    }
    sv::SequenceOptions o;
    o.file = bundled;
    o.ground = true;
    o.aspect = aspect;
    constexpr int kColumns = 6, kRows = 4;
    for (int r = 0; r < kRows; r++) {
        for (int c = 0; c < kColumns; c++) {
            if (r == 0 && c == 0) continue; /* the main file's */
            const Kind &k = kinds[(std::size_t)((r * kColumns + c) % (int)kinds.size())];
            const double scale = k.file == bundled ? 1 : k.height / model_height(k.file);
            sv::ModelPlacement m;
            m.path = k.file;
            m.placement.translation = {(c - 2.5) * 1.5, 0, -r * 1.7};
            m.placement.yaw_degrees = 25.0 * (r * kColumns + c);
            m.placement.scale = scale;
            o.adds.push_back(m);
        }
    }
    o.placement.translation = {-2.5 * 1.5, 0, 0};
    sv::SceneLight l;
    l.kind = sv::LightKind::point;
    l.position = {0, 8, 4};
    o.lights = {l};
    const std::string what =
        "knights: " + std::to_string(kColumns * kRows) + " characters (" +
        std::to_string(animated) + " animated kinds from " +
        (animated ? shared_dir : std::string("nowhere: ../shared is absent")) +
        ", the rest the bundled character) on the ground, a point light circling above";
    return std::make_unique<SequencePreset>(o, what, true);
}

} // namespace

const char *scene_preset_names() { return "simple, knights, demo"; }

std::unique_ptr<ScenePreset> make_scene_preset(const std::string &name, double aspect,
                                               const std::string &models_dir,
                                               const std::string &shared_dir,
                                               const std::string &demo_file) {
    if (name == "simple") return std::make_unique<SimplePreset>(aspect);
    if (name == "knights") return knights(aspect, models_dir, shared_dir);
    sv::SequenceOptions o;
    o.file = name == "demo" ? demo_file : name;
    o.aspect = aspect;
    return std::make_unique<SequencePreset>(o, (name == "demo" ? "demo: " : "file: ") + o.file,
                                            false);
}

} // namespace svbench
