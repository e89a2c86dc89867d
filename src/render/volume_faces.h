/*
 * The drawn faces of a light's shadow volumes in window space, and what
 * they are near at a pixel: the two judges' common ground. A stencil that
 * differs from Mesa's, or from the truth, at a pixel where a volume face
 * passes within a few float ulps of the stored depth was decided by a
 * depth tie (a face through the receiver: a light grazing a triangle puts
 * its silhouette quad in the triangle's own plane); one within 1/8 pixel
 * of a face's edge, by the snapping of two rasterisers.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_VOLUME_FACES_H
#define SV_RENDER_VOLUME_FACES_H

#include <vector>

#include "frame.h"

namespace sv::render {

/* A depth tie: within 128 float ulps of the stored depth (two depth
 * interpolations in float and double of the same plane differ by a few
 * ulps; a fixed tolerance would excuse metres at a distance). */
constexpr int kDepthTieUlps = 128;
double depth_tie_width(float stored);
/* Two rasterisers that snap to 1/256 pixel put an edge at most a few
 * 1/256 of a pixel apart (their float and double transforms differ far
 * less); a difference further from every edge is a real one. */
constexpr double kEdgeDistance = 1.0 / 8;

/* The window triangles of every volume triangle drawn for light LI. */
std::vector<raster::Rasterizer::WindowTriangle> drawn_volume_triangles(const Scene &scene,
                                                                       const Frame &f, int li);

/* Pixel I against those triangles: the distance from its centre to the
 * nearest edge (pixels), and the smallest gap between a covering face's
 * depth and DEPTH (in float ulps of DEPTH); HUGE_VAL when none is near. */
struct FaceProximity {
    double nearest_edge;
    double gap_ulps;
};
FaceProximity face_proximity(const std::vector<raster::Rasterizer::WindowTriangle> &tris,
                             const Frame &f, std::size_t pixel, float depth);

} // namespace sv::render

#endif
