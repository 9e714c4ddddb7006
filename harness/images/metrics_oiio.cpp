// The image metrics' OpenImageIO calls (metrics.cpp), in the image module.
#include "images/namespace.h"
#include "images/image_module.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace cavity::images::oiio {

namespace {

namespace IBA = OIIO::ImageBufAlgo;

// OIIO reads the HostImage's floats in place; nothing here writes through it.
OIIO::ImageBuf wrap(const HostImage& img) {
    OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT);
    return OIIO::ImageBuf(spec, const_cast<float*>(img.pixels.data()));
}

}  // namespace

// fixNonFinite in its counting-only mode counts pixels (not values) holding
// any NaN or Inf, which is what the gate reports.
long long nonFinitePixels(const HostImage& img) {
    int n = 0;
    OIIO::ImageBuf unused;
    IBA::fixNonFinite(unused, wrap(img), IBA::NONFINITE_NONE, &n);
    return n;
}

OiioCompareSums compare(const HostImage& a, const HostImage& b, double threshold) {
    const auto cr = IBA::compare(wrap(a), wrap(b), float(threshold), float(threshold));
    return {cr.maxerror, cr.meanerror, cr.rms_error, (long long)cr.nfail, cr.maxx, cr.maxy};
}

void zeroNonFinite(HostImage& img) {
    OIIO::ImageBuf buf = wrap(img);
    IBA::fixNonFinite(buf, buf, IBA::NONFINITE_BLACK);
}

}  // namespace cavity::images::oiio
