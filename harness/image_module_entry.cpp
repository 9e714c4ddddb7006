// The image module's one exported symbol (image_module.h): its table.
#include "image_module.h"

extern "C" __attribute__((visibility("default"))) const cavity::ImageModule* cavity_image_module() {
    static const cavity::ImageModule table{
        &cavity::oiio::writeImage,     &cavity::oiio::readImage, &cavity::oiio::importGBuffer,
        &cavity::oiio::nonFinitePixels, &cavity::oiio::compare,   &cavity::oiio::zeroNonFinite,
    };
    return &table;
}
