#include "core/camera.h"

#include <cmath>
#include <cstring>

namespace cavity::core {

namespace {

// Column-major 4x4 multiply helpers for the inverse check-free construction.
void setPerspective(float* m, float* inv, float tanX, float tanY, float n, float f) {
    // Maps view (x, y, z, 1), camera looking down -Z, to clip with
    //   x_ndc = x / (-z tanX), y_ndc = -y / (-z tanY)   (+Y up is row 0, the top)
    //   z_ndc = f (z + n) / ((n - f) z)  ... i.e. 0 at z = -n, 1 at z = -f.
    std::memset(m, 0, 16 * sizeof(float));
    std::memset(inv, 0, 16 * sizeof(float));
    const float a = f / (n - f), b = n * f / (n - f);
    m[0] = 1.0f / tanX;
    m[5] = -1.0f / tanY;
    m[10] = a;
    m[11] = -1.0f;
    m[14] = b;
    // Inverse: x = xc tanX, y = -yc tanY, z = -wc, w = (zc - a(-wc)) / b ...
    inv[0] = tanX;
    inv[5] = -tanY;
    inv[11] = 1.0f / b;
    inv[14] = -1.0f;
    inv[15] = a / b;
}

}  // namespace

kernels::FrameUniforms frameUniforms(int width, int height, int srcWidth, int srcHeight) {
    kernels::FrameUniforms u{};
    const float tanY = std::tan(0.5f * kFovYDegrees * 3.14159265358979f / 180.0f);
    const float tanX = tanY * float(srcWidth) / float(srcHeight);
    setPerspective(u.proj, u.invProj, tanX, tanY, kNear, kFar);
    u.camera[0] = tanX;
    u.camera[1] = tanY;
    u.camera[2] = kNear;
    u.camera[3] = kFar;
    u.size[0] = width;
    u.size[1] = height;
    u.srcSize[0] = srcWidth;
    u.srcSize[1] = srcHeight;
    u.invSize[0] = 1.0f / float(width);
    u.invSize[1] = 1.0f / float(height);
    return u;
}

}  // namespace cavity::core