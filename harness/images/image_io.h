// Image files through OpenImageIO: EXR for exact float data (half, ZIP
// compressed), PNG for looking at. Every write goes to a temporary file that
// is renamed into place, so a crash never leaves a half-written image.
#pragma once

#include "images/namespace.h"
#include "core/image.h"
#include "result.h"

#include <string>

namespace cavity::images {

enum class Encoding {
    Linear,        // values as they are, clamped to [0, 1] for PNG
    SignedUnit,    // [-1, 1] mapped to [0, 1] (normals) for PNG
    Preview,       // as Linear, a PNG compressed fast (zlib level 1, about 3x faster to
                   // write than the default 6, a quarter larger): report images, written
                   // on every judge and looked at once
};

// The format follows the extension: .exr (half float) or .png (8 bit; 16 bit
// when sixteenBit). PNGs get 1, 3 or 4 channels (RG images gain a zero blue).
Status writeImage(const std::string& path, const HostImage& img, Encoding enc = Encoding::Linear,
                  bool sixteenBit = false);
Result<HostImage> readImage(const std::string& path);

}  // namespace cavity::images