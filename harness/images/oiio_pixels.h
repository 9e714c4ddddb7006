// Reading pixels with OpenImageIO, inside the image module (image_module.h).
#pragma once

#include "images/namespace.h"
#include "core/image.h"

#include <OpenImageIO/imageio.h>

namespace cavity::images::oiio {

// Every channel of subimage 0 into img (already sized) as floats;
// false with the reason in in.geterror(). image_io.cpp says why not simply
// read_image(..., FLOAT, ...).
bool readFloats(OIIO::ImageInput& in, HostImage& img);

}  // namespace cavity::images::oiio
