// fc-scene: POV-Ray's flags of a ray as frame coherence keeps them, and made again, so that
// a search, a shadow test or a surface hit kept with a sample can be run again on a ray with the same flags
// (tie_searches.h, shadow_tests.h, surface_hits.h).
#ifndef POVRAYFC_SCENE_RAY_FLAGS_H
#define POVRAYFC_SCENE_RAY_FLAGS_H

#include <cstdint>

// POV-Ray's Ray (frame.h is always the first POV-Ray header included)
#include "backend/frame.h"

namespace povrayfc
{
namespace scene
{

// The ray's flags a search or an object's intersection may read. Not the hollow flag: it
// follows the ray's interiors, which no search reads (nor are they kept).
enum : std::uint16_t
{
	kPrimary = 1, kReflection = 2, kRefraction = 4, kSubsurface = 8, kShadowTest = 16,
	kPhoton = 32, kRadiosity = 64, kMonochromatic = 128, kPretrace = 256
};

inline std::uint16_t RayFlagBits(const pov::Ray& ray)
{
	return std::uint16_t((ray.IsPrimaryRay() ? kPrimary : 0) | (ray.IsReflectionRay() ? kReflection : 0) |
	                     (ray.IsRefractionRay() ? kRefraction : 0) | (ray.IsSubsurfaceRay() ? kSubsurface : 0) |
	                     (ray.IsShadowTestRay() ? kShadowTest : 0) | (ray.IsPhotonRay() ? kPhoton : 0) |
	                     (ray.IsRadiosityRay() ? kRadiosity : 0) | (ray.IsMonochromaticRay() ? kMonochromatic : 0) |
	                     (ray.IsPretraceRay() ? kPretrace : 0));
}

// Gives `ray` the flags `bits` through Ray's own setters; false when they cannot make them.
inline bool SetRayFlagBits(pov::Ray& ray, std::uint16_t bits)
{
	const bool shadowTest = (bits & kShadowTest) != 0, photon = (bits & kPhoton) != 0;
	const bool radiosity = (bits & kRadiosity) != 0, monochromatic = (bits & kMonochromatic) != 0;
	const bool pretrace = (bits & kPretrace) != 0;
	if((bits & (kReflection | kRefraction)) == (kReflection | kRefraction))
	{
		// A ray reflected inside a refracted one carries both (Ray::SetFlags from a parent).
		const pov::Ray parent(pov::Ray::RefractionRay, shadowTest, photon, radiosity, monochromatic, pretrace);
		ray.SetFlags(pov::Ray::ReflectionRay, parent);
	}
	else
	{
		const pov::Ray::RayType type = (bits & kPrimary) ? pov::Ray::PrimaryRay : (bits & kReflection) ? pov::Ray::ReflectionRay :
		                               (bits & kRefraction) ? pov::Ray::RefractionRay : (bits & kSubsurface) ? pov::Ray::SubsurfaceRay :
		                               pov::Ray::OtherRay;
		ray.SetFlags(type, shadowTest, photon, radiosity, monochromatic, pretrace);
	}
	return RayFlagBits(ray) == bits;
}

}  // namespace scene
}  // namespace povrayfc

#endif
