// The image module's one exported symbol (image_module.h): its table.
#include "images/namespace.h"
#include "images/image_module.h"

extern "C" __attribute__((visibility("default"))) const cavity::images::ImageModule* cavity_image_module() {
    static const cavity::images::ImageModule table{
        &cavity::images::oiio::writeImage,
        &cavity::images::oiio::readImage,
        &cavity::images::oiio::importGBuffer,
    };
    return &table;
}
