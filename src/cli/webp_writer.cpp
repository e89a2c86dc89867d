/*
 * The animated WebP of webp_writer.h, through libwebp's WebPAnimEncoder.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "webp_writer.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#if SV_LIBWEBP_FOUND
#include <webp/encode.h>
#include <webp/mux.h>
#endif

namespace svcli {

#if SV_LIBWEBP_FOUND

bool webp_available() { return true; }

struct WebpAnimation::Encoder {
    WebPAnimEncoder *enc = nullptr;
    WebPConfig config{};
    ~Encoder() {
        if (enc) WebPAnimEncoderDelete(enc);
    }
};

WebpAnimation::WebpAnimation(int width, int height, double fps)
    : encoder_(std::make_unique<Encoder>()), width_(width), height_(height), fps_(fps) {
    WebPAnimEncoderOptions options;
    if (!WebPAnimEncoderOptionsInit(&options) || !WebPConfigInit(&encoder_->config))
        throw std::runtime_error("libwebp: the library's version does not match its headers");
    options.anim_params.loop_count = 0; /* forever */
    /* Every frame lossless, so that it decodes to the PNG's bytes. */
    options.allow_mixed = 0;
    encoder_->config.lossless = 1;
    encoder_->config.quality = 75; /* lossless: the effort spent on the size, not the picture */
    encoder_->config.method = 4;
    encoder_->enc = WebPAnimEncoderNew(width, height, &options);
    if (!encoder_->enc) throw std::runtime_error("libwebp: cannot start an animation encoder");
}

WebpAnimation::~WebpAnimation() = default;

namespace {
/* Frame K's start in milliseconds: rounded from K/FPS, so no drift over
 * many frames. */
int timestamp_ms(int k, double fps) { return (int)std::lround(1000.0 * k / fps); }
} // namespace

void WebpAnimation::add(const std::vector<uint8_t> &rgb) {
    if (rgb.size() != (std::size_t)width_ * height_ * 3)
        throw std::runtime_error("webp: a frame of the wrong size");
    WebPPicture picture;
    if (!WebPPictureInit(&picture)) throw std::runtime_error("libwebp: WebPPictureInit failed");
    picture.use_argb = 1;
    picture.width = width_;
    picture.height = height_;
    const bool imported = WebPPictureImportRGB(&picture, rgb.data(), width_ * 3) != 0;
    const bool added = imported &&
                       WebPAnimEncoderAdd(encoder_->enc, &picture, timestamp_ms(frames_, fps_),
                                          &encoder_->config) != 0;
    WebPPictureFree(&picture);
    if (!added) {
        throw std::runtime_error(
            std::string("libwebp: frame ") + std::to_string(frames_) + ": " +
            (imported ? WebPAnimEncoderGetError(encoder_->enc) : "cannot import the pixels"));
    }
    frames_++;
}

void WebpAnimation::write(const std::string &path) {
    /* The end of the last frame: its duration. */
    if (!WebPAnimEncoderAdd(encoder_->enc, nullptr, timestamp_ms(frames_, fps_), nullptr))
        throw std::runtime_error(std::string("libwebp: ") + WebPAnimEncoderGetError(encoder_->enc));
    WebPData data;
    WebPDataInit(&data);
    if (!WebPAnimEncoderAssemble(encoder_->enc, &data))
        throw std::runtime_error(std::string("libwebp: ") + WebPAnimEncoderGetError(encoder_->enc));
    FILE *f = std::fopen(path.c_str(), "wb");
    const bool written = f && std::fwrite(data.bytes, 1, data.size, f) == data.size;
    const bool closed = f && std::fclose(f) == 0;
    WebPDataClear(&data);
    if (!written || !closed) throw std::runtime_error("--webp " + path + ": cannot write the file");
}

#else

bool webp_available() { return false; }

struct WebpAnimation::Encoder {};

WebpAnimation::WebpAnimation(int width, int height, double fps)
    : width_(width), height_(height), fps_(fps) {
    throw std::runtime_error("--webp: this shadowvol was built without libwebp (Debian's "
                             "libwebp-dev; SV_WEBP=ON)");
}
WebpAnimation::~WebpAnimation() = default;
void WebpAnimation::add(const std::vector<uint8_t> &) {}
void WebpAnimation::write(const std::string &) {}

#endif

} // namespace svcli
