// FanApexes: the points a render block's segments are bundled by.
#ifndef POVRAYFC_FAN_APEXES_H
#define POVRAYFC_FAN_APEXES_H

#include <cmath>
#include <cstdint>

namespace povrayfc {

// The points a render block's segments are bundled by (see segment_fans.h): the camera
// position its camera rays start from, and the light positions its shadow rays aim at.
// Filled as rays are recorded; index = the bundle's fan number.
//
// Each light has two bundles: the shadow rays from the surfaces the block's camera rays
// hit, and the "deep" ones, from where its reflected and refracted rays hit. The first
// come from neighbouring points and make a narrow cone; the second come from anywhere a
// curved mirror looks, and their cone spans tens of degrees. In one bundle, that wide
// cone reached every change near the block and every shadow ray of it was tested: on
// Newton's cradle nine in ten of those tests found nothing.
struct FanApexes {
    static constexpr int kMax = 16;  // the camera and seven lights, each twice
    double point[kMax][3];
    bool isOrigin[kMax];
    bool isDeep[kMax];
    int count = 0;

    void Clear() { count = 0; }
    // The fan of a segment starting at `origin`: the block's first recorded origin (its
    // first camera ray's) is fan 0; other origins are loose.
    std::uint8_t OriginFan(const double origin[3]) {
        if (count == 0) {
            Set(0, origin, true);
            count = 1;
        }
        return (isOrigin[0] && Same(point[0], origin)) ? 0 : kLoose;
    }
    // The fan of a shadow segment aimed at `aim` (the light point it tests, as origin +
    // depth * direction: the same light gives points a few ulps apart, hence the
    // tolerance; how far each segment really strays from its apex is measured when the
    // cones are built).
    // `deep`: the ray leaves a point a reflected or refracted ray hit.
    std::uint8_t AimFan(const double aim[3], bool deep = false) {
        for (int i = 0; i < count; ++i)
            if (!isOrigin[i] && isDeep[i] == deep && Near(point[i], aim)) return std::uint8_t(i);
        if (count == kMax) return kLoose;
        Set(count, aim, false);
        isDeep[count] = deep;
        return std::uint8_t(count++);
    }

    static constexpr std::uint8_t kLoose = 0xff;

  private:
    static bool Same(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
    static bool Near(const double *a, const double *b) {
        const double tolerance = 1e-6 * (1.0 + std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]));
        return std::fabs(a[0] - b[0]) <= tolerance && std::fabs(a[1] - b[1]) <= tolerance &&
               std::fabs(a[2] - b[2]) <= tolerance;
    }
    void Set(int i, const double *p, bool origin) {
        point[i][0] = p[0];
        point[i][1] = p[1];
        point[i][2] = p[2];
        isOrigin[i] = origin;
        isDeep[i] = false;
    }
};

}  // namespace povrayfc

#endif
