/*
 * sv_webp_frames FILE.webp DIR FPS [DUMP_DIR]: decodes the animated WebP that
 * `shadowvol scene --webp` wrote (libwebpdemux's WebPAnimDecoder) and
 * compares every frame byte for byte with DIR/frame_NNN.png, the PNG
 * frames scene wrote for the same options, and each frame's time with
 * K/FPS (to the millisecond). Prints one line per frame; exit 0 when all
 * agree and the counts match, 1 otherwise, 2 on bad arguments or a file
 * that cannot be read. With DUMP_DIR it also writes each decoded frame
 * there as DUMP_DIR/webp_NNN.png, to look at.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <webp/demux.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace {

bool read_file(const char *path, std::vector<uint8_t> &bytes) {
    FILE *f = std::fopen(path, "rb");
    if (!f) return false;
    uint8_t buf[65536];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.insert(bytes.end(), buf, buf + n);
    std::fclose(f);
    return true;
}

} // namespace

int main(int argc, char **argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: sv_webp_frames FILE.webp DIR FPS [DUMP_DIR]\n");
        return 2;
    }
    const double fps = std::atof(argv[3]);
    std::vector<uint8_t> bytes;
    if (!read_file(argv[1], bytes) || !(fps > 0)) {
        std::fprintf(stderr, "sv_webp_frames: cannot read %s (or FPS %s)\n", argv[1], argv[3]);
        return 2;
    }
    WebPData data = {bytes.data(), bytes.size()};
    WebPAnimDecoderOptions options;
    if (!WebPAnimDecoderOptionsInit(&options)) return 2;
    options.color_mode = MODE_RGBA;
    options.use_threads = 0;
    WebPAnimDecoder *dec = WebPAnimDecoderNew(&data, &options);
    if (!dec) {
        std::fprintf(stderr, "sv_webp_frames: %s is not an animated WebP libwebp decodes\n",
                     argv[1]);
        return 1;
    }
    WebPAnimInfo info;
    WebPAnimDecoderGetInfo(dec, &info);
    std::printf("%s: %ux%u, %u frames, loop count %u, %zu bytes\n", argv[1], info.canvas_width,
                info.canvas_height, info.frame_count, info.loop_count, bytes.size());
    bool ok = info.loop_count == 0;
    if (!ok) std::printf("FAIL: the animation does not loop forever\n");
    unsigned k = 0;
    while (WebPAnimDecoderHasMoreFrames(dec)) {
        uint8_t *rgba = nullptr;
        int timestamp = 0; /* the frame's end, in ms */
        if (!WebPAnimDecoderGetNext(dec, &rgba, &timestamp)) {
            std::printf("FAIL: frame %u does not decode\n", k);
            ok = false;
            break;
        }
        char png[4096];
        if (argc == 5) {
            std::snprintf(png, sizeof png, "%s/webp_%03u.png", argv[4], k);
            if (!stbi_write_png(png, (int)info.canvas_width, (int)info.canvas_height, 4, rgba,
                                (int)info.canvas_width * 4)) {
                std::printf("FAIL: cannot write %s\n", png);
                ok = false;
            }
        }
        std::snprintf(png, sizeof png, "%s/frame_%03u.png", argv[2], k);
        int w = 0, h = 0, c = 0;
        uint8_t *rgb = stbi_load(png, &w, &h, &c, 3);
        if (!rgb) {
            std::printf("FAIL: frame %u: %s cannot be read\n", k, png);
            ok = false;
            k++;
            continue;
        }
        std::size_t differ = 0, not_opaque = 0;
        if (w != (int)info.canvas_width || h != (int)info.canvas_height) {
            differ = (std::size_t)-1;
        } else {
            for (std::size_t p = 0; p < (std::size_t)w * h; p++) {
                for (int ch = 0; ch < 3; ch++) differ += rgba[p * 4 + ch] != rgb[p * 3 + ch];
                not_opaque += rgba[p * 4 + 3] != 255;
            }
        }
        stbi_image_free(rgb);
        const int want_end = (int)std::lround(1000.0 * (k + 1) / fps);
        const bool same = differ == 0 && not_opaque == 0 && timestamp == want_end;
        std::printf("frame %u: ends at %d ms (%d expected), %s\n", k, timestamp, want_end,
                    differ == (std::size_t)-1 ? "a PNG of another size"
                    : same                    ? "the PNG's bytes"
                                              : "DIFFERS from the PNG");
        if (differ && differ != (std::size_t)-1)
            std::printf("  %zu bytes differ, %zu pixels not opaque\n", differ, not_opaque);
        ok &= same;
        k++;
    }
    WebPAnimDecoderDelete(dec);
    char next[4096];
    std::snprintf(next, sizeof next, "%s/frame_%03u.png", argv[2], k);
    if (FILE *f = std::fopen(next, "rb")) {
        std::fclose(f);
        std::printf("FAIL: %s has no frame in the animation\n", next);
        ok = false;
    }
    if (k != info.frame_count || k == 0) ok = false;
    std::printf("%s\n", ok ? "every frame the PNG's bytes" : "FAILED");
    return ok ? 0 : 1;
}
