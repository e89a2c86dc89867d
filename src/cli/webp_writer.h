/*
 * Frames as an animated WebP (issue 30): `shadowvol scene --webp FILE`,
 * a file a browser plays. Lossless (WebP's VP8L), so every frame decodes
 * to the bytes of the PNG frame scene writes beside it; the animation
 * encoder stores each frame as the rectangle that changed, so a scene
 * where one character moves stays small.
 *
 * Built with Debian's libwebp-dev (libwebpmux's WebPAnimEncoder); without
 * it (SV_LIBWEBP_FOUND 0) webp_available() is false and the writer says so.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_WEBP_WRITER_H
#define SV_CLI_WEBP_WRITER_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace svcli {

/* Whether this build has libwebp. */
bool webp_available();

class WebpAnimation {
public:
    /* WIDTH x HEIGHT frames, each shown 1/FPS s; the animation loops. */
    WebpAnimation(int width, int height, double fps);
    ~WebpAnimation();
    WebpAnimation(const WebpAnimation &) = delete;
    WebpAnimation &operator=(const WebpAnimation &) = delete;

    /* The next frame: WIDTH*HEIGHT*3 bytes, RGB, rows top to bottom.
     * Throws std::runtime_error with libwebp's reason. */
    void add(const std::vector<uint8_t> &rgb);
    /* Assembles the animation and writes it to PATH (throws
     * std::runtime_error naming PATH). */
    void write(const std::string &path);

private:
    struct Encoder;
    std::unique_ptr<Encoder> encoder_;
    int width_, height_;
    double fps_;
    int frames_ = 0;
};

} // namespace svcli

#endif
